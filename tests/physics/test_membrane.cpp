// Membrane energy: finite-difference gradient and Hessian, rigid invariance, PSD projection; the
// compression factor of elements too coarse for their wrinkles against hand-computed energies.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "physics/membrane.hpp"
#include "physics/psd.hpp"
#include "support/finite_difference.hpp"

namespace vdc {
namespace {

struct RandomMembrane {
  TriStencil x;
  MembraneElement m;
};

RandomMembrane random_membrane(std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  // A well-shaped rest triangle of about 5 cm, and a random affine map plus noise to world.
  Vec2 u0(0, 0), u1(0.05 + 0.01 * U(rng), 0.01 * U(rng)), u2(0.02 + 0.01 * U(rng), 0.045 + 0.01 * U(rng));
  MembraneStiffness k{4000 + 1000 * U(rng), 300 + 100 * U(rng), 3000 + 1000 * U(rng), 200 + 100 * U(rng)};
  RandomMembrane r;
  r.m = make_membrane_element(u0, u1, u2, k);
  Mat32 a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) a(i, j) = (i == j ? 1.0 : 0.0) + 0.3 * U(rng);
  Vec3 t(U(rng), U(rng), U(rng));
  std::array<Vec2, 3> u{u0, u1, u2};
  for (int i = 0; i < 3; ++i)
    r.x[static_cast<std::size_t>(i)] = a * u[static_cast<std::size_t>(i)] + t + 0.005 * Vec3(U(rng), U(rng), U(rng));
  return r;
}

VecN<9> flatten(const TriStencil& x) {
  VecN<9> q;
  for (int i = 0; i < 3; ++i) q.segment<3>(3 * i) = x[static_cast<std::size_t>(i)];
  return q;
}

TriStencil unflatten(const VecN<9>& q) { return {q.segment<3>(0), q.segment<3>(3), q.segment<3>(6)}; }

TEST(Membrane, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    auto [x, m] = random_membrane(rng);
    const VecN<9> g = membrane_gradient(x, m);
    const Eigen::VectorXd fd =
        test::central_differences([&](const VecN<9>& q) { return membrane_energy(unflatten(q), m); }, flatten(x), 1e-7);
    EXPECT_LT((g - fd).norm() / g.norm(), 1e-5) << "trial " << trial;
  }
}

TEST(Membrane, HessianMatchesFiniteDifferences) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 50; ++trial) {
    auto [x, m] = random_membrane(rng);
    const MatN<9> h = membrane_hessian(x, m);
    const Eigen::MatrixXd fd =
        test::central_differences([&](const VecN<9>& q) { return membrane_gradient(unflatten(q), m); }, flatten(x), 1e-6);
    EXPECT_LT((h - fd).norm() / h.norm(), 1e-4) << "trial " << trial;
  }
}

TEST(Membrane, RigidMotionHasNoEnergyOrForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    auto [x, m] = random_membrane(rng);
    Mat3 rot = Eigen::Quaterniond(U(rng), U(rng), U(rng), U(rng)).normalized().toRotationMatrix();
    Vec3 t(U(rng), U(rng), U(rng));
    // Rest shape placed by a rotation and translation: u -> R (u, 0) + t.
    Mat2 du = m.du_inv.inverse();
    std::array<Vec2, 3> u{Vec2::Zero(), du.col(0), du.col(1)};
    TriStencil rigid;
    for (int i = 0; i < 3; ++i) rigid[static_cast<std::size_t>(i)] = rot * Vec3(u[static_cast<std::size_t>(i)].x(), u[static_cast<std::size_t>(i)].y(), 0) + t;
    EXPECT_NEAR(membrane_energy(rigid, m), 0.0, 1e-15);
    // Forces scale like stiffness * length (4000 N/m * 0.05 m = 200 N): 1e-9 N is rounding.
    EXPECT_LT(membrane_gradient(rigid, m).norm(), 1e-9);
  }
}

