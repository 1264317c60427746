#include "physics/block_diagonal_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <omp.h>

#include "core/task_order.hpp"

namespace vdc {

std::vector<std::pair<Eigen::Index, Eigen::Index>> independent_ranges(const SparseMatrix& a, Eigen::Index min_size) {
  // A range can end after column j when no column up to j reaches a row below j: with both
  // triangles stored, nothing then couples the columns before the cut to those after it.
  std::vector<std::pair<Eigen::Index, Eigen::Index>> ranges;
  Eigen::Index start = 0, reach = -1;
  for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
    reach = std::max(reach, j);
    for (SparseMatrix::InnerIterator it(a, j); it; ++it) reach = std::max(reach, it.row());
    if (reach == j) {
      if (!ranges.empty() && ranges.back().second < min_size) ranges.back().second = j + 1 - ranges.back().first;
      else ranges.emplace_back(start, j + 1 - start);
      start = j + 1;
    }
  }
  if (ranges.size() > 1 && ranges.back().second < min_size) {
    const Eigen::Index last = ranges.back().second;
    ranges.pop_back();
    ranges.back().second += last;
  }
  return ranges;
}

BlockDiagonalSolver::BlockDiagonalSolver(LinearSolverKind kind, const LinearSolverParams& params)
    : kind_(kind), params_(params) {}

void BlockDiagonalSolver::analyze(const SparseMatrix& a) {
  // The blocks are copied from the compressed arrays; an uncompressed matrix is solved whole.
  const auto ranges = a.isCompressed() ? independent_ranges(a, kMinBlockUnknowns)
                                       : std::vector<std::pair<Eigen::Index, Eigen::Index>>{{0, a.rows()}};
  blocks_.clear();
  blocks_.resize(ranges.size());
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    blocks_[k].start = ranges[k].first;
    blocks_[k].size = ranges[k].second;
  }
  std::stable_sort(blocks_.begin(), blocks_.end(), [](const Block& p, const Block& q) { return p.size > q.size; });
  LinearSolverParams inner = params_;
  if (blocks_.size() > 1) inner.threads = 1;  // the blocks are the parallelism
  // Each block analyzed on its own (its own CHOLMOD workspace, METIS reseeding for each), the
  // blocks side by side, largest first.
  std::vector<std::array<Eigen::Index, 2>> halves(blocks_.size(), {-1, -1});
  auto analyze_block = [&](std::size_t k) {
    Block& block = blocks_[k];
    if (kind_ == LinearSolverKind::Cholmod && a.isCompressed() && block.size >= kMinSeparatedUnknowns) {
      block.separated = std::make_unique<SeparatedCholesky>();
      if (block.separated->analyze(a, block.start, block.size, inner.threads)) {
        halves[k] = {block.separated->half_unknowns(0), block.separated->half_unknowns(1)};
        return;
      }
      block.separated.reset();
    }
    block.solver = make_linear_solver(kind_, inner);
    if (blocks_.size() > 1) {
      copy_pattern(a, block);
      copy_values(a, block);
      block.solver->analyze(block.a);
    } else {
      block.solver->analyze(a);
    }
  };
  // (No one-thread region around a single block: CHOLMOD's own would then be a nested team.)
  for_each_in_order(index_order(blocks_.size()), blocks_.size() > 1 ? params_.threads : 1,
                    [&](int k) { analyze_block(static_cast<std::size_t>(k)); });
  std::vector<std::pair<Eigen::Index, std::pair<int, int>>> units;
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    if (blocks_[k].separated) {
      for (int h = 0; h < 2; ++h) units.push_back({halves[k][static_cast<std::size_t>(h)], {static_cast<int>(k), h}});
    } else {
      units.push_back({blocks_[k].size, {static_cast<int>(k), -1}});
    }
  }
  std::stable_sort(units.begin(), units.end(), [](const auto& p, const auto& q) { return p.first > q.first; });
  units_.clear();
  for (const auto& unit : units) units_.push_back(unit.second);
}

std::size_t BlockDiagonalSolver::separated_blocks() const {
  return static_cast<std::size_t>(std::count_if(blocks_.begin(), blocks_.end(), [](const Block& b) { return b.separated != nullptr; }));
}

