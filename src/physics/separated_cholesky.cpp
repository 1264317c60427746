// One level of nested dissection with a dense separator (George 1973): two CHOLMOD halves and
// the separator's Schur complement.
#include "physics/separated_cholesky.hpp"

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <array>
#include <cmath>

#include "core/task_order.hpp"
#include "physics/cholmod_use.hpp"
#include "physics/supernodal_cholesky.hpp"

namespace vdc {

struct SeparatedCholesky::Half {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  SupernodalCholesky numeric;          // factors it (CHOLMOD's bits without its OpenMP regions)
  SparseMatrix m;                      // M_h, lower triangle: interior unknowns, then the separator's
  std::vector<Eigen::Index> source;    // per value of m: its index in a's values
  std::vector<Eigen::Index> unknown;   // per unknown of m: the range's unknown
  Eigen::Index interior = 0;           // interior unknowns (the first of m's)
  Eigen::MatrixXd separator_factor;    // L_hS, lower triangular
  Eigen::MatrixXd separator_product;   // L_hS L_hS^T
  Eigen::VectorXd y;                   // the substitutions' vector, interior then separator

  Half() { cholmod_start(&common); }
  // Half h (0 or 1) of `part`'s split of the range's nodes (graph col_start / rows): its
  // unknowns ordered, M_h's pattern taken from `a`, CHOLMOD's analysis in that order.
  bool analyze(const SparseMatrix& a, Eigen::Index start, int h, const std::vector<int>& part, const std::vector<int>& col_start,
               const std::vector<int>& rows, const std::vector<Eigen::Index>& separator);
  ~Half() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  cholmod_sparse view() const { return Eigen::viewAsCholmod(m.selfadjointView<Eigen::Lower>()); }
  // Solves L u = v (`system` CHOLMOD_L) or L^T u = v (CHOLMOD_Lt) in place.
  bool substitute(int system, Eigen::VectorXd& v) {
    cholmod_dense d{};
    d.nrow = d.d = d.nzmax = static_cast<std::size_t>(v.size());
    d.ncol = 1;
    d.x = v.data();
    d.xtype = CHOLMOD_REAL;
    d.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* u = nullptr;
    cholmod_serial([&] { u = cholmod_solve(system, factor, &d, &common); });
    if (u == nullptr) return false;
    v = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(u->x), v.size());
    cholmod_free_dense(&u, &common);
    return true;
  }
};

bool SeparatedCholesky::Half::analyze(const SparseMatrix& a, Eigen::Index start, int h, const std::vector<int>& part,
                                      const std::vector<int>& col_start, const std::vector<int>& rows,
                                      const std::vector<Eigen::Index>& separator) {
  const std::size_t n = part.size();
  // The interior's own nested dissection, then the separator last.
  std::vector<int> local(n, -1), nodes;
  for (std::size_t j = 0; j < n; ++j)
    if (part[j] == h) {
      local[j] = static_cast<int>(nodes.size());
      nodes.push_back(static_cast<int>(j));
    }
  std::vector<int> sub_start(nodes.size() + 1, 0), sub_rows, order;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    for (int q = col_start[static_cast<std::size_t>(nodes[k])]; q < col_start[static_cast<std::size_t>(nodes[k]) + 1]; ++q)
      if (local[static_cast<std::size_t>(rows[static_cast<std::size_t>(q)])] >= 0)
        sub_rows.push_back(local[static_cast<std::size_t>(rows[static_cast<std::size_t>(q)])]);
    sub_start[k + 1] = static_cast<int>(sub_rows.size());
  }
  if (!metis_node_order(sub_start, sub_rows, order, common)) return false;
  unknown.clear();
  for (const int k : order)
    for (int r = 0; r < 3; ++r) unknown.push_back(3 * static_cast<Eigen::Index>(nodes[static_cast<std::size_t>(k)]) + r);
  interior = static_cast<Eigen::Index>(unknown.size());
  unknown.insert(unknown.end(), separator.begin(), separator.end());
  // M_h's lower triangle, each entry holding (exactly, as a double) its index in a's values.
  const auto* outer = a.outerIndexPtr();
  const auto* inner = a.innerIndexPtr();
  std::vector<Eigen::Index> position(3 * n, -1);
  for (std::size_t i = 0; i < unknown.size(); ++i) position[static_cast<std::size_t>(unknown[i])] = static_cast<Eigen::Index>(i);
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t c = 0; c < unknown.size(); ++c) {
    const Eigen::Index column = start + unknown[c];
    for (auto k = outer[column]; k < outer[column + 1]; ++k) {
      const Eigen::Index r = position[static_cast<std::size_t>(inner[k] - start)];
      if (r >= static_cast<Eigen::Index>(c)) entries.emplace_back(static_cast<int>(r), static_cast<int>(c), static_cast<double>(k));
    }
  }
  const auto size = static_cast<Eigen::Index>(unknown.size());
  m.resize(size, size);
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  source.resize(static_cast<std::size_t>(m.nonZeros()));
  for (Eigen::Index i = 0; i < m.nonZeros(); ++i) source[static_cast<std::size_t>(i)] = static_cast<Eigen::Index>(m.valuePtr()[i]);
  // Analyzed in the order given: supernodal, no fill-reducing permutation, no postorder (the
  // separator must stay last).
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_NATURAL;
  common.postorder = 0;
  common.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse v = view();
  cholmod_serial([&] { factor = cholmod_analyze(&v, &common); });
  if (factor == nullptr || !factor->is_super) return false;
  const int* perm = static_cast<const int*>(factor->Perm);
  for (Eigen::Index i = 0; i < size; ++i)
    if (perm[i] != i) return false;
  numeric.prepare(m, *factor, common);
  return true;
}