TEST(Membrane, ProjectedHessianIsPsdAndExactUnderTension) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 50; ++trial) {
    auto [x, m] = random_membrane(rng);
    MatN<9> psd = membrane_hessian_psd(x, m);
    double scale = psd.norm();
    EXPECT_GT(min_eigenvalue<9>(psd), -1e-10 * scale) << "trial " << trial;
    // Stretched 10% in every direction: stress is positive definite, nothing to clamp.
    Mat2 du = m.du_inv.inverse();
    std::array<Vec2, 3> u{Vec2::Zero(), du.col(0), du.col(1)};
    TriStencil stretched;
    for (int i = 0; i < 3; ++i) stretched[static_cast<std::size_t>(i)] = 1.1 * Vec3(u[static_cast<std::size_t>(i)].x(), u[static_cast<std::size_t>(i)].y(), 0.0);
    EXPECT_LT((membrane_hessian_psd(stretched, m) - membrane_hessian(stretched, m)).norm(), 1e-12 * membrane_hessian(stretched, m).norm());
  }
}

TEST(Membrane, ProjectionIsNeededInCompression) {
  // Compressed 20%: the exact Hessian is indefinite, the projected one is not.
  MembraneElement m = make_membrane_element(Vec2(0, 0), Vec2(0.05, 0), Vec2(0, 0.05), {4000, 800, 4000, 300});
  TriStencil x{Vec3(0, 0, 0), Vec3(0.04, 0, 0), Vec3(0, 0.04, 0)};
  EXPECT_LT(min_eigenvalue<9>(membrane_hessian(x, m)), -1.0);
  EXPECT_GT(min_eigenvalue<9>(membrane_hessian_psd(x, m)), -1e-9);
}

TEST(Membrane, UniaxialStretchMatchesAnalyticEnergy) {
  // Stretch by s along warp only: E11 = (s^2 - 1)/2, others 0, W = A c11 E11^2 / 2.
  MembraneStiffness k{5000, 0, 3000, 300};
  MembraneElement m = make_membrane_element(Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1), k);
  const double s = 1.05;
  TriStencil x{Vec3(0, 0, 0), Vec3(0.1 * s, 0, 0), Vec3(0, 0.1, 0)};
  double e11 = 0.5 * (s * s - 1);
  EXPECT_NEAR(membrane_energy(x, m), 0.005 * 0.5 * 5000 * e11 * e11, 1e-15);
}

// Shrinks the world triangle by up to `most` (a fraction) along a random, mostly in-plane
// direction.
void squeeze_randomly(TriStencil& x, std::mt19937& rng, double most) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const Vec3 d = Vec3(U(rng), U(rng), 0.2 * U(rng)).normalized();
  const double shrink = most * (0.5 + 0.5 * U(rng));
  for (auto& p : x) p -= shrink * d * d.dot(p - x[0]);
}

