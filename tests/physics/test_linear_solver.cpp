// The direct solver (CHOLMOD with a METIS ordering of the node graph) gives bit-identical
// solutions whether it runs alone or beside another solve on a second thread: the parts of a
// crowd solve side by side, and a run must reproduce exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/linear_solver.hpp"
#include "grid_system.hpp"

namespace vdc {
namespace {

Eigen::VectorXd solve_once(const SparseMatrix& a, const Eigen::VectorXd& b) {
  const auto solver = make_linear_solver(LinearSolverKind::Cholmod);
  solver->analyze(a);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  EXPECT_TRUE(solver->solve(a, b, x).ok);
  return x;
}

TEST(LinearSolver, SolvesSideBySideMatchASolveAloneBitForBit) {
  const SparseMatrix a = grid_system(40);
  Eigen::VectorXd b(a.rows());
  for (Eigen::Index k = 0; k < b.size(); ++k) b[k] = std::sin(0.37 * static_cast<double>(k));
  const Eigen::VectorXd alone = solve_once(a, b);
  ASSERT_LT((a * alone - b).norm(), 1e-10 * b.norm());
  const int runs = 16;
  std::vector<Eigen::VectorXd> side_by_side(runs);
#pragma omp parallel for schedule(static, 1) num_threads(2)
  for (int k = 0; k < runs; ++k) side_by_side[static_cast<std::size_t>(k)] = solve_once(a, b);
  for (int k = 0; k < runs; ++k) EXPECT_EQ((side_by_side[static_cast<std::size_t>(k)] - alone).cwiseAbs().maxCoeff(), 0.0) << "solve " << k;
}

}  // namespace
}  // namespace vdc
