// Backward Euler with one Newton step per step (Baraff and Witkin 1998, eq. 18): assemble,
// constrain handles, solve for dv, then v += dv, x += h v.
#pragma once
#include <memory>
#include <string>

#include "physics/assembly.hpp"
#include "physics/linear_solver.hpp"

namespace vdc {

struct StepReport {
  bool ok = false;
  std::string failure;  // why the step was refused, when !ok
  int solver_iterations = 0;
  int factorizations = 0;
  double assemble_seconds = 0, solve_seconds = 0;
  double max_dv = 0;  // largest velocity change of a free node, m/s (before any clamping)
  int clamped_nodes = 0;  // nodes whose velocity change was clamped (VelocityLimit::Clamp)
};

// What a step does with a velocity change above the limit: refuse the step, or (a last resort
// when smaller steps do not help) clamp each node's change to the limit and go on.
enum class VelocityLimit { Refuse, Clamp };

class ImplicitIntegrator {
 public:
  ImplicitIntegrator(const ClothModel& model, LinearSolverKind kind, const LinearSolverParams& params = {});
  // Advances x, v (3n each) by p.h. On failure (non-finite values, solver failure, a velocity
  // change above max_dv unless clamped) x and v are left unchanged and the report says why.
  // `contacts` (proximity repulsion and friction) join the elastic forces.
  StepReport step(Eigen::VectorXd& x, Eigen::VectorXd& v, const std::vector<VelocityConstraint>& constraints,
                  const StepParams& p, double max_dv, const std::vector<ContactTerm>& contacts = {},
                  VelocityLimit limit = VelocityLimit::Refuse);
  const SystemAssembler& assembler() const { return assembler_; }

 private:
  SystemAssembler assembler_;
  std::unique_ptr<LinearSolver> solver_;
  Eigen::VectorXd dv_;
};

}  // namespace vdc