// Random elements as above, with a compression factor, deformed so that warp or weft (or both)
// are compressed in most trials: the scaled energy's gradient and Hessian match finite
// differences within each piece of its piecewise strain.
TEST(Membrane, CompressionFactorKeepsGradientAndHessianExact) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int compressed = 0;
  for (int trial = 0; trial < 50; ++trial) {
    auto [x, m] = random_membrane(rng);
    m.compression = 0.05 + 0.9 * (0.5 + 0.5 * U(rng));
    squeeze_randomly(x, rng, 0.15);
    const Mat2 e = green_strain(deformation_gradient(x, m));
    // Finite differences must not straddle a kink of the piecewise strain.
    if (std::abs(e(0, 0)) < 1e-4 || std::abs(e(1, 1)) < 1e-4) continue;
    compressed += e(0, 0) < 0 || e(1, 1) < 0;
    VecN<9> g = membrane_gradient(x, m), fd;
    MatN<9> h = membrane_hessian(x, m), fdh;
    VecN<9> q = flatten(x);
    for (int i = 0; i < 9; ++i) {
      VecN<9> qp = q, qm = q;
      qp[i] += 1e-7;
      qm[i] -= 1e-7;
      fd[i] = (membrane_energy(unflatten(qp), m) - membrane_energy(unflatten(qm), m)) / 2e-7;
      qp = q;
      qm = q;
      qp[i] += 1e-6;
      qm[i] -= 1e-6;
      fdh.col(i) = (membrane_gradient(unflatten(qp), m) - membrane_gradient(unflatten(qm), m)) / 2e-6;
    }
    EXPECT_LT((g - fd).norm() / g.norm(), 1e-5) << "trial " << trial;
    EXPECT_LT((h - fdh).norm() / h.norm(), 1e-4) << "trial " << trial;
    const MembraneEval eval = membrane_eval(x, m);
    EXPECT_NEAR(eval.energy, membrane_energy(x, m), 1e-15);
    EXPECT_LT((eval.gradient - g).norm(), 1e-12 * g.norm());
    EXPECT_LT((eval.hessian - membrane_hessian_psd(x, m)).norm(), 1e-12 * h.norm());
    EXPECT_GT(min_eigenvalue<9>(eval.hessian), -1e-10 * eval.hessian.norm()) << "trial " << trial;
  }
  EXPECT_GE(compressed, 30);
}

// Warp compressed by 10% and weft stretched by 5% on a right triangle: psi of (a E11, E22), by
// hand; in tension alone the factor changes nothing; a factor of 1 is the plain element.
TEST(Membrane, CompressionFactorScalesOnlyCompressiveWarpAndWeftStrain) {
  const MembraneStiffness k{5000, 700, 3500, 300};
  const double a = 0.2;
  const MembraneElement plain = make_membrane_element(Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1), k);
  const MembraneElement coarse = make_membrane_element(Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1), k, a);
  const double e11 = 0.5 * (0.9 * 0.9 - 1), e22 = 0.5 * (1.05 * 1.05 - 1);
  const TriStencil x{Vec3(0, 0, 0), Vec3(0.09, 0, 0), Vec3(0, 0.105, 0)};
  const double area = 0.005;
  EXPECT_NEAR(membrane_energy(x, coarse), area * 0.5 * (k.c11 * a * a * e11 * e11 + 2 * k.c12 * a * e11 * e22 + k.c22 * e22 * e22), 1e-15);
  EXPECT_NEAR(membrane_energy(x, plain), area * 0.5 * (k.c11 * e11 * e11 + 2 * k.c12 * e11 * e22 + k.c22 * e22 * e22), 1e-15);
  // Stretched and sheared, nothing compressed: identical to the plain element, bit for bit.
  const TriStencil taut{Vec3(0, 0, 0), Vec3(0.104, 0.003, 0), Vec3(0.002, 0.102, 0.001)};
  EXPECT_EQ(membrane_energy(taut, coarse), membrane_energy(taut, plain));
  EXPECT_EQ(membrane_gradient(taut, coarse), membrane_gradient(taut, plain));
  EXPECT_EQ(membrane_eval(taut, coarse).hessian, membrane_eval(taut, plain).hessian);
  // Node 1 is pulled along warp by A F S g_1 with S11 = dpsi/dE11 of the scaled energy.
  const VecN<9> g = membrane_gradient(x, coarse);
  const double s11 = a * (k.c11 * a * e11 + k.c12 * e22);  // dpsi/dE11
  EXPECT_NEAR(g[3], area * 0.9 * s11 / 0.1, 1e-12);  // node 1's x force: A F S g_1, g_1 = (1/0.1, 0)
}

