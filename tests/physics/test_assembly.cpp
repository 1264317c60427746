// System assembly (Baraff and Witkin 1998, eq. 18) against a dense sum of the same element
// terms, and the matrix pattern against the node pairs the elements couple.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "core/mesh_build.hpp"
#include "physics/assembly.hpp"
#include "physics/cloth_model.hpp"
#include "support/finite_difference.hpp"

namespace vdc {
namespace {

// Two garments in one model (a sheet and a smaller, offset one), bent, stretched and moving.
struct TwoSheets {
  Mesh a, b;
  ClothModel model;
  Eigen::VectorXd x, v;
  TwoSheets() : a(build_mesh(make_grid(0.4, 0.3, 5, 4))), b(build_mesh(make_grid(0.2, 0.2, 3, 3))) {
    Material m;
    const int32_t offset[2] = {append_garment(model, a, m), append_garment(model, b, m)};
    x.resize(3 * model.num_nodes);
    v.resize(3 * model.num_nodes);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int g = 0; g < 2; ++g) {
      const Mesh* mesh = g == 0 ? &a : &b;
      const Vec3 shift = g == 0 ? Vec3::Zero() : Vec3(1, 0, 0);
      for (NodeId n : mesh->nodes()) {
        const int32_t i = offset[g] + n.idx;
        Vec3 p = mesh->x(n);
        p.y() += 0.04 * std::sin(9 * p.x()) + 0.002 * U(rng);
        x.segment<3>(3 * i) = 1.03 * p + shift;
        v.segment<3>(3 * i) = Vec3(U(rng), U(rng), U(rng));
      }
    }
  }
};

TEST(Assembly, MatrixAndForcesAreTheElementTermsSummedDensely) {
  TwoSheets s;
  StepParams p;
  p.h = 0.004;
  p.damping = 0.7;
  p.gravity = Vec3(0, -9.8, 0);
  p.threads = 2;
  SystemAssembler assembler(s.model);
  assembler.assemble(s.x, s.v, p);

  const int64_t dim = 3 * static_cast<int64_t>(s.model.num_nodes);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(dim, dim);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(dim);
  const double h = p.h, h2 = p.h * p.h;
  auto add_element = [&](const auto& nodes, const auto& gradient, const auto& hessian) {
    const auto k = static_cast<int>(nodes.size());
    Eigen::VectorXd vl(3 * k);
    for (int i = 0; i < k; ++i) vl.segment<3>(3 * i) = s.v.segment<3>(3 * nodes[static_cast<std::size_t>(i)]);
    const Eigen::VectorXd rhs = -h * gradient - h2 * (hessian * vl);
    for (int i = 0; i < k; ++i) {
      const int64_t r = 3 * nodes[static_cast<std::size_t>(i)];
      b.segment<3>(r) += rhs.template segment<3>(3 * i);
      for (int j = 0; j < k; ++j) a.block<3, 3>(r, 3 * nodes[static_cast<std::size_t>(j)]) += h2 * hessian.template block<3, 3>(3 * i, 3 * j);
    }
  };
  for (std::size_t f = 0; f < s.model.face_nodes.size(); ++f) {
    const auto& nodes = s.model.face_nodes[f];
    TriStencil xs;
    for (std::size_t i = 0; i < 3; ++i) xs[i] = s.x.segment<3>(3 * nodes[i]);
    const MembraneEval m = membrane_eval(xs, s.model.membranes[f]);
    add_element(nodes, m.gradient, m.hessian);
  }
  for (std::size_t e = 0; e < s.model.bend_nodes.size(); ++e) {
    const auto& nodes = s.model.bend_nodes[e];
    BendStencil xs;
    for (std::size_t i = 0; i < 4; ++i) xs[i] = s.x.segment<3>(3 * nodes[i]);
    const BendingEval be = bending_eval(xs, s.model.bends[e]);
    add_element(nodes, be.gradient, be.hessian);
  }
  for (int32_t i = 0; i < s.model.num_nodes; ++i) {
    const double mass = s.model.node_mass[static_cast<std::size_t>(i)];
    a.block<3, 3>(3 * i, 3 * i) += mass * (1 + h * p.damping) * Mat3::Identity();
    b.segment<3>(3 * i) += h * mass * (p.gravity - p.damping * s.v.segment<3>(3 * i));
  }

  const Eigen::MatrixXd assembled = Eigen::MatrixXd(assembler.matrix());
  EXPECT_LE((assembled - a).cwiseAbs().maxCoeff(), 1e-12 * a.cwiseAbs().maxCoeff());
  EXPECT_LE((assembler.rhs() - b).cwiseAbs().maxCoeff(), 1e-12 * b.cwiseAbs().maxCoeff());
  EXPECT_LE((assembled - assembled.transpose()).cwiseAbs().maxCoeff(), 1e-12 * a.cwiseAbs().maxCoeff());
}

// StepParams::coarse_damping: the system with it less the system without is, face by face,
// h beta K on the matrix and -h beta K v on the forces, beta = coarse_damping h (1 - compression),
// on the softened faces only; and it is damping of deformation: a rigid motion feels none.
TEST(Assembly, CoarseDampingIsRayleighDampingOfTheSoftenedFacesOnly) {
  TwoSheets s;
  for (std::size_t f = 0; f < s.model.membranes.size(); f += 3) s.model.membranes[f].compression = 0.3;
  StepParams p;
  p.h = 0.004;
  p.threads = 2;
  SystemAssembler plain(s.model), damped(s.model);
  plain.assemble(s.x, s.v, p);
  p.coarse_damping = 2;
  damped.assemble(s.x, s.v, p);

  const int64_t dim = 3 * static_cast<int64_t>(s.model.num_nodes);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(dim, dim);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(dim);
  int softened = 0;
  for (std::size_t f = 0; f < s.model.face_nodes.size(); ++f) {
    if (s.model.membranes[f].compression == 1) continue;
    ++softened;
    const auto& nodes = s.model.face_nodes[f];
    TriStencil xs;
    VecN<9> vl;
    for (std::size_t i = 0; i < 3; ++i) {
      xs[i] = s.x.segment<3>(3 * nodes[i]);
      vl.segment<3>(3 * static_cast<Eigen::Index>(i)) = s.v.segment<3>(3 * nodes[i]);
    }
    const double beta = 2 * p.h * (1 - 0.3);
    const MatN<9> k = membrane_eval(xs, s.model.membranes[f]).hessian;
    const VecN<9> force = -p.h * beta * (k * vl);
    for (int i = 0; i < 3; ++i) {
      b.segment<3>(3 * nodes[static_cast<std::size_t>(i)]) += force.segment<3>(3 * i);
      for (int j = 0; j < 3; ++j)
        a.block<3, 3>(3 * nodes[static_cast<std::size_t>(i)], 3 * nodes[static_cast<std::size_t>(j)]) += p.h * beta * k.block<3, 3>(3 * i, 3 * j);
    }
  }
  ASSERT_GT(softened, 10);
  const Eigen::MatrixXd added = Eigen::MatrixXd(damped.matrix()) - Eigen::MatrixXd(plain.matrix());
  EXPECT_GT(a.cwiseAbs().maxCoeff(), 0);
  EXPECT_LE((added - a).cwiseAbs().maxCoeff(), 1e-9 * a.cwiseAbs().maxCoeff());
  EXPECT_LE((damped.rhs() - plain.rhs() - b).cwiseAbs().maxCoeff(), 1e-9 * b.cwiseAbs().maxCoeff());

  // A rigid translation of everything: the membrane Hessian has it in its null space.
  Eigen::VectorXd translation(dim);
  for (int32_t i = 0; i < s.model.num_nodes; ++i) translation.segment<3>(3 * i) = Vec3(0.8, -0.3, 0.5);
  damped.assemble(s.x, translation, p);
  p.coarse_damping = 0;
  plain.assemble(s.x, translation, p);
  EXPECT_LE((damped.rhs() - plain.rhs()).cwiseAbs().maxCoeff(), 1e-12 * plain.rhs().cwiseAbs().maxCoeff());
}

// The assembled forces against central differences of the total elastic energy at `x_forces`,
// and the assembled stiffness against central differences of those forces at `x_stiffness`,
// where the element Hessians the assembler uses must be the exact ones. With v = 0, no gravity
// and no damping the system is A = M + h^2 K, b = -h grad E.
void expect_derivatives_of_the_energy(const ClothModel& model, const Eigen::VectorXd& x_forces, const Eigen::VectorXd& x_stiffness) {
  const int64_t dim = 3 * static_cast<int64_t>(model.num_nodes);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(dim);
  StepParams p;
  p.h = 0.01;
  p.gravity = Vec3::Zero();
  SystemAssembler assembler(model);
  auto energy = [&](const Eigen::VectorXd& at) {
    assembler.assemble(at, v, p);
    return assembler.elastic_energy();
  };
  auto gradient = [&](const Eigen::VectorXd& at) {
    assembler.assemble(at, v, p);
    return Eigen::VectorXd(-assembler.rhs() / p.h);
  };
  const Eigen::VectorXd g = gradient(x_forces);
  const Eigen::VectorXd fd_gradient = test::central_differences(energy, x_forces, 1e-6);
  EXPECT_GT(g.norm(), 1e-3 * g.size());  // away from equilibrium: the forces are not all zero
  EXPECT_LE((g - fd_gradient).cwiseAbs().maxCoeff(), 1e-6 * g.cwiseAbs().maxCoeff());

  assembler.assemble(x_stiffness, v, p);
  Eigen::MatrixXd stiffness = Eigen::MatrixXd(assembler.matrix());
  for (int32_t i = 0; i < model.num_nodes; ++i)
    stiffness.block<3, 3>(3 * i, 3 * i) -= model.node_mass[static_cast<std::size_t>(i)] * Mat3::Identity();
  stiffness /= p.h * p.h;
  const Eigen::MatrixXd fd_stiffness = test::central_differences(gradient, x_stiffness, 1e-6);
  EXPECT_LE((stiffness - fd_stiffness).cwiseAbs().maxCoeff(), 1e-5 * stiffness.cwiseAbs().maxCoeff());
}

// A wavy sheet whose bending rest angles are its own, scaled by `scale` in world space.
Eigen::VectorXd wavy_sheet(Mesh& mesh, double scale) {
  for (NodeId n : mesh.nodes()) {
    Vec3 q = mesh.x(n);
    q.y() += 0.03 * std::sin(9 * q.x()) + 0.02 * std::cos(7 * q.z());
    mesh.x(n) = q;
  }
  set_rest_angles_from_world(mesh);
  Eigen::VectorXd x(3 * mesh.num_nodes());
  for (NodeId n : mesh.nodes()) x.segment<3>(3 * n.idx) = scale * mesh.x(n);
  return x;
}

// Membranes stretched 3% (no stress clamped, so their PSD Hessian is the exact one), bending at
// its rest angles (where its Gauss-Newton Hessian is exact).
TEST(Assembly, ForcesAndStiffnessAreTheTotalEnergysDerivatives) {
  Mesh mesh = build_mesh(make_grid(0.3, 0.2, 4, 3));
  const Eigen::VectorXd x = wavy_sheet(mesh, 1.03);
  ClothModel model;
  append_garment(model, mesh, Material{});
  expect_derivatives_of_the_energy(model, x, x);
}

// Bending alone, too weak to show beside the membranes above: its forces away from the rest
// angles, its stiffness at them.
TEST(Assembly, BendingForcesAndStiffnessAreTheTotalEnergysDerivatives) {
  Mesh mesh = build_mesh(make_grid(0.3, 0.2, 4, 3));
  const Eigen::VectorXd rest = wavy_sheet(mesh, 1.0);
  Eigen::VectorXd bent = rest;
  for (int64_t k = 1; k < bent.size(); k += 3) bent[k] += 0.01 * std::sin(5.0 * static_cast<double>(k));
  Material bending_only;
  bending_only.warp = bending_only.weft = bending_only.shear = bending_only.poisson = 0;
  bending_only.bending = 1.0;  // N m: forces of order one
  ClothModel model;
  append_garment(model, mesh, bending_only);
  expect_derivatives_of_the_energy(model, bent, rest);
}

// The pattern and gather lists built on two threads are the one-thread ones: the same matrix and
// forces, value for value.
TEST(Assembly, TwoThreadsBuildTheSystemOneThreadBuilds) {
  TwoSheets s;
  StepParams p;
  p.h = 0.004;
  p.gravity = Vec3(0, -9.8, 0);
  SystemAssembler one(s.model, 1), two(s.model, 2);
  one.assemble(s.x, s.v, p);
  two.assemble(s.x, s.v, p);
  const SparseMatrix& a = one.matrix();
  const SparseMatrix& b = two.matrix();
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  ASSERT_EQ(a.cols(), b.cols());
  EXPECT_TRUE(std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.cols() + 1, b.outerIndexPtr()));
  EXPECT_TRUE(std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr()));
  EXPECT_TRUE(std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), b.valuePtr()));
  EXPECT_EQ(one.rhs(), two.rhs());
}

