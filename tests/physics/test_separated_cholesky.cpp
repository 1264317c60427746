// A system solved in two halves across a vertex separator: the split found, the answer the
// whole system's factorization gives, the same bits on one thread or two, and a system that
// is not positive definite refused without a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grid_system.hpp"
#include "physics/block_diagonal_solver.hpp"
#include "physics/separated_cholesky.hpp"

namespace vdc {
namespace {

Eigen::VectorXd cosine_load(Eigen::Index n) {
  Eigen::VectorXd b(n);
  for (Eigen::Index k = 0; k < n; ++k) b[k] = std::cos(0.23 * static_cast<double>(k)) - 0.2;
  return b;
}

// The grid system of side x side nodes, compressed as the solvers take it.
SparseMatrix compressed_grid(int side) {
  SparseMatrix a = grid_system(side);
  a.makeCompressed();
  return a;
}

Eigen::VectorXd whole_solution(const SparseMatrix& a, const Eigen::VectorXd& b) {
  const auto whole = make_linear_solver(LinearSolverKind::Cholmod);
  whole->analyze(a);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  EXPECT_TRUE(whole->solve(a, b, x).ok);
  return x;
}

// A 50 x 50 node sheet (7,500 unknowns) splits into two halves of at least a fifth of the nodes
// each, with a separator about one row of the grid; the answer is the whole factorization's to
// rounding.
TEST(SeparatedCholesky, SolvesASheetInTwoHalvesAsTheWholeFactorizationDoes) {
  const SparseMatrix a = compressed_grid(50);
  const Eigen::VectorXd b = cosine_load(a.rows());
  SeparatedCholesky solver;
  ASSERT_TRUE(solver.analyze(a, 0, a.rows()));
  const Eigen::Index s = solver.separator_unknowns();
  EXPECT_GT(s, 0);
  EXPECT_LE(s, 3 * 100);  // a cut across the grid: at most two rows of 50 nodes
  for (int h = 0; h < 2; ++h) {
    EXPECT_GE(solver.half_unknowns(h) - s, a.rows() / 5) << h;
    EXPECT_TRUE(solver.factor_half(a, h)) << h;
  }
  EXPECT_EQ(solver.half_unknowns(0) + solver.half_unknowns(1) - s, a.rows());  // every unknown once
  Eigen::VectorXd x;
  const SolveReport r = solver.solve(a, b, x);
  ASSERT_TRUE(r.ok);
  EXPECT_LT(r.residual, 1e-13);
  EXPECT_NEAR(r.residual, (a * x - b).norm() / b.norm(), 1e-15);
  const Eigen::VectorXd expected = whole_solution(a, b);
  EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
}

// The halves' substitutions taken in either order (as two threads may take them) give solve's
// bits: neither half reads what the other writes.
TEST(SeparatedCholesky, TheHalvesStepsInEitherOrderGiveSolvesBits) {
  const SparseMatrix a = compressed_grid(30);
  const Eigen::VectorXd b = cosine_load(a.rows());
  SeparatedCholesky solver;
  ASSERT_TRUE(solver.analyze(a, 0, a.rows()));
  ASSERT_TRUE(solver.factor_half(a, 1) && solver.factor_half(a, 0));
  Eigen::VectorXd whole;
  ASSERT_TRUE(solver.solve(a, b, whole).ok);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(a.rows(), std::nan(""));
  ASSERT_TRUE(solver.forward_half(b, 1) && solver.forward_half(b, 0) && solver.solve_separator(a, b));
  ASSERT_TRUE(solver.back_half(1, x) && solver.back_half(0, x));
  const SolveReport r = solver.finish(a, b, x);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ((x - whole).cwiseAbs().maxCoeff(), 0.0);  // and every unknown written: no NaN left
}

// Two sheets side by side, 50 x 50 and 20 x 20 nodes: the large one is split, the small one
// (1,200 unknowns) solved whole; the same bits on one thread or two.
TEST(SeparatedCholesky, TheBlockSolverSplitsLargeBlocksOnlyAndGivesTheSameBitsOnAnyThreadCount) {
  std::vector<Eigen::Triplet<double>> t;
  add_grid_system(t, 50, 0);
  add_grid_system(t, 20, 7500);
  SparseMatrix a(8700, 8700);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  const Eigen::VectorXd b = cosine_load(a.rows());
  const Eigen::VectorXd expected = whole_solution(a, b);
  Eigen::VectorXd first;
  for (int threads : {1, 2, 2, 1}) {
    LinearSolverParams p;
    p.threads = threads;
    BlockDiagonalSolver solver(LinearSolverKind::Cholmod, p);
    solver.analyze(a);
    EXPECT_EQ(solver.blocks(), 2u);
    EXPECT_EQ(solver.separated_blocks(), 1u);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
    const SolveReport r = solver.solve(a, b, x);
    ASSERT_TRUE(r.ok) << threads;
    EXPECT_NEAR(r.residual, (a * x - b).norm() / b.norm(), 1e-15);
    EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff()) << threads;
    if (first.size() == 0) first = x;
    EXPECT_EQ((x - first).cwiseAbs().maxCoeff(), 0.0) << threads << " threads";
  }
  // One block alone: its halves analyzed side by side on two threads, the same bits.
  const SparseMatrix sheet = compressed_grid(50);
  const Eigen::VectorXd load = cosine_load(sheet.rows());
  Eigen::VectorXd alone;
  for (int threads : {1, 2}) {
    LinearSolverParams p;
    p.threads = threads;
    BlockDiagonalSolver solver(LinearSolverKind::Cholmod, p);
    solver.analyze(sheet);
    EXPECT_EQ(solver.separated_blocks(), 1u);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(load.size());
    ASSERT_TRUE(solver.solve(sheet, load, x).ok) << threads;
    if (alone.size() == 0) alone = x;
    EXPECT_EQ((x - alone).cwiseAbs().maxCoeff(), 0.0) << threads << " threads";
  }
  // Below kMinSeparatedUnknowns, or with another solver, nothing is split.
  BlockDiagonalSolver small(LinearSolverKind::Cholmod, {});
  small.analyze(grid_system(40));  // 4,800 unknowns
  EXPECT_EQ(small.separated_blocks(), 0u);
  BlockDiagonalSolver pcg(LinearSolverKind::CholmodPcg, {});
  pcg.analyze(a);
  EXPECT_EQ(pcg.separated_blocks(), 0u);
}

// A matrix that is not positive definite: a half's factorization fails and the solve reports it.
TEST(SeparatedCholesky, ANegativeDefiniteSystemIsRefused) {
  SparseMatrix a = -grid_system(50);
  a.makeCompressed();
  BlockDiagonalSolver solver(LinearSolverKind::Cholmod, {});
  solver.analyze(a);
  ASSERT_EQ(solver.separated_blocks(), 1u);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(a.rows());
  EXPECT_FALSE(solver.solve(a, cosine_load(a.rows()), x).ok);
}

}  // namespace
}  // namespace vdc
