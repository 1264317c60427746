// Repulsion and friction in the implicit step, against their analytic answers: a sheet resting
// on a plane settles at band - g h^2 / stiffness, a sheet sliding on it slows down by Coulomb's
// law step by step, and cloth-cloth contact forces conserve momentum.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/collider.hpp"
#include "core/mesh_build.hpp"
#include "physics/contact.hpp"
#include "physics/integrator.hpp"

namespace vdc {
namespace {

constexpr double kG = 9.8, kH = 0.005;

// A 0.2 m sheet, 4 x 4 cells, flat at height y0 over one large ground triangle whose vertices and
// edges are all far from the sheet, so every cloth vertex has exactly one pair: with the face.
struct SheetOnGround {
  Mesh mesh;
  ClothModel model;
  Eigen::VectorXd x, v;
  std::unique_ptr<Collider> collider;
  std::vector<std::vector<Vec3>> ground{{Vec3(-5, 0, 5), Vec3(5, 0, 5), Vec3(0, 0, -5)}};
  std::vector<std::vector<Vec3>> ground_v{{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}};

  explicit SheetOnGround(double y0, Vec3 v0) : mesh(build_mesh(make_grid(0.2, 0.2, 4, 4))) {
    append_garment(model, mesh, Material());
    x.resize(3 * model.num_nodes);
    v.resize(3 * model.num_nodes);
    for (NodeId n : mesh.nodes()) {
      x.segment<3>(3 * n.idx) = mesh.x(n) + Vec3(0, y0, 0);
      v.segment<3>(3 * n.idx) = v0;
    }
    CollisionMesh tri;
    tri.faces.push_back({0, 1, 2});  // counter-clockwise from above: outward normal +y
    collider = std::make_unique<Collider>(model.face_nodes, std::vector<CollisionMesh>{tri}, model.num_nodes);
  }

  // One step with repulsion and friction; returns the number of pairs.
  std::size_t step(ImplicitIntegrator& integrator, const ContactParams& cp) {
    std::vector<char> fixed(static_cast<std::size_t>(model.num_nodes), 0);
    auto pairs = collider->proximities(x, v, fixed, ground, ground_v, cp.band, 1);
    StepParams p;
    p.h = kH;
    p.gravity = Vec3(0, -kG, 0);
    StepReport r = integrator.step(x, v, {}, p, 1e9, contact_terms(pairs, v, model.node_mass, kH, cp));
    EXPECT_TRUE(r.ok) << r.failure;
    return pairs.size();
  }
};

TEST(Contact, RestingSheetSettlesAtTheAnalyticHeight) {
  ContactParams cp;
  cp.band = 0.004;
  cp.stiffness = 1.0;
  cp.friction = 0.3;
  SheetOnGround s(0.003, Vec3::Zero());
  ImplicitIntegrator integrator(s.model, LinearSolverKind::Cholmod);
  for (int i = 0; i < 400; ++i) ASSERT_EQ(s.step(integrator, cp), static_cast<std::size_t>(s.model.num_nodes));
  // k (band - y) = m g with k = stiffness m / h^2, whatever each node's mass.
  const double expected = cp.band - kG * kH * kH / cp.stiffness;
  for (int32_t i = 0; i < s.model.num_nodes; ++i) {
    EXPECT_NEAR(s.x[3 * i + 1], expected, 1e-7) << "node " << i;
    EXPECT_LT(s.v.segment<3>(3 * i).norm(), 1e-6);
  }
}

TEST(Contact, SlidingSheetFollowsCoulombStepByStep) {
  ContactParams cp;
  cp.band = 0.004;
  cp.stiffness = 1.0;
  cp.friction = 0.3;
  const double rest = cp.band - kG * kH * kH / cp.stiffness;  // normal force m g from the start
  const double v0 = 1.0;
  SheetOnGround s(rest, Vec3(v0, 0, 0));
  ImplicitIntegrator integrator(s.model, LinearSolverKind::Cholmod);
  // The lagged friction of one step: m (u' - u) = -h c u', c = min(mu m g / u, m / h).
  double u = v0, travelled = 0;
  const double x0 = s.x[0];
  for (int i = 0; i < 50; ++i) {
    s.step(integrator, cp);
    const double c_over_m = std::min(cp.friction * kG / u, 1 / kH);
    u = u / (1 + kH * c_over_m);
    travelled += kH * u;
  }
  for (int32_t i = 0; i < s.model.num_nodes; ++i) EXPECT_NEAR(s.v[3 * i], u, 1e-6 * v0) << "node " << i;
  EXPECT_NEAR(s.x[0] - x0, travelled, 1e-6);
  // 50 steps of 5 ms at mu g = 2.94 m/s^2: near Coulomb's continuous 1 - 0.735 m/s; the lag
  // loses (mu g h)^2 / u per step, 0.018 m/s in all here.
  EXPECT_NEAR(u, v0 - cp.friction * kG * 50 * kH, 0.025);
  // It stops after v0 / (mu g) = 0.34 s and stays (static friction holds it).
  for (int i = 0; i < 100; ++i) s.step(integrator, cp);
  for (int32_t i = 0; i < s.model.num_nodes; ++i) EXPECT_LT(s.v.segment<3>(3 * i).norm(), 1e-6) << "node " << i;
}

TEST(Contact, ClothClothForcesConserveMomentum) {
  ProximityPair p;
  p.nodes = {0, 1, 2, 3};
  p.weights = {1.0, -0.2, -0.5, -0.3};
  p.normal = Vec3(0, 1, 0);
  p.distance = 0.001;
  p.obstacle_velocity.fill(Vec3::Zero());
  Eigen::VectorXd v(12);
  v << 0.3, -1, 0.2, 0, 0, 0, 0.1, 0.2, 0, -0.4, 0, 0.1;
  std::vector<double> mass{1e-3, 2e-3, 1.5e-3, 1e-3};
  auto terms = contact_terms({p}, v, mass, kH, ContactParams{});
  ASSERT_EQ(terms.size(), 1u);
  Vec3 total = Vec3::Zero();
  for (std::size_t j = 0; j < 4; ++j) total += terms[0].weights[j] * terms[0].rhs;
  EXPECT_LT(total.norm(), 1e-15);
  // The normal force is the penalty's: stiffness m_eff / h^2 times the gap (the default stiffness).
  const double m_eff = 1 / (1 / 1e-3 + 0.04 / 2e-3 + 0.25 / 1.5e-3 + 0.09 / 1e-3);
  EXPECT_NEAR(terms[0].normal_force, ContactParams{}.stiffness * m_eff / (kH * kH) * (0.004 - 0.001), 1e-12);
}

}  // namespace
}  // namespace vdc