void BlockDiagonalSolver::copy_pattern(const SparseMatrix& a, Block& block) {
  const Eigen::Index s = block.start, n = block.size;
  const auto* outer = a.outerIndexPtr();
  block.a.resize(n, n);
  block.a.resizeNonZeros(outer[s + n] - outer[s]);
  auto* block_outer = block.a.outerIndexPtr();
  auto* block_inner = block.a.innerIndexPtr();
  for (Eigen::Index j = 0; j <= n; ++j) block_outer[j] = outer[s + j] - outer[s];
  for (auto k = outer[s]; k < outer[s + n]; ++k) block_inner[k - outer[s]] = a.innerIndexPtr()[k] - static_cast<int>(s);
}

void BlockDiagonalSolver::copy_values(const SparseMatrix& a, Block& block) {
  const auto* outer = a.outerIndexPtr();
  std::copy(a.valuePtr() + outer[block.start], a.valuePtr() + outer[block.start + block.size], block.a.valuePtr());
}

SolveReport BlockDiagonalSolver::solve(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (blocks_.size() == 1 && blocks_.front().solver) return blocks_.front().solver->solve(a, b, x);
  // One active level: CHOLMOD's and BLAS's own teams inside each unit run on the unit's thread
  // (as in cholmod_use.hpp's cholmod_serial). On one thread no region is opened: inside even a
  // one-thread region, cholmod_serial's team would be a nested one, whose threads libgomp
  // starts and ends at every call (about 70 thread starts a karate frame).
  omp_set_max_active_levels(1);
  // A block split in two is solved in four steps (SeparatedCholesky::solve): its halves'
  // factorizations and forward substitutions, its separator, its halves' back substitutions,
  // its separator's unknowns and residual. Each step's units side by side, the whole blocks'
  // solves with the first.
  for (Block& block : blocks_)
    if (block.separated) {
      block.b = b.segment(block.start, block.size);
      block.x.resize(block.size);
    }
  auto factor_or_solve = [&](int u) {
    const auto [k, half] = units_[static_cast<std::size_t>(u)];
    Block& block = blocks_[static_cast<std::size_t>(k)];
    if (half >= 0) {
      block.half_ready[static_cast<std::size_t>(half)] = block.separated->factor_half(a, half) && block.separated->forward_half(block.b, half);
      return;
    }
    copy_values(a, block);
    block.b = b.segment(block.start, block.size);
    block.x = x.segment(block.start, block.size);
    block.report = block.solver->solve(block.a, block.b, block.x);
  };
  auto solve_separator = [&](int k) {
    Block& block = blocks_[static_cast<std::size_t>(k)];
    if (!block.separated) return;
    block.separator_solved = block.half_ready[0] && block.half_ready[1] && block.separated->solve_separator(a, block.b);
  };
  auto back_substitute = [&](int u) {
    const auto [k, half] = units_[static_cast<std::size_t>(u)];
    Block& block = blocks_[static_cast<std::size_t>(k)];
    if (half < 0) return;
    block.half_solved[static_cast<std::size_t>(half)] = block.separator_solved && block.separated->back_half(half, block.x);
  };
  auto finish = [&](int k) {
    Block& block = blocks_[static_cast<std::size_t>(k)];
    if (!block.separated) return;
    block.report = block.half_solved[0] && block.half_solved[1] ? block.separated->finish(a, block.b, block.x) : SolveReport{};
  };
  const auto n = static_cast<int>(units_.size()), m = static_cast<int>(blocks_.size());
  auto steps = [&](auto&& each) {
    each(n, factor_or_solve);
    each(m, solve_separator);
    each(n, back_substitute);
    each(m, finish);
  };
  if (params_.threads > 1) {
    // One team for the four steps, each a loop shared out within it.
#pragma omp parallel num_threads(params_.threads)
    steps([](int count, auto&& step) {
#pragma omp for schedule(dynamic, 1)
      for (int i = 0; i < count; ++i) step(i);
    });
  } else {
    steps([](int count, auto&& step) {
      for (int i = 0; i < count; ++i) step(i);
    });
  }
  SolveReport r;
  r.ok = true;
  double residual2 = 0;
  for (const Block& block : blocks_) {
    r.ok = r.ok && block.report.ok;
    r.iterations = std::max(r.iterations, block.report.iterations);
    r.factorizations = std::max(r.factorizations, block.report.factorizations);
    const double rb = block.report.residual * block.b.norm();
    residual2 += rb * rb;
    if (block.x.size() == block.size) x.segment(block.start, block.size) = block.x;
  }
  const double nb = b.norm();
  r.residual = nb > 0 ? std::sqrt(residual2) / nb : std::sqrt(residual2);
  return r;
}

}  // namespace vdc