SeparatedCholesky::SeparatedCholesky() = default;
SeparatedCholesky::~SeparatedCholesky() = default;

Eigen::Index SeparatedCholesky::half_unknowns(int h) const {
  return halves_[static_cast<std::size_t>(h)] ? halves_[static_cast<std::size_t>(h)]->m.rows() : 0;
}

bool SeparatedCholesky::analyze(const SparseMatrix& a, Eigen::Index start, Eigen::Index size, int threads) {
  start_ = start;
  size_ = size;
  separator_.clear();
  separator_entries_.clear();
  for (auto& h : halves_) h = std::make_unique<Half>();
  if (size % 3 != 0 || size == 0 || !a.isCompressed()) return false;
  const auto n = static_cast<std::size_t>(size / 3);
  std::vector<int> col_start, rows;
  node_graph(a, start, size, col_start, rows);
  std::vector<int> part(n, 0);
  {
    cholmod_sparse g = node_graph_view(col_start, rows);
    const MetisTurn turn;
    if (cholmod_bisect(&g, nullptr, 0, 1, part.data(), &halves_[0]->common) < 0) return false;
  }
  std::array<std::size_t, 3> count{};
  for (const int p : part) {
    if (p < 0 || p > 2) return false;
    ++count[static_cast<std::size_t>(p)];
  }
  // Garment meshes split with about sqrt(n) separator nodes (43 to 65 of 2,100 to 2,200 on
  // solo-dancer's dress); a larger separator makes the dense Schur complement cost more than the
  // halves save.
  const double most_separator = std::min(0.1 * static_cast<double>(n), 3.0 * std::sqrt(static_cast<double>(n)));
  if (count[2] == 0 || 5 * count[0] < n || 5 * count[1] < n || static_cast<double>(count[2]) > most_separator) return false;

  for (std::size_t j = 0; j < n; ++j)
    if (part[j] == 2)
      for (int r = 0; r < 3; ++r) separator_.push_back(3 * static_cast<Eigen::Index>(j) + r);
  // The halves are independent (each its own CHOLMOD workspace, METIS reseeding for each and
  // drawing from the thread's own generator): side by side with two threads.
  // (No one-thread region on one thread: CHOLMOD's own would then be a nested team.)
  std::array<bool, 2> analyzed{};
  auto analyze_half = [&](int h) {
    analyzed[static_cast<std::size_t>(h)] = halves_[static_cast<std::size_t>(h)]->analyze(a, start, h, part, col_start, rows, separator_);
  };
  for_each_index(2, threads >= 2 ? 2 : 1, [&](int64_t h) { analyze_half(static_cast<int>(h)); });
  if (!analyzed[0] || !analyzed[1]) return false;
  const Half& first = *halves_[0];
  for (Eigen::Index c = first.interior; c < first.m.cols(); ++c)
    for (auto k = first.m.outerIndexPtr()[c]; k < first.m.outerIndexPtr()[c + 1]; ++k)
      separator_entries_.push_back({static_cast<int>(first.m.innerIndexPtr()[k] - first.interior), static_cast<int>(c - first.interior),
                                    first.source[static_cast<std::size_t>(k)]});
  return true;
}

