// A system whose pattern falls apart into independent diagonal blocks, solved block by block on
// parallel threads. The garments of one character are such blocks: nothing in the implicit
// system couples two of them (contacts between garments add only diagonal blocks,
// SystemAssembler::add_contacts), so a layered outfit's factorizations, serial inside CHOLMOD,
// can run side by side. A block too large to leave to one thread (a garment of a few thousand
// faces) is split in two across a vertex separator (SeparatedCholesky), its halves factored like
// blocks of their own. What a solve finds does not depend on the thread count.
#pragma once
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "physics/linear_solver.hpp"
#include "physics/separated_cholesky.hpp"

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
  // Blocks from this many unknowns (2,000 nodes, about 4,000 faces) are split across a
  // separator when the solver is CHOLMOD's direct one.
  static constexpr Eigen::Index kMinSeparatedUnknowns = 6000;
  // How many blocks are solved in two halves (after analyze).
  std::size_t separated_blocks() const;

 private:
  struct Block {
    Eigen::Index start = 0, size = 0;
    std::unique_ptr<LinearSolver> solver;            // or, for a block split in two:
    std::unique_ptr<SeparatedCholesky> separated;
    std::array<bool, 2> half_ready{};  // factored and forward-substituted
    std::array<bool, 2> half_solved{};  // back-substituted
    bool separator_solved = false;
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
  // Units of a solve's parallel work: (block, -1) a whole block's solve, (block, h) half h of a
  // separated block (its factorization and forward substitution, later its back substitution);
  // largest first.
  std::vector<std::pair<int, int>> units_;
};

}  // namespace vdc
