// Left-looking supernodal Cholesky (Ng and Peyton 1993) on CHOLMOD's symbolic factor.
#include "physics/supernodal_cholesky.hpp"

#include <algorithm>

namespace vdc {

// The Fortran BLAS and LAPACK entry points CHOLMOD itself calls (Debian's OpenBLAS behind
// libblas.so.3 and liblapack.so.3), with 32-bit integers as Debian's CHOLMOD uses them.
extern "C" {
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a, const int* lda,
            const double* beta, double* c, const int* ldc);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* b, const int* ldb, const double* beta, double* c, const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n, const double* alpha,
            const double* a, const int* lda, double* b, const int* ldb);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
}

bool SupernodalCholesky::prepare(const SparseMatrix& a, cholmod_factor& factor, cholmod_common& common) {
  prepared_ = nullptr;
  entries_.clear();
  const auto n = static_cast<std::size_t>(factor.n);
  if (!factor.is_super || factor.itype != CHOLMOD_INT || factor.dtype != CHOLMOD_DOUBLE || a.rows() != a.cols() ||
      static_cast<std::size_t>(a.rows()) != n)
    return false;
  if (factor.xtype == CHOLMOD_PATTERN && !cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, &factor, &common)) return false;
  if (factor.xtype != CHOLMOD_REAL || !factor.is_ll) return false;
  const int* super = static_cast<const int*>(factor.super);
  const int* pi = static_cast<const int*>(factor.pi);
  const int* px = static_cast<const int*>(factor.px);
  const int* ls = static_cast<const int*>(factor.s);
  const int* perm = static_cast<const int*>(factor.Perm);
  const auto nsuper = static_cast<std::size_t>(factor.nsuper);
  supernode_of_.assign(n, 0);
  for (std::size_t s = 0; s < nsuper; ++s)
    for (int k = super[s]; k < super[s + 1]; ++k) supernode_of_[static_cast<std::size_t>(k)] = static_cast<int>(s);
  std::vector<int> position(n);  // original unknown -> its column in L
  for (std::size_t k = 0; k < n; ++k) position[static_cast<std::size_t>(perm != nullptr ? perm[k] : static_cast<int>(k))] = static_cast<int>(k);
  const auto* outer = a.outerIndexPtr();
  const auto* inner = a.innerIndexPtr();
  entries_.reserve(static_cast<std::size_t>(a.nonZeros()) / 2 + n);
  for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
    const auto end = a.isCompressed() ? outer[j + 1] : outer[j] + a.innerNonZeroPtr()[j];
    for (auto k = outer[j]; k < end; ++k) {
      if (inner[k] < j) continue;  // the lower triangle only
      const int pr = position[static_cast<std::size_t>(inner[k])], pc = position[static_cast<std::size_t>(j)];
      const int row = std::max(pr, pc), col = std::min(pr, pc);
      const auto s = static_cast<std::size_t>(supernode_of_[static_cast<std::size_t>(col)]);
      const int* first = ls + pi[s];
      const int* last = ls + pi[s + 1];
      const int* at = std::lower_bound(first, last, row);
      if (at == last || *at != row) return false;
      const auto nsrow = static_cast<std::size_t>(pi[s + 1] - pi[s]);
      entries_.push_back({static_cast<std::size_t>(k), static_cast<std::size_t>(px[s]) +
                                                           static_cast<std::size_t>(col - super[s]) * nsrow +
                                                           static_cast<std::size_t>(at - first)});
    }
  }
  // By target, so that each supernode's entries are one run, loaded with it (load_supernode).
  // (Already so without a fill-reducing permutation: a's columns in order.)
  auto by_target = [](const Entry& x, const Entry& y) { return x.target < y.target; };
  if (!std::is_sorted(entries_.begin(), entries_.end(), by_target)) std::sort(entries_.begin(), entries_.end(), by_target);
  entry_start_.assign(nsuper + 1, 0);
  for (std::size_t s = 0, e = 0; s < nsuper; ++s) {
    while (e < entries_.size() && entries_[e].target < static_cast<std::size_t>(px[s + 1])) ++e;
    entry_start_[s + 1] = e;
  }
  // What no supernode holds (if anything) stays zero, as cholmod_factorize leaves it.
  std::fill(static_cast<double*>(factor.x), static_cast<double*>(factor.x) + factor.xsize, 0.0);
  map_.assign(n, -1);
  relative_map_.assign(n, 0);
  head_.assign(nsuper, -1);
  next_.assign(nsuper, -1);
  lpos_.assign(nsuper, 0);
  update_.assign(std::max<std::size_t>(factor.maxcsize, 1), 0.0);
  prepared_ = &factor;
  return true;
}

