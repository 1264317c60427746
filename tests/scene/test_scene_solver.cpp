// The `solver` block: the linear solver by name, the iteration bound's range, the step's bound.
#include <gtest/gtest.h>

#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

TEST(SceneSolver, DefaultsAndEveryNamedSolver) {
  const SolverSpec plain = parse_solver(json_block("{}", "solver"));
  EXPECT_EQ(plain.linear, LinearSolverKind::Cholmod);
  EXPECT_EQ(plain.params.cg_tolerance, LinearSolverParams{}.cg_tolerance);
  EXPECT_EQ(plain.params.cg_max_iterations, LinearSolverParams{}.cg_max_iterations);
  EXPECT_EQ(plain.max_velocity_change, 50.0);
  const std::pair<const char*, LinearSolverKind> names[] = {{"cholmod-pcg", LinearSolverKind::CholmodPcg},
                                                            {"cholmod", LinearSolverKind::Cholmod},
                                                            {"ldlt", LinearSolverKind::SimplicialLdlt},
                                                            {"cg", LinearSolverKind::ConjugateGradient}};
  for (const auto& [name, kind] : names)
    EXPECT_EQ(parse_solver(json_block(std::string(R"({"linear": ")") + name + "\"}", "solver")).linear, kind) << name;
  const SolverSpec given = parse_solver(json_block(R"({"cg_tolerance": 1e-9, "cg_max_iterations": 7, "max_velocity_change": 3})", "solver"));
  EXPECT_EQ(given.params.cg_tolerance, 1e-9);
  EXPECT_EQ(given.params.cg_max_iterations, 7);
  EXPECT_EQ(given.max_velocity_change, 3.0);
}

TEST(SceneSolver, ErrorsNameTheKey) {
  EXPECT_EQ(input_error([] { parse_solver(json_block(R"({"linear": "lu"})", "solver")); }),
            "scene.json:solver.linear: expected \"cholmod-pcg\", \"cholmod\", \"ldlt\" or \"cg\"");
  EXPECT_EQ(input_error([] { parse_solver(json_block(R"({"cg_max_iterations": 0})", "solver")); }),
            "scene.json:solver.cg_max_iterations: must be between 1 and 1,000,000");
  EXPECT_EQ(input_error([] { parse_solver(json_block(R"({"cg_max_iterations": 1000000})", "solver")); }), "");
}

}  // namespace
}  // namespace vdc
