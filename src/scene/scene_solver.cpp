// The `solver` block (docs/scene-format.md, "solver"): the linear solver and the step's bounds.
#include "scene/scene_blocks.hpp"

namespace vdc {

SolverSpec parse_solver(const JsonValue& j) {
  j.only_keys({"linear", "cg_tolerance", "cg_max_iterations", "max_velocity_change"});
  SolverSpec s;
  if (auto lin = j.find("linear"))
    if (!parse_linear_solver_kind(lin->string(), s.linear)) lin->fail("expected \"cholmod-pcg\", \"cholmod\", \"ldlt\" or \"cg\"");
  s.params.cg_tolerance = j.positive_or("cg_tolerance", s.params.cg_tolerance);
  long long it = j.integer_or("cg_max_iterations", s.params.cg_max_iterations);
  if (it < 1 || it > 1'000'000) j.at("cg_max_iterations").fail("must be between 1 and 1,000,000");
  s.params.cg_max_iterations = static_cast<int>(it);
  s.max_velocity_change = j.positive_or("max_velocity_change", s.max_velocity_change);
  return s;
}

}  // namespace vdc
