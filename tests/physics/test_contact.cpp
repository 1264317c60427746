// Repulsion and friction in the implicit step, against their analytic answers: repulsion's force
// and stiffness are the derivatives of its penalty energy, a sheet resting on a plane settles at
// band - g h^2 / stiffness, a sheet sliding on it slows down by Coulomb's law step by step, and
// cloth-cloth contact forces conserve momentum.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/collider.hpp"
#include "core/mesh_build.hpp"
#include "physics/contact.hpp"
#include "physics/integrator.hpp"
#include "support/finite_difference.hpp"

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

// Repulsion (Bridson, Fedkiw and Anderson 2002, section 7.2) against central differences: a
// vertex-face pair of four movable nodes of unequal masses, 2 mm apart inside a 4 mm band, at
// rest, without friction. Node i's force w_i rhs / h is minus the gradient of the penalty energy
// E = k (band - d)^2 / 2, d = n . sum_j w_j x_j, k = stiffness m_eff / h^2 (contact.hpp); the
// block w_i w_j A between nodes i and j is h^2 times minus the derivative of node i's force along
// node j's position, differenced from contact_terms itself.
TEST(Contact, RepulsionIsTheGradientAndStiffnessOfItsPenaltyEnergy) {
  const std::vector<double> mass = {0.01, 0.02, 0.015, 0.03};
  ProximityPair pair;
  pair.nodes = {0, 1, 2, 3};
  pair.weights = {1.0, -0.2, -0.5, -0.3};
  pair.normal = Vec3(0.2, 1.0, 0.1).normalized();
  ContactParams params;
  params.friction = 0;
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(12);
  Eigen::VectorXd x(12);
  x << 0.01, 0.02, -0.03, -0.05, 0.001, 0.02, 0.04, -0.002, 0.03, 0.01, 0.003, -0.04;
  auto separation = [&](const Eigen::VectorXd& at) {
    Vec3 s = Vec3::Zero();
    for (int j = 0; j < 4; ++j) s += pair.weights[static_cast<std::size_t>(j)] * at.segment<3>(3 * j);
    return pair.normal.dot(s);
  };
  x.segment<3>(0) += (0.002 - separation(x)) * pair.normal;  // d = 2 mm (w_0 = 1)
  ASSERT_NEAR(separation(x), 0.002, 1e-15);

  double inv_mass = 0;
  for (int j = 0; j < 4; ++j) inv_mass += pair.weights[static_cast<std::size_t>(j)] * pair.weights[static_cast<std::size_t>(j)] / mass[static_cast<std::size_t>(j)];
  const double k = params.stiffness / inv_mass / (kH * kH);
  auto energy = [&](const Eigen::VectorXd& at) { return 0.5 * k * std::pow(params.band - separation(at), 2); };
  auto term_at = [&](const Eigen::VectorXd& at) {
    ProximityPair p = pair;
    p.distance = separation(at);
    const std::vector<ContactTerm> terms = contact_terms({p}, v, mass, kH, params);
    EXPECT_EQ(terms.size(), 1u);
    return terms.at(0);
  };
  auto forces = [&](const Eigen::VectorXd& at) {
    const ContactTerm t = term_at(at);
    Eigen::VectorXd f(12);
    for (int i = 0; i < 4; ++i) f.segment<3>(3 * i) = t.weights[static_cast<std::size_t>(i)] * t.rhs / kH;
    return f;
  };

  const Eigen::VectorXd f = forces(x);
  const ContactTerm t = term_at(x);
  Eigen::MatrixXd stiffness(12, 12);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      stiffness.block<3, 3>(3 * i, 3 * j) = t.weights[static_cast<std::size_t>(i)] * t.weights[static_cast<std::size_t>(j)] * t.block;
  const Eigen::VectorXd fd_force = -test::central_differences(energy, x, 1e-7);
  const Eigen::MatrixXd fd_stiffness = -kH * kH * test::central_differences(forces, x, 1e-7);
  EXPECT_GT(f.norm(), 1.0);  // well inside the band: forces of order newtons
  EXPECT_LE((f - fd_force).cwiseAbs().maxCoeff(), 1e-6 * f.cwiseAbs().maxCoeff());
  EXPECT_LE((stiffness - fd_stiffness).cwiseAbs().maxCoeff(), 1e-6 * stiffness.cwiseAbs().maxCoeff());
}

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
