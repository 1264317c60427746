// Backward Euler: momentum conservation without external forces, handles held exactly, and
// a hanging sheet's static equilibrium.
#include <gtest/gtest.h>

#include <random>

#include "core/mesh_build.hpp"
#include "physics/cloth_model.hpp"
#include "physics/integrator.hpp"

namespace vdc {
namespace {

struct Sheet {
  Mesh mesh;
  ClothModel model;
  Eigen::VectorXd x, v;
  explicit Sheet(int cells) : mesh(build_mesh(make_grid(0.5, 0.5, cells, cells))) {
    Material m;
    append_garment(model, mesh, m);
    x.resize(3 * model.num_nodes);
    v.resize(3 * model.num_nodes);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (NodeId n : mesh.nodes()) {
      Vec3 p = mesh.x(n);
      p.y() = 0.03 * std::sin(10 * p.x());  // bent and slightly stretched: internal forces act
      x.segment<3>(3 * n.idx) = 1.02 * p;
      v.segment<3>(3 * n.idx) = Vec3(0.3, -0.2, 0.1) + 0.5 * Vec3(U(rng), U(rng), U(rng));
    }
  }
  Vec3 momentum() const {
    Vec3 p = Vec3::Zero();
    for (int32_t i = 0; i < model.num_nodes; ++i) p += model.node_mass[static_cast<std::size_t>(i)] * v.segment<3>(3 * i);
    return p;
  }
};

void check_momentum(LinearSolverKind kind) {
  Sheet s(12);
  StepParams p;
  p.h = 0.005;
  p.gravity = Vec3::Zero();
  LinearSolverParams lp;
  lp.cg_tolerance = 1e-13;
  ImplicitIntegrator integrator(s.model, kind, lp);
  const Vec3 p0 = s.momentum();
  for (int step = 0; step < 100; ++step) {
    StepReport r = integrator.step(s.x, s.v, {}, p, 1e9);
    ASSERT_TRUE(r.ok) << r.failure;
  }
  EXPECT_LT((s.momentum() - p0).norm() / p0.norm(), 1e-9);
  ASSERT_TRUE(s.x.allFinite());
}

TEST(Integrator, ConservesMomentumWithDirectCholesky) { check_momentum(LinearSolverKind::Cholmod); }
TEST(Integrator, ConservesMomentumWithLaggedCholeskyPcg) { check_momentum(LinearSolverKind::CholmodPcg); }

TEST(Integrator, HandlesFollowPrescribedVelocity) {
  Sheet s(8);
  s.v.setZero();
  StepParams p;
  ImplicitIntegrator integrator(s.model, LinearSolverKind::CholmodPcg);
  const Vec3 target_v(0.1, 0.2, -0.3);
  for (int step = 0; step < 10; ++step) {
    std::vector<VelocityConstraint> c{{0, target_v - Vec3(s.v.segment<3>(0))}};
    ASSERT_TRUE(integrator.step(s.x, s.v, c, p, 1e9).ok);
    EXPECT_LT((Vec3(s.v.segment<3>(0)) - target_v).norm(), 1e-12);
  }
}

TEST(Integrator, StretchedStripSettlesToAnalyticElongation) {
  // A 1 m x 0.1 m strip hangs from its top edge (warp along the strip, coupling and bending
  // off). In equilibrium the tension at height s carries the cloth below it: the Green strain
  // obeys c11 E (1 + 2E)^(1/2) ... for small strain, E(s) ~ rho g (L - s) / c11, and the total
  // elongation is rho g L^2 / (2 c11). Checked to 5% after the motion has been damped out.
  const double rho = 0.2, c11 = 2000, g = 9.8, L = 1.0, W = 0.1;
  Mesh mesh = build_mesh(make_grid(W, L, 2, 20));
  for (NodeId n : mesh.nodes()) {
    const Vec2& u = mesh.u(mesh.node_verts(n).front());
    mesh.x(n) = Vec3(u.x(), u.y(), 0);  // hanging in the x-y plane, top at y = L
  }
  Material m;
  m.density = rho;
  m.warp = 5000;  // across the strip
  m.weft = c11;   // along the strip (material v axis)
  m.shear = 500;
  m.poisson = 0;
  m.bending = 0;
  ClothModel model;
  append_garment(model, mesh, m);
  Eigen::VectorXd x(3 * model.num_nodes), v = Eigen::VectorXd::Zero(3 * model.num_nodes);
  std::vector<VelocityConstraint> top;
  for (NodeId n : mesh.nodes()) {
    x.segment<3>(3 * n.idx) = mesh.x(n);
    if (mesh.x(n).y() > L - 1e-9) top.push_back({n.idx, Vec3::Zero()});
  }
  StepParams p;
  p.h = 0.005;
  p.damping = 5.0;
  ImplicitIntegrator integrator(model, LinearSolverKind::CholmodPcg);
  for (int step = 0; step < 3000; ++step) ASSERT_TRUE(integrator.step(x, v, top, p, 1e9).ok);
  double bottom = 1e9;
  for (int32_t i = 0; i < model.num_nodes; ++i) bottom = std::min(bottom, x[3 * i + 1]);
  const double elongation = -bottom;
  const double expected = rho * g * L * L / (2 * c11);
  EXPECT_NEAR(elongation / expected, 1.0, 0.05) << "elongation " << elongation << " expected " << expected;
  EXPECT_LT(v.norm(), 1e-4);
}

}  // namespace
}  // namespace vdc