bool SeparatedCholesky::factor_half(const SparseMatrix& a, int h) {
  Half& half = *halves_[static_cast<std::size_t>(h)];
  for (std::size_t i = 0; i < half.source.size(); ++i) half.m.valuePtr()[i] = a.valuePtr()[half.source[i]];
  bool factored = false;
  if (half.numeric.prepared_for(*half.factor)) {
    cholmod_serial([&] { factored = half.numeric.factorize(half.m, *half.factor); });
  } else {
    cholmod_sparse view = half.view();
    cholmod_serial([&] { factored = cholmod_factorize(&view, half.factor, &half.common) != 0; });
    factored = factored && half.common.status == CHOLMOD_OK;
  }
  if (!factored || half.factor->minor != half.factor->n) return false;
  // L_hS from the supernodes holding the separator's columns (the last ones).
  const auto s = static_cast<Eigen::Index>(separator_.size());
  half.separator_factor.setZero(s, s);
  const int* super = static_cast<const int*>(half.factor->super);
  const int* pi = static_cast<const int*>(half.factor->pi);
  const int* px = static_cast<const int*>(half.factor->px);
  const int* ls = static_cast<const int*>(half.factor->s);
  const double* lx = static_cast<const double*>(half.factor->x);
  for (std::size_t sn = 0; sn < half.factor->nsuper; ++sn) {
    const int k1 = super[sn], k2 = super[sn + 1];
    if (k2 <= half.interior) continue;
    const int nsrow = pi[sn + 1] - pi[sn];
    for (int j = 0; j < k2 - k1; ++j) {
      if (k1 + j < half.interior) continue;
      for (int i = j; i < nsrow; ++i)
        half.separator_factor(ls[pi[sn] + i] - half.interior, k1 + j - half.interior) = lx[px[sn] + i + static_cast<std::ptrdiff_t>(j) * nsrow];
    }
  }
  half.separator_product.noalias() = half.separator_factor.triangularView<Eigen::Lower>() * half.separator_factor.transpose();
  return true;
}

SolveReport SeparatedCholesky::solve(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  x.resize(size_);
  if (!forward_half(b, 0) || !forward_half(b, 1) || !solve_separator(a, b) || !back_half(0, x) || !back_half(1, x)) return {};
  return finish(a, b, x);
}

bool SeparatedCholesky::forward_half(const Eigen::VectorXd& b, int h) {
  Half& half = *halves_[static_cast<std::size_t>(h)];
  half.y.setZero(half.m.rows());
  for (Eigen::Index i = 0; i < half.interior; ++i) half.y[i] = b[half.unknown[static_cast<std::size_t>(i)]];
  return half.substitute(CHOLMOD_L, half.y);
}

bool SeparatedCholesky::solve_separator(const SparseMatrix& a, const Eigen::VectorXd& b) {
  const auto s = static_cast<Eigen::Index>(separator_.size());
  Eigen::MatrixXd schur = halves_[0]->separator_product + halves_[1]->separator_product;
  for (const Entry& e : separator_entries_) {
    schur(e.row, e.col) -= a.valuePtr()[e.source];
    if (e.row != e.col) schur(e.col, e.row) -= a.valuePtr()[e.source];
  }
  const Eigen::LLT<Eigen::MatrixXd> schur_factor(schur);
  if (schur_factor.info() != Eigen::Success) return false;
  // The forward substitutions' separator parts are y_hS = -L_hS^-1 g_h.
  Eigen::VectorXd separator_rhs(s);
  for (Eigen::Index k = 0; k < s; ++k) separator_rhs[k] = b[separator_[static_cast<std::size_t>(k)]];
  for (const auto& half : halves_) separator_rhs.noalias() += half->separator_factor.triangularView<Eigen::Lower>() * half->y.tail(s);
  separator_x_ = schur_factor.solve(separator_rhs);
  return true;
}

bool SeparatedCholesky::back_half(int h, Eigen::VectorXd& x) {
  Half& half = *halves_[static_cast<std::size_t>(h)];
  const auto s = static_cast<Eigen::Index>(separator_.size());
  half.y.tail(s).noalias() = half.separator_factor.transpose().triangularView<Eigen::Upper>() * separator_x_;
  if (!half.substitute(CHOLMOD_Lt, half.y)) return false;
  for (Eigen::Index i = 0; i < half.interior; ++i) x[half.unknown[static_cast<std::size_t>(i)]] = half.y[i];
  return true;
}

SolveReport SeparatedCholesky::finish(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  SolveReport report;
  for (std::size_t k = 0; k < separator_.size(); ++k) x[separator_[k]] = separator_x_[static_cast<Eigen::Index>(k)];
  // |A x - b| over the range's columns (both triangles stored: a row is its column).
  Eigen::VectorXd r = -b;
  const auto* outer = a.outerIndexPtr();
  const auto* inner = a.innerIndexPtr();
  for (Eigen::Index j = 0; j < size_; ++j)
    for (auto k = outer[start_ + j]; k < outer[start_ + j + 1]; ++k) r[inner[k] - start_] += a.valuePtr()[k] * x[j];
  const double nb = b.norm();
  report.residual = nb > 0 ? r.norm() / nb : r.norm();
  report.iterations = 1;
  report.factorizations = 1;
  report.ok = x.allFinite() && report.residual < 1e-6;
  return report;
}

}  // namespace vdc
