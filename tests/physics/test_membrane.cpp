// Membrane energy: finite-difference gradient and Hessian, rigid invariance, PSD projection.
#include <gtest/gtest.h>

#include <random>

#include "physics/membrane.hpp"
#include "physics/psd.hpp"

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
    VecN<9> g = membrane_gradient(x, m), fd;
    VecN<9> q = flatten(x);
    const double eps = 1e-7;
    for (int i = 0; i < 9; ++i) {
      VecN<9> qp = q, qm = q;
      qp[i] += eps;
      qm[i] -= eps;
      fd[i] = (membrane_energy(unflatten(qp), m) - membrane_energy(unflatten(qm), m)) / (2 * eps);
    }
    EXPECT_LT((g - fd).norm() / g.norm(), 1e-5) << "trial " << trial;
  }
}

TEST(Membrane, HessianMatchesFiniteDifferences) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 50; ++trial) {
    auto [x, m] = random_membrane(rng);
    MatN<9> h = membrane_hessian(x, m), fd;
    VecN<9> q = flatten(x);
    const double eps = 1e-6;
    for (int i = 0; i < 9; ++i) {
      VecN<9> qp = q, qm = q;
      qp[i] += eps;
      qm[i] -= eps;
      fd.col(i) = (membrane_gradient(unflatten(qp), m) - membrane_gradient(unflatten(qm), m)) / (2 * eps);
    }
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

}  // namespace
}  // namespace vdc
