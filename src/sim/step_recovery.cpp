// Substep recovery: refuse, clamp, halve, fail (step halving as Baraff and Witkin 1998 control
// their step size, with a clamp for velocity changes that halving does not shrink).
#include "sim/step_recovery.hpp"

#include <cmath>

namespace vdc {

Recovery after_failure(const StepInterval& step, const StepRecoveryLimits& limits) {
  return step.depth >= limits.max_halvings ? Recovery::Fail : Recovery::Halve;
}

Recovery after_solve(const StepReport& refused, const StepInterval& step, const StepRecoveryLimits& limits) {
  if (refused.ok) return Recovery::Accept;
  // A velocity change that does not shrink with the step (the contact penalty pushing a deep
  // penetration out asks for a fixed displacement, so a velocity growing as 1/h) or that remains
  // at the smallest step: clamp it to the limit rather than end the run.
  const bool over_limit = std::isfinite(refused.max_dv) && refused.max_dv > limits.max_velocity_change;
  const bool not_shrinking = step.refused_dv > 0 && refused.max_dv >= step.refused_dv;
  if (over_limit && (step.depth >= limits.max_halvings || not_shrinking)) return Recovery::Clamp;
  return after_failure(step, limits);
}

bool zones_may_halve(const StepInterval& step, const StepRecoveryLimits& limits) {
  return step.depth < limits.collision_halvings && step.depth < limits.max_halvings;
}

std::pair<StepInterval, StepInterval> halves(const StepInterval& step, const StepReport& report, const StepRecoveryLimits& limits) {
  const double dv = report.max_dv > limits.max_velocity_change ? report.max_dv : 0;
  const double t_mid = step.t + (step.t_end - step.t) / 2;
  return {StepInterval{step.t, t_mid, step.depth + 1, dv}, StepInterval{t_mid, step.t_end, step.depth + 1, dv}};
}

}  // namespace vdc
