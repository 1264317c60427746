// Backward Euler, one Newton step (Baraff and Witkin 1998, eq. 18).
#include "physics/integrator.hpp"

#include <chrono>
#include <cmath>

#include "core/stopwatch.hpp"
#include "physics/block_diagonal_solver.hpp"

namespace vdc {

ImplicitIntegrator::ImplicitIntegrator(const ClothModel& model, LinearSolverKind kind, const LinearSolverParams& params)
    : assembler_(model, params.threads), solver_(std::make_unique<BlockDiagonalSolver>(kind, params)) {
  solver_->analyze(assembler_.matrix());
  dv_.setZero(3 * static_cast<int64_t>(model.num_nodes));
}

StepReport ImplicitIntegrator::step(Eigen::VectorXd& x, Eigen::VectorXd& v, const std::vector<VelocityConstraint>& constraints,
                                    const StepParams& p, double max_dv, const std::vector<ContactTerm>& contacts,
                                    VelocityLimit limit) {
  StepReport r;
  auto t0 = std::chrono::steady_clock::now();
  assembler_.assemble(x, v, p);
  assembler_.add_contacts(contacts);
  assembler_.constrain(constraints);
  r.assemble_seconds = seconds_since(t0);
  if (!assembler_.rhs().allFinite()) {
    r.failure = "non-finite forces";
    return r;
  }
  auto t1 = std::chrono::steady_clock::now();
  SolveReport s = solver_->solve(assembler_.matrix(), assembler_.rhs(), dv_);
  r.solve_seconds = seconds_since(t1);
  r.solver_iterations = s.iterations;
  r.factorizations = s.factorizations;
  if (!s.ok) {
    r.failure = "linear solver failed (relative residual " + std::to_string(s.residual) + ")";
    dv_.setZero();
    return r;
  }
  std::vector<char> constrained(static_cast<std::size_t>(x.size() / 3), 0);
  for (const auto& c : constraints) constrained[static_cast<std::size_t>(c.node)] = 1;
  for (int64_t i = 0; i < x.size() / 3; ++i)
    if (!constrained[static_cast<std::size_t>(i)]) r.max_dv = std::max(r.max_dv, dv_.segment<3>(3 * i).norm());
  if (!(r.max_dv <= max_dv) && limit == VelocityLimit::Clamp && std::isfinite(r.max_dv)) {
    for (int64_t i = 0; i < x.size() / 3; ++i)
      if (const double d = dv_.segment<3>(3 * i).norm(); d > max_dv && !constrained[static_cast<std::size_t>(i)]) {
        dv_.segment<3>(3 * i) *= max_dv / d;
        ++r.clamped_nodes;
      }
  } else if (!(r.max_dv <= max_dv)) {
    r.failure = "velocity change " + std::to_string(r.max_dv) + " m/s exceeds the limit " + std::to_string(max_dv) + " m/s";
    dv_.setZero();
    return r;
  }
  v += dv_;
  x += p.h * v;
  r.ok = true;
  return r;
}

}  // namespace vdc
