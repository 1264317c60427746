// The per-thread generator METIS draws from (src/physics/metis_random.cpp), and orderings side by
// side.
#include <gtest/gtest.h>

#include <array>
#include <barrier>
#include <cstdlib>
#include <thread>
#include <vector>

#include "grid_system.hpp"
#include "physics/cholmod_use.hpp"

namespace vdc {
namespace {

// glibc's rand() after srand(1) (and before any srand): its documented first values.
constexpr std::array<int, 5> kGlibcFromSeedOne{1804289383, 846930886, 1681692777, 1714636915, 1957747793};

TEST(MetisRandom, TheTestProgramExportsItsGeneratorToMetis) { EXPECT_TRUE(metis_draws_per_thread()); }

TEST(MetisRandom, TwoThreadsDrawingInTurnEachGetGlibcsWholeSequence) {
  // The draws alternate between the threads (a barrier after each): from one process-wide
  // generator each thread would get every other value.
  std::array<std::vector<int>, 2> drawn;
  std::barrier turn(2);
  auto draw = [&](std::size_t t) {
    srand(1);
    turn.arrive_and_wait();
    for (std::size_t k = 0; k < kGlibcFromSeedOne.size(); ++k) {
      if (k % 2 == t) drawn[t].push_back(rand());
      turn.arrive_and_wait();
      if (k % 2 != t) drawn[t].push_back(rand());
      turn.arrive_and_wait();
    }
  };
  std::thread first(draw, 0), second(draw, 1);
  first.join();
  second.join();
  for (const auto& values : drawn) EXPECT_EQ(values, std::vector<int>(kGlibcFromSeedOne.begin(), kGlibcFromSeedOne.end()));
}

TEST(MetisRandom, AThreadThatNeverSeededDrawsAsIfSeededWithOne) {
  int first = 0;
  std::thread fresh([&] { first = rand(); });
  fresh.join();
  EXPECT_EQ(first, kGlibcFromSeedOne[0]);
}

TEST(MetisRandom, OrderingsSideBySideAreTheOrderingsAlone) {
  // METIS's nested dissection randomizes its matchings and refinements: two orderings at once
  // drawing from one sequence give different permutations from run to run.
  std::array<std::vector<int>, 2> col_start, rows, alone;
  std::array<cholmod_common, 2> common{};
  for (std::size_t g = 0; g < 2; ++g) {
    const SparseMatrix a = grid_system(g == 0 ? 40 : 37);
    node_graph(a, 0, a.rows(), col_start[g], rows[g]);
    cholmod_start(&common[g]);
    ASSERT_TRUE(metis_node_order(col_start[g], rows[g], alone[g], common[g]));
  }
  for (int round = 0; round < 10; ++round) {
    std::array<std::vector<int>, 2> together;
    std::array<bool, 2> ok{};
    auto order = [&](std::size_t g) { ok[g] = metis_node_order(col_start[g], rows[g], together[g], common[g]); };
    std::thread first(order, 0), second(order, 1);
    first.join();
    second.join();
    for (std::size_t g = 0; g < 2; ++g) {
      ASSERT_TRUE(ok[g]);
      EXPECT_EQ(together[g], alone[g]) << "graph " << g << ", round " << round;
    }
  }
  for (auto& c : common) cholmod_finish(&c);
}

}  // namespace
}  // namespace vdc
