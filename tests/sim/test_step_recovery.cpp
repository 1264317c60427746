// The substep recovery policy, case by case: what a refused solve, a failed clamp and impact
// zones that do not separate lead to at each halving depth.
#include <gtest/gtest.h>

#include <limits>

#include "sim/step_recovery.hpp"

namespace vdc {
namespace {

const StepRecoveryLimits kLimits{.max_halvings = 3, .collision_halvings = 2, .max_velocity_change = 10};

StepReport report(bool ok, double max_dv) {
  StepReport r;
  r.ok = ok;
  r.max_dv = max_dv;
  return r;
}

StepInterval at_depth(int depth, double refused_dv = 0) { return StepInterval{0.0, 0.01, depth, refused_dv}; }

TEST(StepRecovery, ATakenSolveIsAccepted) {
  for (int depth = 0; depth <= 3; ++depth) EXPECT_EQ(after_solve(report(true, 25), at_depth(depth, 30), kLimits), Recovery::Accept);
}

TEST(StepRecovery, AVelocityChangeOverTheLimitHalvesWhileItShrinks) {
  // First refusal: nothing to compare with, so halve.
  EXPECT_EQ(after_solve(report(false, 40), at_depth(0), kLimits), Recovery::Halve);
  // The halves ask for less than their parent: halving helps, halve again.
  EXPECT_EQ(after_solve(report(false, 25), at_depth(1, 40), kLimits), Recovery::Halve);
  // As much or more than the parent (a change that grows as 1/h): clamp.
  EXPECT_EQ(after_solve(report(false, 40), at_depth(1, 40), kLimits), Recovery::Clamp);
  EXPECT_EQ(after_solve(report(false, 80), at_depth(2, 40), kLimits), Recovery::Clamp);
  // At the smallest step any finite change over the limit is clamped.
  EXPECT_EQ(after_solve(report(false, 11), at_depth(3), kLimits), Recovery::Clamp);
}

TEST(StepRecovery, AFailureThatIsNotTheVelocityLimitHalvesThenEndsTheRun) {
  // A failed solve (non-finite values) within the limit: halve, and at the smallest step fail.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(after_solve(report(false, nan), at_depth(0), kLimits), Recovery::Halve);
  EXPECT_EQ(after_solve(report(false, nan), at_depth(3, 40), kLimits), Recovery::Fail);
  EXPECT_EQ(after_solve(report(false, 5), at_depth(2, 40), kLimits), Recovery::Halve);
  EXPECT_EQ(after_solve(report(false, std::numeric_limits<double>::infinity()), at_depth(3), kLimits), Recovery::Fail);
  for (int depth = 0; depth < 3; ++depth) EXPECT_EQ(after_failure(at_depth(depth), kLimits), Recovery::Halve) << depth;
  EXPECT_EQ(after_failure(at_depth(3), kLimits), Recovery::Fail);
}

TEST(StepRecovery, ZonesHalveTheStepTwiceThenKeepTheirStartPositions) {
  EXPECT_TRUE(zones_may_halve(at_depth(0), kLimits));
  EXPECT_TRUE(zones_may_halve(at_depth(1), kLimits));
  EXPECT_FALSE(zones_may_halve(at_depth(2), kLimits));
  // Never past the smallest step, whatever the collision halvings allow.
  const StepRecoveryLimits shallow{.max_halvings = 1, .collision_halvings = 2, .max_velocity_change = 10};
  EXPECT_TRUE(zones_may_halve(at_depth(0), shallow));
  EXPECT_FALSE(zones_may_halve(at_depth(1), shallow));
}

TEST(StepRecovery, HalvesSplitTheStepAndPassDownAVelocityChangeOverTheLimit) {
  const StepInterval step{0.5, 0.51, 1, 0};
  const auto [first, second] = halves(step, report(false, 40), kLimits);
  EXPECT_DOUBLE_EQ(first.t, 0.5);
  EXPECT_DOUBLE_EQ(first.t_end, 0.505);
  EXPECT_DOUBLE_EQ(second.t, 0.505);
  EXPECT_DOUBLE_EQ(second.t_end, 0.51);
  EXPECT_EQ(first.depth, 2);
  EXPECT_EQ(second.depth, 2);
  EXPECT_EQ(first.refused_dv, 40);
  EXPECT_EQ(second.refused_dv, 40);
  // Refused for another reason (within the limit): nothing to compare the halves with.
  EXPECT_EQ(halves(step, report(false, 5), kLimits).first.refused_dv, 0);
}

}  // namespace
}  // namespace vdc
