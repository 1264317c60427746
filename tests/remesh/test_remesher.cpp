// The remeshing loop against a prescribed sizing field: every edge valid afterwards, the mesh
// Delaunay in the metric, nothing inverted, area conserved, edge lengths in a stated band.
#include <gtest/gtest.h>

#include <cmath>

#include "core/mesh_build.hpp"
#include "remesh/remesher.hpp"

namespace vdc {
namespace {

Mesh sheet_with_sizing(int cells, const Mat2& m) {
  Mesh mesh = build_mesh(make_grid(1, 1, cells, cells));
  auto& s = mesh.vert_attrs().add<Mat2>(kSizingAttr, m);
  for (VertId v : mesh.verts()) s[v] = m;
  return mesh;
}

double total_area(const Mesh& m) {
  double a = 0;
  for (FaceId f : m.faces()) a += m.material_area(f);
  return a;
}

void expect_remeshed(const Mesh& mesh, const RemeshOptions& o) {
  ValidationReport v = mesh.validate();
  ASSERT_TRUE(v.ok()) << v.summary();
  for (EdgeId e : mesh.edges()) {
    EXPECT_LE(edge_size2(mesh, e), 1.0 + 1e-12) << "edge " << e.idx;
    EXPECT_FALSE(should_flip(mesh, e, o.flip_threshold) && can_flip(mesh, e) && flip_keeps_valid(mesh, e))
        << "edge " << e.idx << " not Delaunay";
  }
  for (FaceId f : mesh.faces()) {
    EXPECT_GT(mesh.material_area(f), 0);
    EXPECT_GT(mesh.world_normal(f).y(), 0.99);  // the flat sheet keeps facing up
  }
  EXPECT_NEAR(total_area(mesh), 1.0, 1e-12);
}

TEST(Remesher, RefinesACoarseSheetToAConstantIsotropicField) {
  // h = 5 cm on a 1 m sheet of 2 x 2 cells: every edge must end at most h long. Collapses stop
  // at s^2 <= 1 - margin = 0.8, so an edge shorter than sqrt(0.8) h / 2 = 0.45 h would have been
  // collapsible unless a collapse were refused for shape: with a midpoint-split mesh edges fall
  // in [h/4, h]; on average they sit between h/2 and h.
  const double h = 0.05;
  Mesh mesh = sheet_with_sizing(2, Mat2::Identity() / (h * h));
  RemeshOptions o;
  RemeshStats s = remesh(mesh, o);
  EXPECT_GT(s.splits, 100);
  expect_remeshed(mesh, o);
  double sum = 0, shortest = 1;
  for (EdgeId e : mesh.edges()) {
    double len = (mesh.x(mesh.edge_node(e, 0)) - mesh.x(mesh.edge_node(e, 1))).norm();
    sum += len;
    shortest = std::min(shortest, len);
  }
  const double mean = sum / mesh.num_edges();
  EXPECT_GT(shortest, h / 4) << "shortest edge";
  EXPECT_GT(mean, 0.5 * h);
  EXPECT_LT(mean, h);
  // Face count near the ideal for equilateral triangles of side ~0.75 h: area / (sqrt(3)/4 a^2).
  const double ideal = 1.0 / (std::sqrt(3.0) / 4 * std::pow(0.75 * h, 2));
  EXPECT_GT(mesh.num_faces(), 0.5 * ideal);
  EXPECT_LT(mesh.num_faces(), 2.0 * ideal);
}

TEST(Remesher, CoarsensAFineSheet) {
  const double h = 0.2;
  Mesh mesh = sheet_with_sizing(40, Mat2::Identity() / (h * h));
  RemeshOptions o;
  RemeshStats s = remesh(mesh, o);
  EXPECT_GT(s.collapses, 1000);
  expect_remeshed(mesh, o);
  EXPECT_LT(mesh.num_faces(), 400);
}

TEST(Remesher, AnisotropicFieldGivesAnisotropicEdges) {
  // 2 cm across u, 20 cm along v: edges along u short, the mesh much finer in u.
  Mat2 m = Mat2::Zero();
  m(0, 0) = 1.0 / (0.02 * 0.02);
  m(1, 1) = 1.0 / (0.2 * 0.2);
  Mesh mesh = sheet_with_sizing(4, m);
  RemeshOptions o;
  remesh(mesh, o);
  expect_remeshed(mesh, o);
  double du = 0, dv = 0;
  for (EdgeId e : mesh.edges()) {
    Vec3 d = mesh.x(mesh.edge_node(e, 0)) - mesh.x(mesh.edge_node(e, 1));
    du = std::max(du, std::abs(d.x()));
    dv = std::max(dv, std::abs(d.z()));
  }
  EXPECT_LE(du, 0.02 + 1e-12);
  EXPECT_GT(dv, 0.05);
}

}  // namespace
}  // namespace vdc