bool SupernodalCholesky::factorize(const SparseMatrix& a, cholmod_factor& factor) {
  if (!prepared_for(factor)) return false;
  const int* super = static_cast<const int*>(factor.super);
  const int* pi = static_cast<const int*>(factor.pi);
  const int* px = static_cast<const int*>(factor.px);
  const int* ls = static_cast<const int*>(factor.s);
  double* lx = static_cast<double*>(factor.x);
  const double* values = a.valuePtr();
  // Supernode s's columns: zero but for a's entries, loaded just before s is factored (no
  // descendant writes them earlier), while they stay in cache for its updates.
  auto load_supernode = [&](int s) {
    const auto su = static_cast<std::size_t>(s);
    std::fill(lx + px[s], lx + px[s + 1], 0.0);
    for (std::size_t e = entry_start_[su]; e < entry_start_[su + 1]; ++e) lx[entries_[e].target] = values[entries_[e].source];
  };
  const double one = 1.0, zero = 0.0;
  const auto nsuper = static_cast<int>(factor.nsuper);
  std::fill(head_.begin(), head_.end(), -1);
  for (int s = 0; s < nsuper; ++s) {
    load_supernode(s);
    const int k1 = super[s], k2 = super[s + 1], nscol = k2 - k1;
    const int psi = pi[s], nsrow = pi[s + 1] - psi, psx = px[s];
    for (int k = 0; k < nsrow; ++k) map_[static_cast<std::size_t>(ls[psi + k])] = k;
    // Each descendant d updates s with its rows from k1 on: C = L_d(rows >= k1) L_d(rows in s)^T,
    // subtracted from s's columns; then d waits for the supernode of its next row.
    for (int d = head_[static_cast<std::size_t>(s)], after = -1; d != -1; d = after) {
      const auto du = static_cast<std::size_t>(d);
      const int ndcol = super[d + 1] - super[d];
      const int pdi = pi[d], pdend = pi[d + 1];
      const int ndrow = pdend - pdi;
      const int pdi1 = pdi + lpos_[du], pdx1 = px[d] + lpos_[du];
      int pdi2 = pdi1;
      while (pdi2 < pdend && ls[pdi2] < k2) ++pdi2;
      const int ndrow1 = pdi2 - pdi1, ndrow2 = pdend - pdi1, ndrow3 = ndrow2 - ndrow1;
      if (update_.size() < static_cast<std::size_t>(ndrow1) * static_cast<std::size_t>(ndrow2))
        update_.resize(static_cast<std::size_t>(ndrow1) * static_cast<std::size_t>(ndrow2));
      double* c = update_.data();
      dsyrk_("L", "N", &ndrow1, &ndcol, &one, lx + pdx1, &ndrow, &zero, c, &ndrow2);
      if (ndrow3 > 0) dgemm_("N", "C", &ndrow3, &ndrow1, &ndcol, &one, lx + pdx1 + ndrow1, &ndrow, lx + pdx1, &ndrow, &zero, c + ndrow1, &ndrow2);
      for (int i = 0; i < ndrow2; ++i) relative_map_[static_cast<std::size_t>(i)] = map_[static_cast<std::size_t>(ls[pdi1 + i])];
      for (int j = 0; j < ndrow1; ++j) {
        double* column = lx + psx + static_cast<std::ptrdiff_t>(relative_map_[static_cast<std::size_t>(j)]) * nsrow;
        const double* cj = c + static_cast<std::ptrdiff_t>(ndrow2) * j;
        for (int i = j; i < ndrow2; ++i) column[relative_map_[static_cast<std::size_t>(i)]] -= cj[i];
      }
      after = next_[du];
      lpos_[du] = pdi2 - pdi;
      if (lpos_[du] < ndrow) {
        const auto ancestor = static_cast<std::size_t>(supernode_of_[static_cast<std::size_t>(ls[pdi2])]);
        next_[du] = head_[ancestor];
        head_[ancestor] = d;
      }
    }
    int info = 0;
    dpotrf_("L", &nscol, lx + psx, &nsrow, &info);
    if (info != 0) {
      for (int later = s + 1; later < nsuper; ++later) load_supernode(later);  // as cholmod_factorize leaves them
      factor.minor = static_cast<std::size_t>(k1 + info - 1);
      return false;
    }
    const int below = nsrow - nscol;
    if (below > 0) {
      dtrsm_("R", "L", "C", "N", &below, &nscol, &one, lx + psx, &nsrow, lx + psx + nscol, &nsrow);
      const auto parent = static_cast<std::size_t>(supernode_of_[static_cast<std::size_t>(ls[psi + nscol])]);
      lpos_[static_cast<std::size_t>(s)] = nscol;
      next_[static_cast<std::size_t>(s)] = head_[parent];
      head_[parent] = s;
    }
    head_[static_cast<std::size_t>(s)] = -1;
  }
  factor.minor = factor.n;
  return true;
}

}  // namespace vdc
