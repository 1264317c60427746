// Where a run's groups go: longest processing time first, and moves from the busiest process
// or trades only when they pay for themselves, against placements worked out by hand.
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
  // Loads 6 (groups 0, 1, 2: 3, 2, 1 s a frame) and 1 (group 3), ten frames ahead: 60 and 10
  // s. Group 1 to process 1 leaves 40 and 10 + 20 + 0.5 = 30.5 s (group 0 would leave 30 and
  // 40.5): it moves. Then process 0's 40 s can lose nothing: group 0 would make process 1 61 s,
  // group 2 41 s (more than 40 less 1%), and no lighter group of process 1 is there to trade.
  const std::vector<int> owner{0, 0, 0, 1};
  const std::vector<double> seconds{3, 2, 1, 1};
  const auto moves = rebalance(owner, seconds, {0.5, 0.5, 0.5, 0.5}, 2, 10);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_EQ(moves[0].group, 1);
  EXPECT_EQ(moves[0].from, 0);
  EXPECT_EQ(moves[0].to, 1);
  // Moving costs the receiver: at 35 s a group, group 2 still pays (50 and 10 + 10 + 35 = 55 s,
  // below 60 less 1%); at 50 s none does (70 s and more).
  const auto dear = rebalance(owner, seconds, {35, 35, 35, 35}, 2, 10);
  ASSERT_EQ(dear.size(), 1u);
  EXPECT_EQ(dear[0].group, 2);
  EXPECT_TRUE(rebalance(owner, seconds, {50, 50, 50, 50}, 2, 10).empty());
  // One frame ahead: 6 s; group 1 leaves 4 and 3.5 s.
  EXPECT_EQ(rebalance(owner, seconds, {0.5, 0.5, 0.5, 0.5}, 2, 1).size(), 1u);
  // Balanced already: nothing moves however cheap.
  EXPECT_TRUE(rebalance({0, 1}, {2, 2}, {0, 0}, 2, 10).empty());
  // A gain of less than 1% of the busiest process's time is not taken: loads 101 and 99 (one
  // group of 1 s could even them to 100 and 100).
  EXPECT_TRUE(rebalance({0, 0, 1}, {100, 1, 99}, {0, 0, 0}, 2, 1).empty());
}

TEST(Placement, TheBusiestProcessTradesWhereNoSingleMovePays) {
  // Groups of 6 and 2 s on process 0, 5 and 1 s on process 1: 80 and 60 s over ten frames.
  // No single move lowers the busier (the 2 s group would make them 60 and 80). Trading the
  // 6 s group for the 5 s one makes both 70 + 0.5 s; trading the 2 for the 1 does as well, but
  // the heavier group is tried first.
  const auto moves = rebalance({0, 0, 1, 1}, {6, 2, 5, 1}, {0.5, 0.5, 0.5, 0.5}, 2, 10);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_EQ(moves[0].group, 0);
  EXPECT_EQ(moves[0].from, 0);
  EXPECT_EQ(moves[0].to, 1);
  EXPECT_EQ(moves[1].group, 2);
  EXPECT_EQ(moves[1].from, 1);
  EXPECT_EQ(moves[1].to, 0);
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
