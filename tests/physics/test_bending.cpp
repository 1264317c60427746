// Bending: dihedral angle and energy derivatives against finite differences, invariance, and
// the discrete energy of a bent plate against the continuum value 1/2 k kappa^2 per area.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/mesh_build.hpp"
#include "physics/bending.hpp"
#include "physics/cloth_model.hpp"
#include "physics/psd.hpp"
#include "support/finite_difference.hpp"

namespace vdc {
namespace {

BendStencil random_stencil(std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  // Edge along x, opposite vertices on either side, folded by up to about 100 degrees.
  double fold = 1.7 * U(rng);
  Vec3 x0(0, 0, 0), x1(0.05, 0, 0);
  Vec3 x2(0.025 + 0.01 * U(rng), 0.04 + 0.005 * U(rng), 0.005 * U(rng));
  Vec3 x3(0.025 + 0.01 * U(rng), -0.04 * std::cos(fold), -0.04 * std::sin(fold));
  Mat3 rot = Eigen::Quaterniond(U(rng), U(rng), U(rng), U(rng)).normalized().toRotationMatrix();
  Vec3 t(U(rng), U(rng), U(rng));
  BendStencil s{x0, x1, x2, x3};
  for (auto& p : s) p = rot * p + t + 0.002 * Vec3(U(rng), U(rng), U(rng));
  return s;
}

VecN<12> flatten(const BendStencil& x) {
  VecN<12> q;
  for (int i = 0; i < 4; ++i) q.segment<3>(3 * i) = x[static_cast<std::size_t>(i)];
  return q;
}

BendStencil unflatten(const VecN<12>& q) { return {q.segment<3>(0), q.segment<3>(3), q.segment<3>(6), q.segment<3>(9)}; }

TEST(Bending, AngleSignAndValue) {
  // Flat: zero. Opposite vertex of face 0 lifted along its normal (+z): negative angle.
  BendStencil flat{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, -1, 0)};
  EXPECT_NEAR(dihedral_angle(flat), 0.0, 1e-15);
  BendStencil folded{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, -std::cos(0.3), std::sin(0.3))};
  EXPECT_NEAR(dihedral_angle(folded), -0.3, 1e-12);
}

TEST(Bending, AngleGradientMatchesFiniteDifferences) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    BendStencil x = random_stencil(rng);
    const VecN<12> g = dihedral_angle_gradient(x);
    const Eigen::VectorXd fd = test::central_differences([](const VecN<12>& q) { return dihedral_angle(unflatten(q)); }, flatten(x), 1e-7);
    EXPECT_LT((g - fd).norm() / g.norm(), 1e-5) << "trial " << trial;
  }
}

TEST(Bending, EnergyGradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    BendStencil x = random_stencil(rng);
    BendingElement b{0.3 * U(rng), bending_coefficient(1e-5, 0.05, 1e-3, 1.2e-3)};
    const VecN<12> g = bending_gradient(x, b);
    const MatN<12> h = bending_hessian(x, b);
    const Eigen::VectorXd gfd = test::central_differences([&](const VecN<12>& q) { return bending_energy(unflatten(q), b); }, flatten(x), 1e-7);
    const Eigen::MatrixXd hfd = test::central_differences([&](const VecN<12>& q) { return bending_gradient(unflatten(q), b); }, flatten(x), 1e-7);
    EXPECT_LT((g - gfd).norm() / g.norm(), 1e-5) << "trial " << trial;
    EXPECT_LT((h - hfd).norm() / h.norm(), 1e-4) << "trial " << trial;
  }
}

TEST(Bending, ProjectedHessianIsPsdAndDropsOnlyTheCurvatureTerm) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 30; ++trial) {
    BendStencil x = random_stencil(rng);
    BendingElement b{0.1, 1.0};
    MatN<12> psd = bending_hessian_psd(x, b);
    EXPECT_GT(min_eigenvalue<12>(psd), -1e-9 * psd.norm());
    // At the rest angle the exact Hessian is the Gauss-Newton one.
    BendingElement at_rest{dihedral_angle(x), 1.0};
    EXPECT_LT((bending_hessian(x, at_rest) - bending_hessian_psd(x, at_rest)).norm(), 1e-9 * psd.norm());
  }
}

TEST(Bending, RigidMotionOfTheRestShapeHasNoForce) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    BendStencil x = random_stencil(rng);
    BendingElement b{dihedral_angle(x), 2.0};
    Mat3 rot = Eigen::Quaterniond(U(rng), U(rng), U(rng), U(rng)).normalized().toRotationMatrix();
    Vec3 t(U(rng), U(rng), U(rng));
    BendStencil moved = x;
    for (auto& p : moved) p = rot * p + t;
    EXPECT_NEAR(bending_energy(moved, b), 0.0, 1e-20);
    EXPECT_LT(bending_gradient(moved, b).norm(), 1e-9);
  }
}

