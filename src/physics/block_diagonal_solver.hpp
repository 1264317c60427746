// A system whose pattern falls apart into independent diagonal blocks, solved block by block on
// parallel threads. The garments of one character are such blocks: nothing in the implicit
// system couples two of them (contacts between garments add only diagonal blocks,
// SystemAssembler::add_contacts), so a layered outfit's factorizations, serial inside CHOLMOD,
// can run side by side.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "physics/linear_solver.hpp"

namespace vdc {

// The finest split of a symmetric matrix's unknowns into contiguous ranges [start, start + size)
// with no stored entry coupling two ranges, ranges smaller than `min_size` unknowns merged into
// the one after them (the last into the one before). One range when nothing splits.
std::vector<std::pair<Eigen::Index, Eigen::Index>> independent_ranges(const SparseMatrix& a, Eigen::Index min_size);

class BlockDiagonalSolver final : public LinearSolver {
 public:
  // Each block gets its own solver of `kind`; params.threads blocks are solved at once.
  BlockDiagonalSolver(LinearSolverKind kind, const LinearSolverParams& params);
  void analyze(const SparseMatrix& a) override;
  // The blocks' reports combined: ok when every block is, the most iterations and
  // factorizations of any block, and the relative residual of the whole system.
  SolveReport solve(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) override;
  std::size_t blocks() const { return blocks_.size(); }

  // Blocks below this many unknowns (about 200 nodes) join a neighbour: each factorization has
  // a fixed cost, and small garments gain nothing from a thread of their own.
  static constexpr Eigen::Index kMinBlockUnknowns = 600;

 private:
  struct Block {
    Eigen::Index start = 0, size = 0;
    std::unique_ptr<LinearSolver> solver;
    SparseMatrix a;
    Eigen::VectorXd b, x;
    SolveReport report;
  };
  // The block's pattern (at analysis) and its values (at every solve), taken from `a`'s columns.
  static void copy_pattern(const SparseMatrix& a, Block& block);
  static void copy_values(const SparseMatrix& a, Block& block);

  LinearSolverKind kind_;
  LinearSolverParams params_;
  std::vector<Block> blocks_;  // largest first, so the threads finish together
};

}  // namespace vdc
