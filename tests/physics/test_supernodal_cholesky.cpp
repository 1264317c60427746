// The supernodal factorization done outside CHOLMOD: the same factor as cholmod_factorize, bit
// for bit, on sheets and random sparse systems under three orderings and two amalgamations
// (CHOLMOD's and a three times wider one); a matrix that is not positive definite refused at
// the column CHOLMOD names; a matrix whose pattern the analysis does not cover left to CHOLMOD.
#include <gtest/gtest.h>

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <array>
#include <cstring>
#include <random>
#include <vector>

#include "grid_system.hpp"
#include "physics/cholmod_use.hpp"
#include "physics/supernodal_cholesky.hpp"

namespace vdc {
namespace {

// A symmetric positive-definite system of `nodes` nodes, 3 unknowns each, coupled along random
// edges (about `degree` a node) by random 3x3 blocks, the diagonal made dominant.
SparseMatrix random_system(int nodes, int degree, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> pick(0, nodes - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> row_sum(static_cast<std::size_t>(3 * nodes), 0.0);
  for (int e = 0; e < nodes * degree / 2; ++e) {
    const int p = pick(random), q = pick(random);
    if (p == q) continue;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const double v = value(random);
        t.emplace_back(3 * p + r, 3 * q + c, v);
        t.emplace_back(3 * q + c, 3 * p + r, v);
        row_sum[static_cast<std::size_t>(3 * p + r)] += std::abs(v);
        row_sum[static_cast<std::size_t>(3 * q + c)] += std::abs(v);
      }
  }
  for (int k = 0; k < 3 * nodes; ++k) t.emplace_back(k, k, 1.0 + row_sum[static_cast<std::size_t>(k)] + 0.5 * value(random));
  SparseMatrix a(3 * nodes, 3 * nodes);
  a.setFromTriplets(t.begin(), t.end());  // repeated edges sum: still symmetric and dominant
  a.makeCompressed();
  return a;
}

struct Cholmod {
  cholmod_common common{};
  Cholmod() {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.final_asis = 1;
  }
  ~Cholmod() { cholmod_finish(&common); }
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;
};

enum class Ordering { Natural, Amd, Metis };

// CHOLMOD's view of a's lower triangle (as the solvers pass it).
cholmod_sparse lower_view(const SparseMatrix& a) { return Eigen::viewAsCholmod(a.selfadjointView<Eigen::Lower>()); }

// CHOLMOD's analysis of a under `ordering`, then its factorization and SupernodalCholesky's of
// a copy of the analysis: the two factors' values compared bit for bit.
void expect_same_factor(const SparseMatrix& a, Ordering ordering, bool amalgamated, const char* what) {
  SCOPED_TRACE(what);
  Cholmod cm;
  cm.common.nmethods = 1;
  cm.common.method[0].ordering = ordering == Ordering::Natural ? CHOLMOD_NATURAL : ordering == Ordering::Amd ? CHOLMOD_AMD : CHOLMOD_METIS;
  if (amalgamated) {  // supernodes amalgamated three times as far as CHOLMOD's defaults: fewer, larger
    const std::array<std::size_t, 3> nrelax{12, 48, 144};
    const std::array<double, 3> zrelax{1.05, 0.25, 0.125};
    std::copy(nrelax.begin(), nrelax.end(), cm.common.nrelax);
    std::copy(zrelax.begin(), zrelax.end(), cm.common.zrelax);
  }
  cholmod_sparse view = lower_view(a);
  cholmod_factor* theirs = nullptr;
  cholmod_serial([&] { theirs = cholmod_analyze(&view, &cm.common); });
  ASSERT_NE(theirs, nullptr);
  ASSERT_TRUE(theirs->is_super);
  cholmod_factor* ours = cholmod_copy_factor(theirs, &cm.common);
  ASSERT_NE(ours, nullptr);
  SupernodalCholesky numeric;
  ASSERT_TRUE(numeric.prepare(a, *ours, cm.common));
  int factored = 0;
  bool ours_factored = false;
  cholmod_serial([&] {
    factored = cholmod_factorize(&view, theirs, &cm.common);
    ours_factored = numeric.factorize(a, *ours);
  });
  ASSERT_TRUE(factored && theirs->minor == theirs->n);
  ASSERT_TRUE(ours_factored);
  EXPECT_EQ(ours->minor, ours->n);
  ASSERT_EQ(ours->xsize, theirs->xsize);
  EXPECT_GT(theirs->nsuper, 10u);
  const auto* x = static_cast<const double*>(ours->x);
  const auto* y = static_cast<const double*>(theirs->x);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < theirs->xsize; ++k) differ += std::memcmp(x + k, y + k, sizeof(double)) != 0;
  EXPECT_EQ(differ, 0u) << "of " << theirs->xsize << " values";
  // A second factorization with the same preparation (the solvers factor eight times a frame).
  SparseMatrix b = a;
  for (Eigen::Index k = 0; k < b.rows(); ++k) b.coeffRef(k, k) *= 1.5;
  cholmod_sparse view_b = lower_view(b);
  cholmod_serial([&] {
    factored = cholmod_factorize(&view_b, theirs, &cm.common);
    ours_factored = numeric.factorize(b, *ours);
  });
  ASSERT_TRUE(factored && ours_factored);
  differ = 0;
  for (std::size_t k = 0; k < theirs->xsize; ++k) differ += std::memcmp(x + k, y + k, sizeof(double)) != 0;
  EXPECT_EQ(differ, 0u) << "refactored, of " << theirs->xsize << " values";
  cholmod_free_factor(&theirs, &cm.common);
  cholmod_free_factor(&ours, &cm.common);
}

TEST(SupernodalCholesky, FactorsAsCholmodBitForBit) {
  SparseMatrix sheet = grid_system(30);
  sheet.makeCompressed();
  for (const Ordering o : {Ordering::Natural, Ordering::Amd, Ordering::Metis}) {
    expect_same_factor(sheet, o, false, "sheet 30 x 30");
    expect_same_factor(sheet, o, true, "sheet 30 x 30, amalgamated");
  }
  for (const unsigned seed : {1u, 2u, 3u}) {
    const SparseMatrix a = random_system(400, 5, seed);
    expect_same_factor(a, Ordering::Metis, true, "random, amalgamated");
    expect_same_factor(a, Ordering::Amd, false, "random");
  }
}

// The diagonal of one node made negative: both refuse it, at the same column of L.
TEST(SupernodalCholesky, RefusesAMatrixThatIsNotPositiveDefiniteWhereCholmodDoes) {
  SparseMatrix a = grid_system(20);
  a.makeCompressed();
  a.coeffRef(3 * 210 + 1, 3 * 210 + 1) = -4.0;
  Cholmod cm;
  cholmod_sparse view = lower_view(a);
  cholmod_factor* theirs = cholmod_analyze(&view, &cm.common);
  ASSERT_NE(theirs, nullptr);
  cholmod_factor* ours = cholmod_copy_factor(theirs, &cm.common);
  SupernodalCholesky numeric;
  ASSERT_TRUE(numeric.prepare(a, *ours, cm.common));
  bool ours_factored = true;
  cholmod_serial([&] {
    cholmod_factorize(&view, theirs, &cm.common);
    ours_factored = numeric.factorize(a, *ours);
  });
  EXPECT_FALSE(ours_factored);
  EXPECT_LT(theirs->minor, theirs->n);
  EXPECT_EQ(ours->minor, theirs->minor);
  cholmod_free_factor(&theirs, &cm.common);
  cholmod_free_factor(&ours, &cm.common);
}

// An entry the analysed pattern does not hold (and so no place in L): not prepared, nothing
// factored.
TEST(SupernodalCholesky, LeavesToCholmodAPatternItsAnalysisDoesNotCover) {
  SparseMatrix a = grid_system(10);
  a.makeCompressed();
  Cholmod cm;
  cm.common.nmethods = 1;
  cm.common.method[0].ordering = CHOLMOD_NATURAL;
  cholmod_sparse view = lower_view(a);
  cholmod_factor* factor = cholmod_analyze(&view, &cm.common);
  ASSERT_NE(factor, nullptr);
  SparseMatrix wider = a;
  wider.coeffRef(a.rows() - 1, 0) = 0.5;  // couples the first and last nodes
  wider.coeffRef(0, a.rows() - 1) = 0.5;
  wider.makeCompressed();
  SupernodalCholesky numeric;
  EXPECT_FALSE(numeric.prepare(wider, *factor, cm.common));
  EXPECT_FALSE(numeric.prepared_for(*factor));
  EXPECT_FALSE(numeric.factorize(wider, *factor));
  EXPECT_TRUE(numeric.prepare(a, *factor, cm.common));
  cholmod_free_factor(&factor, &cm.common);
}

}  // namespace
}  // namespace vdc