// A patch of equilateral triangles (side a) covering about size x size metres in material space.
MeshSource equilateral_patch(double size, double a) {
  MeshSource src;
  const int cols = static_cast<int>(size / a), rows = static_cast<int>(size / (a * std::sqrt(3.0) / 2));
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= cols; ++i) {
      Vec2 u(a * (i + 0.5 * (j % 2)), a * std::sqrt(3.0) / 2 * j);
      src.uvs.push_back(u);
      src.positions.emplace_back(u.x(), 0, -u.y());
    }
  auto id = [cols](int i, int j) { return j * (cols + 1) + i; };
  auto c = [](int k) { return Corner{k, k}; };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      if (j % 2 == 0) {
        src.faces.push_back({c(id(i, j)), c(id(i + 1, j)), c(id(i, j + 1))});
        if (i + 1 < cols + 1 && i + 1 <= cols) src.faces.push_back({c(id(i + 1, j)), c(id(i + 1, j + 1)), c(id(i, j + 1))});
      } else {
        src.faces.push_back({c(id(i, j)), c(id(i + 1, j + 1)), c(id(i, j + 1))});
        src.faces.push_back({c(id(i, j)), c(id(i + 1, j)), c(id(i + 1, j + 1))});
      }
    }
  return src;
}

// Bends a flat patch onto a cylinder of radius R whose axis runs along material direction
// `axis_angle` (radians from the u axis), and returns the discrete energy over the continuum
// 1/2 k (1/R)^2 times the area of the faces (interior edges only carry energy, so the patch is
// measured on its interior: total area minus a half-cell boundary band).
double cylinder_energy_ratio(const MeshSource& flat, double radius, double axis_angle) {
  const double k = 1e-5;
  Mesh mesh = build_mesh(flat);
  const Vec2 across(std::cos(axis_angle + std::numbers::pi / 2), std::sin(axis_angle + std::numbers::pi / 2));
  const Vec2 along(std::cos(axis_angle), std::sin(axis_angle));
  for (NodeId n : mesh.nodes()) {
    const Vec2& u = mesh.u(mesh.node_verts(n).front());
    double s = u.dot(across) / radius, t = u.dot(along);
    mesh.x(n) = radius * std::sin(s) * Vec3(across.x(), 0, -across.y()) + radius * (1 - std::cos(s)) * Vec3(0, 1, 0) +
                t * Vec3(along.x(), 0, -along.y());
  }
  Material mat;
  mat.bending = k;
  ClothModel model;
  append_garment(model, mesh, mat);
  double energy = 0, area = 0;
  for (std::size_t e = 0; e < model.bends.size(); ++e) {
    const auto& n = model.bend_nodes[e];
    energy += bending_energy({mesh.x(NodeId(n[0])), mesh.x(NodeId(n[1])), mesh.x(NodeId(n[2])), mesh.x(NodeId(n[3]))}, model.bends[e]);
  }
  // Each interior edge stands for (A0 + A1) / 3 of area: the share of its two faces.
  for (EdgeId e : mesh.edges())
    if (!mesh.is_boundary(e)) area += (mesh.material_area(mesh.edge_face(e, 0)) + mesh.material_area(mesh.edge_face(e, 1))) / 3;
  return energy / (0.5 * k / (radius * radius) * area);
}

TEST(Bending, CylinderEnergyMatchesContinuumOnEquilateralMeshes) {
  // On a regular equilateral mesh the discrete energy equals the plate energy 1/2 k kappa^2 in
  // every bending direction, to the order of (a / R)^2.
  MeshSource flat = equilateral_patch(0.4, 0.01);
  for (double angle : {0.0, 0.4, std::numbers::pi / 6, 1.0, std::numbers::pi / 2})
    EXPECT_NEAR(cylinder_energy_ratio(flat, 0.3, angle), 1.0, 0.01) << "axis angle " << angle;
}

TEST(Bending, CylinderEnergyOnRightTriangleGridMatchesAboutAGridAxis) {
  // On a grid of right triangles bent about a grid axis only the edges along the axis fold
  // (each cell's four corners stay coplanar); each carries |e|^2 / (A0 + A1) = 1 and angle
  // kappa a, which again gives 1/2 k kappa^2 per area.
  EXPECT_NEAR(cylinder_energy_ratio(make_grid(0.4, 0.4, 40, 40), 0.3, std::numbers::pi / 2), 1.0, 0.02);
}

}  // namespace
}  // namespace vdc