// A coarse element that remembers the gathering it was made with (warp -0.05): compressed less
// than that, the compression factor alone (bit for bit the element without the memory); beyond
// it, the strain psi sees continues with the gathering factor, by hand; continuous at the
// gathered strain; stretched, the plain material.
TEST(Membrane, GatheringBeyondWhatTheElementWasMadeWithMeetsTheSteeperFactor) {
  const MembraneStiffness k{5000, 700, 3500, 300};
  const double a = 0.2, g = 0.3, made = -0.05;
  const MembraneElement soft = make_membrane_element(Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1), k, a);
  MembraneElement kept = soft;
  kept.gathered = Vec2(made, 0);
  kept.gathering = g;
  const double area = 0.005;
  // Warp 0.9, weft 1.05: E11 = -0.095 beyond the gathered -0.05, E22 = 0.05125 stretched.
  const double e11 = 0.5 * (0.9 * 0.9 - 1), e22 = 0.5 * (1.05 * 1.05 - 1);
  const double seen11 = a * made + g * (e11 - made);  // -0.01 - 0.0135
  EXPECT_NEAR(seen11, -0.0235, 1e-15);
  const TriStencil beyond{Vec3(0, 0, 0), Vec3(0.09, 0, 0), Vec3(0, 0.105, 0)};
  EXPECT_NEAR(membrane_energy(beyond, kept), area * 0.5 * (k.c11 * seen11 * seen11 + 2 * k.c12 * seen11 * e22 + k.c22 * e22 * e22), 1e-15);
  // Node 1's warp force: A F S g_1 with S11 = dpsi/dE11 = g (c11 seen11 + c12 E22).
  EXPECT_NEAR(membrane_gradient(beyond, kept)[3], area * 0.9 * g * (k.c11 * seen11 + k.c12 * e22) / 0.1, 1e-12);
  // Warp 0.98 (E11 = -0.0198, within the gathering): the compression factor alone.
  const TriStencil within{Vec3(0, 0, 0), Vec3(0.098, 0, 0), Vec3(0, 0.105, 0)};
  EXPECT_EQ(membrane_energy(within, kept), membrane_energy(within, soft));
  EXPECT_EQ(membrane_gradient(within, kept), membrane_gradient(within, soft));
  // Continuous where the pieces meet: across E11 = -0.05 (2e-9 of warp stretch apart) the energy
  // changes by its slope times the step (dW/ds about 0.05 J), where a jump would be of W itself.
  const double at = std::sqrt(1 + 2 * made);
  const auto warp = [](double s) { return TriStencil{Vec3(0, 0, 0), Vec3(0.1 * s, 0, 0), Vec3(0, 0.1, 0)}; };
  const double below = membrane_energy(warp(at - 1e-9), kept), above = membrane_energy(warp(at + 1e-9), kept);
  EXPECT_NEAR(below, above, 1e-6 * above);
  EXPECT_NEAR(0.5 * (below + above), area * 0.5 * k.c11 * (a * made) * (a * made), 1e-6 * above);
  // Without the compression law (factor 1) nothing is gathered: the plain material.
  MembraneElement plain = make_membrane_element(Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1), k);
  const double plain_energy = membrane_energy(beyond, plain);
  plain.gathered = Vec2(made, 0);
  plain.gathering = g;
  EXPECT_EQ(membrane_energy(beyond, plain), plain_energy);
}

