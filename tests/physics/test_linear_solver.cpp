// The direct solver (CHOLMOD with a METIS ordering of the node graph) gives bit-identical
// solutions whether it runs alone or beside another solve on a second thread: the parts of a
// crowd solve side by side, and a run must reproduce exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/linear_solver.hpp"

namespace vdc {
namespace {

// A grid graph's Laplacian with 3 unknowns a node, shifted to be positive definite: the pattern
// of a sheet's system.
SparseMatrix grid_system(int side) {
  std::vector<Eigen::Triplet<double>> t;
  auto node = [&](int i, int j) { return i * side + j; };
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int c = 0; c < 3; ++c) {
        const int r = 3 * node(i, j) + c;
        t.emplace_back(r, r, 6.1 + 0.01 * c);  // 6 neighbours: diagonally dominant
        for (const auto& [di, dj] : {std::pair{1, 0}, {0, 1}, {1, 1}}) {
          if (i + di >= side || j + dj >= side) continue;
          const int s = 3 * node(i + di, j + dj) + c;
          t.emplace_back(r, s, -1.0);
          t.emplace_back(s, r, -1.0);
        }
      }
  SparseMatrix a(3 * side * side, 3 * side * side);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

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
