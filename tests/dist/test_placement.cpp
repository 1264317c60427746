// Where a run's groups go: longest processing time first, and moves from the busiest process
// only when they pay for themselves, against placements worked out by hand.
#include <gtest/gtest.h>

#include "dist/placement.hpp"

namespace vdc {
namespace {

TEST(Placement, LongestFirstEachToTheLeastLoadedProcess) {
  // Costs 4, 7, 2, 5, 1 on two processes: 7 -> 0, 5 -> 1, 4 -> 1 (5 < 7), 2 -> 0 (7 < 9),
  // 1 -> 0 (9 = 9: the lower rank).
  EXPECT_EQ(place_longest_first({4, 7, 2, 5, 1}, 2), (std::vector<int>{1, 0, 0, 1, 0}));
  // More processes than groups: each group alone, the costliest on process 0.
  EXPECT_EQ(place_longest_first({1, 3}, 4), (std::vector<int>{1, 0}));
  EXPECT_EQ(place_longest_first({2, 2, 2}, 1), (std::vector<int>{0, 0, 0}));
}

TEST(Placement, AMoveIsMadeOnlyWhenItsGainExceedsItsCost) {
  // Loads 6 (groups 0, 1, 2: 3, 2, 1 s a frame) and 1 (group 3). Group 0 to process 1 makes
  // them 3 and 4: 2 s a frame less for the busiest, 20 s over ten frames against 0.5 s to move
  // (group 1 gains as much, but group 0 comes first). Then process 1 is the busiest at 4 and
  // moving group 3 back gains nothing.
  const std::vector<int> owner{0, 0, 0, 1};
  const std::vector<double> seconds{3, 2, 1, 1};
  const auto moves = rebalance(owner, seconds, {0.5, 0.5, 0.5, 0.5}, 2, 10);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_EQ(moves[0].group, 0);
  EXPECT_EQ(moves[0].from, 0);
  EXPECT_EQ(moves[0].to, 1);
  // 20 s of gain does not pay 25 s of moving; 2 s (one frame ahead) pays 0.5 s.
  EXPECT_TRUE(rebalance(owner, seconds, {25, 25, 25, 25}, 2, 10).empty());
  EXPECT_EQ(rebalance(owner, seconds, {0.5, 0.5, 0.5, 0.5}, 2, 1).size(), 1u);
  // Balanced already: nothing moves however cheap.
  EXPECT_TRUE(rebalance({0, 1}, {2, 2}, {0, 0}, 2, 10).empty());
}

TEST(Placement, SeveralMovesEachFromTheBusiestProcess) {
  // Four groups of 1 s on process 0 of four: three moves, one to each idle process.
  const auto moves = rebalance({0, 0, 0, 0}, {1, 1, 1, 1}, {0.1, 0.1, 0.1, 0.1}, 4, 10);
  ASSERT_EQ(moves.size(), 3u);
  std::vector<int> to;
  for (const GroupMove& m : moves) {
    EXPECT_EQ(m.from, 0);
    to.push_back(m.to);
  }
  std::sort(to.begin(), to.end());
  EXPECT_EQ(to, (std::vector<int>{1, 2, 3}));
}

}  // namespace
}  // namespace vdc