// Random coarse elements with a gathered strain on either side of their compressed warp and
// weft: gradient and Hessian match finite differences in every piece.
TEST(Membrane, GatheredStrainKeepsGradientAndHessianExact) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int beyond = 0;
  for (int trial = 0; trial < 60; ++trial) {
    auto [x, m] = random_membrane(rng);
    m.compression = 0.05 + 0.5 * (0.5 + 0.5 * U(rng));
    m.gathering = 0.2 + 0.6 * (0.5 + 0.5 * U(rng));
    m.gathered = Vec2(-0.08 * (0.5 + 0.5 * U(rng)), -0.08 * (0.5 + 0.5 * U(rng)));
    squeeze_randomly(x, rng, 0.2);
    const Mat2 e = green_strain(deformation_gradient(x, m));
    bool near_kink = false;
    for (int i = 0; i < 2; ++i) near_kink |= std::abs(e(i, i)) < 1e-4 || std::abs(e(i, i) - m.gathered[i]) < 1e-4;
    if (near_kink) continue;
    beyond += e(0, 0) < m.gathered[0] || e(1, 1) < m.gathered[1];
    const VecN<9> q = flatten(x);
    const Eigen::VectorXd fd = test::central_differences([&](const VecN<9>& p) { return membrane_energy(unflatten(p), m); }, q, 1e-7);
    const Eigen::MatrixXd fdh =
        test::central_differences([&](const VecN<9>& p) { return VecN<9>(membrane_gradient(unflatten(p), m)); }, q, 1e-6);
    const VecN<9> grad = membrane_gradient(x, m);
    const MatN<9> hess = membrane_hessian(x, m);
    EXPECT_LT((grad - fd).norm() / grad.norm(), 1e-5) << "trial " << trial;
    EXPECT_LT((hess - fdh).norm() / hess.norm(), 1e-4) << "trial " << trial;
    EXPECT_GT(min_eigenvalue<9>(membrane_eval(x, m).hessian), -1e-10 * hess.norm()) << "trial " << trial;
  }
  EXPECT_GE(beyond, 15);
}

// The factor of a coarsened element, by hand: 1 at or below its own resolution (and for a
// coarsening that is not a number), 1/4 at twice the squared length, continuous at 1, falling,
// and not below 1e-6 however coarse.
TEST(Membrane, CoarseCompressionFactorIsOneAtItsOwnResolutionAndFallsAsTheSquareBeyond) {
  EXPECT_EQ(coarse_compression_factor(0.3), 1.0);
  EXPECT_EQ(coarse_compression_factor(1.0), 1.0);
  EXPECT_EQ(coarse_compression_factor(std::nan("")), 1.0);
  EXPECT_DOUBLE_EQ(coarse_compression_factor(2.0), 0.25);
  EXPECT_DOUBLE_EQ(coarse_compression_factor(10.0), 1e-2);
  EXPECT_NEAR(coarse_compression_factor(1 + 1e-9), 1.0, 1e-8);
  double last = 1;
  for (double c = 1.1; c < 999; c *= 1.1) {
    EXPECT_LT(coarse_compression_factor(c), last);
    last = coarse_compression_factor(c);
  }
  EXPECT_EQ(coarse_compression_factor(1e3), 1e-6);
  EXPECT_EQ(coarse_compression_factor(1e5), 1e-6);
  EXPECT_EQ(coarse_compression_factor(1e300), 1e-6);
}

// Softening over a settle time, by hand: towards 1/16 in steps of a quarter of it, the factor
// is 1/16^(1/4) = 1/2, then 1/4, 1/8, and 1/16 at the settle time, where it stays; a step longer
// than the rest stops at the target; stiffening, an equal target or settle 0 take the target.
TEST(Membrane, EasedCompressionSoftensGeometricallyOverTheSettleTimeAndStiffensAtOnce) {
  double c = 1;
  for (double expected : {0.5, 0.25, 0.125, 0.0625, 0.0625}) {
    c = eased_compression(c, 1.0 / 16, 0.1, 0.4);
    EXPECT_NEAR(c, expected, 1e-15);
  }
  EXPECT_DOUBLE_EQ(eased_compression(0.125, 1.0 / 16, 0.3, 0.4), 1.0 / 16);
  EXPECT_EQ(eased_compression(0.0625, 0.5, 0.1, 0.4), 0.5);
  EXPECT_EQ(eased_compression(0.25, 0.25, 0.1, 0.4), 0.25);
  EXPECT_EQ(eased_compression(1.0, 1e-4, 0.1, 0.0), 1e-4);
  // From a factor already soft, the same step takes it the same fraction of the way in logs.
  EXPECT_NEAR(eased_compression(0.5, 1e-4, 0.1, 0.4), 0.05, 1e-15);
}

}  // namespace
}  // namespace vdc
