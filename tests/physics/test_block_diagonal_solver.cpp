// A system of independent garments solved block by block: the split found from the pattern, the
// answer the whole system's solve gives, and the same answer bit for bit on one thread or two.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grid_system.hpp"
#include "physics/block_diagonal_solver.hpp"

namespace vdc {
namespace {

// Three sheets side by side in one system (sides 20, 16 and 3 nodes: 1200, 768 and 27
// unknowns), with diagonal-only terms like the contacts between two garments, and optionally
// one entry coupling the first two.
SparseMatrix three_sheets(bool coupled) {
  std::vector<Eigen::Triplet<double>> t;
  add_grid_system(t, 20, 0);
  add_grid_system(t, 16, 1200);
  add_grid_system(t, 3, 1968);
  t.emplace_back(5, 5, 0.5);
  t.emplace_back(1300, 1300, 0.5);
  if (coupled) {
    t.emplace_back(1199, 1200, -0.5);
    t.emplace_back(1200, 1199, -0.5);
  }
  SparseMatrix a(1995, 1995);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

Eigen::VectorXd load(Eigen::Index n) {
  Eigen::VectorXd b(n);
  for (Eigen::Index k = 0; k < n; ++k) b[k] = std::sin(0.37 * static_cast<double>(k)) + 0.1;
  return b;
}

Eigen::VectorXd solve_blocks(const SparseMatrix& a, const Eigen::VectorXd& b, LinearSolverKind kind, int threads,
                             std::size_t& blocks) {
  LinearSolverParams p;
  p.threads = threads;
  BlockDiagonalSolver solver(kind, p);
  solver.analyze(a);
  blocks = solver.blocks();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  const SolveReport r = solver.solve(a, b, x);
  EXPECT_TRUE(r.ok);
  EXPECT_LT(r.residual, 1e-6);
  EXPECT_NEAR(r.residual, (a * x - b).norm() / b.norm(), 1e-12);
  return x;
}

TEST(BlockDiagonalSolver, SplitsWhereNothingCouplesAndMergesSmallBlocks) {
  using Ranges = std::vector<std::pair<Eigen::Index, Eigen::Index>>;
  EXPECT_EQ(independent_ranges(three_sheets(false), 1), (Ranges{{0, 1200}, {1200, 768}, {1968, 27}}));
  // The 27 unknowns of the last sheet join the one before it.
  EXPECT_EQ(independent_ranges(three_sheets(false), 600), (Ranges{{0, 1200}, {1200, 795}}));
  EXPECT_EQ(independent_ranges(three_sheets(true), 1), (Ranges{{0, 1968}, {1968, 27}}));
  EXPECT_EQ(independent_ranges(three_sheets(false), 800), (Ranges{{0, 1995}}));  // the 795 join the first
  EXPECT_EQ(independent_ranges(grid_system(10), 1), (Ranges{{0, 300}}));
}

TEST(BlockDiagonalSolver, GivesTheWholeSystemsSolution) {
  const SparseMatrix a = three_sheets(false);
  const Eigen::VectorXd b = load(a.rows());
  const auto whole = make_linear_solver(LinearSolverKind::Cholmod);
  whole->analyze(a);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(b.size());
  ASSERT_TRUE(whole->solve(a, b, expected).ok);
  for (LinearSolverKind kind : {LinearSolverKind::Cholmod, LinearSolverKind::CholmodPcg}) {
    std::size_t blocks = 0;
    const Eigen::VectorXd x = solve_blocks(a, b, kind, 2, blocks);
    EXPECT_EQ(blocks, 2u);
    EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff()) << linear_solver_name(kind);
  }
}

TEST(BlockDiagonalSolver, OneThreadOrTwoGiveTheSameBits) {
  const SparseMatrix a = three_sheets(false);
  const Eigen::VectorXd b = load(a.rows());
  std::size_t blocks = 0;
  const Eigen::VectorXd one = solve_blocks(a, b, LinearSolverKind::Cholmod, 1, blocks);
  for (int run = 0; run < 4; ++run)
    EXPECT_EQ((solve_blocks(a, b, LinearSolverKind::Cholmod, 2, blocks) - one).cwiseAbs().maxCoeff(), 0.0) << "run " << run;
}

TEST(BlockDiagonalSolver, SolvesACoupledSystemWhole) {
  const SparseMatrix a = three_sheets(true);
  const Eigen::VectorXd b = load(a.rows());
  std::size_t blocks = 0;
  solve_blocks(a, b, LinearSolverKind::Cholmod, 2, blocks);
  EXPECT_EQ(blocks, 1u);  // the 27 unknowns of the third sheet merge into the coupled pair
}

}  // namespace
}  // namespace vdc
