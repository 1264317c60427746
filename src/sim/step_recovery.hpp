// How a substep that cannot be taken as it stands is recovered: one policy for the four ways
// out (accept, clamp the velocity change, halve the step, end the run), decided from the step's
// report and its halving depth alone.
#pragma once
#include <utility>

#include "physics/integrator.hpp"

namespace vdc {

struct StepRecoveryLimits {
  int max_halvings = 8;               // depth of the smallest step: 1/2^max_halvings of a substep
  int collision_halvings = 2;         // halvings impact zones may ask for before they are frozen
  double max_velocity_change = 0;     // m/s a node may change in a step
};

// A step to take, from t to t_end, `depth` halvings below a substep; refused_dv is the velocity
// change that made its parent step refuse (0 at the top or when the parent failed otherwise).
struct StepInterval {
  double t = 0, t_end = 0;
  int depth = 0;
  double refused_dv = 0;
};

enum class Recovery {
  Accept,  // go on with the step as solved
  Clamp,   // solve again, clamping each node's velocity change to the limit
  Halve,   // take the step as two halves
  Fail     // the step is the smallest and still fails: the run ends
};

// After a solve that refuses velocity changes over the limit: Accept when it was taken; Clamp
// when the change is finite, over the limit and does not shrink with the step (at least the
// parent's) or the step is the smallest; otherwise as after_failure.
Recovery after_solve(const StepReport& refused, const StepInterval& step, const StepRecoveryLimits& limits);

// After a clamped solve that still failed, or impact zones that did not separate: Halve, or Fail
// at the smallest step.
Recovery after_failure(const StepInterval& step, const StepRecoveryLimits& limits);

// Whether impact zones that do not separate may still halve the step; if not, they keep their
// start positions (the collision fallback) and the step is accepted.
bool zones_may_halve(const StepInterval& step, const StepRecoveryLimits& limits);

// The two halves of a step refused by `report` (its velocity change passed down when it was over
// the limit, to tell when halving stops helping), first half first.
std::pair<StepInterval, StepInterval> halves(const StepInterval& step, const StepReport& report, const StepRecoveryLimits& limits);

}  // namespace vdc