TEST(Assembly, PatternHoldsExactlyTheNodePairsThatShareAnElement) {
  TwoSheets s;
  SystemAssembler assembler(s.model);
  std::set<std::pair<int32_t, int32_t>> coupled;
  for (int32_t i = 0; i < s.model.num_nodes; ++i) coupled.insert({i, i});
  auto link = [&](const auto& nodes) {
    for (int32_t p : nodes)
      for (int32_t q : nodes) coupled.insert({p, q});
  };
  for (const auto& f : s.model.face_nodes) link(f);
  for (const auto& e : s.model.bend_nodes) link(e);

  EXPECT_EQ(assembler.matrix().nonZeros(), 9 * static_cast<int64_t>(coupled.size()));
  const int32_t first_of_b = s.a.num_nodes();
  for (int32_t i = 0; i < s.model.num_nodes; ++i)
    for (int32_t j = 0; j < s.model.num_nodes; ++j) {
      const bool in_pattern = assembler.value_index(i, j, 2, 1) >= 0;
      ASSERT_EQ(in_pattern, coupled.count({i, j}) == 1) << "nodes " << i << ", " << j;
      if (in_pattern) {
        // Rows are sorted within each column, and the entry found is the one asked for.
        const int64_t k = assembler.value_index(i, j, 2, 1);
        EXPECT_EQ(assembler.matrix().innerIndexPtr()[k], 3 * i + 2);
        EXPECT_GE(k, assembler.matrix().outerIndexPtr()[3 * j + 1]);
        EXPECT_LT(k, assembler.matrix().outerIndexPtr()[3 * j + 2]);
        EXPECT_EQ(i < first_of_b, j < first_of_b);  // the garments do not couple
      }
    }
}

}  // namespace
}  // namespace vdc
