// Obstacle surfaces as artists' meshes come: each defect repaired, counted, and the result one
// build_mesh accepts, with every position a copy of the input's and no point moved.
#include <gtest/gtest.h>

#include "core/surface_repair.hpp"

namespace vdc {
namespace {

MeshSource soup(std::vector<Vec3> x, const std::vector<std::array<int32_t, 3>>& tris) {
  MeshSource s;
  s.positions = std::move(x);
  for (const auto& t : tris) s.faces.push_back({Corner{t[0], 0}, Corner{t[1], 0}, Corner{t[2], 0}});
  return s;
}

// A tetrahedron's four faces wound outward (or all inward), its corners from `first` on.
std::vector<std::array<int32_t, 3>> tetrahedron(int32_t first, bool inward = false) {
  std::vector<std::array<int32_t, 3>> t{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  for (auto& f : t) {
    for (auto& i : f) i += first;
    if (inward) std::swap(f[1], f[2]);
  }
  return t;
}

// The repair kept every point where it was and build_mesh takes the result.
void expect_buildable(const MeshSource& in, const RepairedSurface& r) {
  ASSERT_EQ(r.source.size(), r.mesh.positions.size());
  for (std::size_t i = 0; i < r.source.size(); ++i) EXPECT_EQ(r.mesh.positions[i], in.positions[static_cast<std::size_t>(r.source[i])]);
  MeshSource m = r.mesh;
  with_canonical_uvs(m);
  EXPECT_NO_THROW(build_mesh(m));
}

const std::vector<Vec3> kTet{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

TEST(SurfaceRepair, AClosedOutwardSurfaceIsLeftAsItIs) {
  const MeshSource in = soup(kTet, tetrahedron(0));
  const RepairedSurface r = repair_surface(in);
  EXPECT_EQ(r.repairs.summary(), "");
  ASSERT_EQ(r.mesh.faces.size(), in.faces.size());
  for (std::size_t f = 0; f < in.faces.size(); ++f)  // the same faces, positions numbered by first use
    for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(r.source[static_cast<std::size_t>(r.mesh.faces[f][k].node)], in.faces[f][k].node);
  EXPECT_EQ(r.repairs.parts, 1);
  expect_buildable(in, r);
}

TEST(SurfaceRepair, AnInsideOutClosedPartIsTurnedToEncloseVolume) {
  const MeshSource in = soup(kTet, tetrahedron(0, true));
  const RepairedSurface r = repair_surface(in);
  EXPECT_EQ(r.repairs.turned_faces, 4);
  EXPECT_GT(enclosed_volume(r.mesh, r.mesh.positions), 0);
  expect_buildable(in, r);
}

TEST(SurfaceRepair, AFaceAgainstItsNeighboursIsTurned) {
  // A square of two triangles, the second wound the other way: an open part, mostly as given.
  const MeshSource in = soup({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 3, 2}});
  const RepairedSurface r = repair_surface(in);
  EXPECT_EQ(r.repairs.turned_faces, 1);
  EXPECT_EQ(r.repairs.open_edges, 4);
  expect_buildable(in, r);
}

TEST(SurfaceRepair, TwoSolidsTouchingAtAPointGetACopyOfIt) {
  // Two tetrahedra sharing corner 0: two fans of faces around one position.
  std::vector<Vec3> x = kTet;
  x.insert(x.end(), {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}});
  std::vector<std::array<int32_t, 3>> t = tetrahedron(0);
  for (auto f : tetrahedron(0)) {  // the mirror image through the origin, sharing position 0
    for (auto& i : f) i = i == 0 ? 0 : i + 3;
    t.push_back(f);
  }
  const MeshSource in = soup(x, t);
  const RepairedSurface r = repair_surface(in);
  EXPECT_EQ(r.repairs.copied_vertices, 1);
  EXPECT_EQ(r.repairs.parts, 2);
  EXPECT_EQ(r.mesh.positions.size(), 8u);
  expect_buildable(in, r);
}

TEST(SurfaceRepair, AnEdgeOfThreeFacesIsCutOpen) {
  // Three fins on the edge from position 0 to 1.
  const MeshSource in = soup({{0, 0, 0}, {0, 0, 1}, {1, 0, 0.5}, {-1, 0, 0.5}, {0, 1, 0.5}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const RepairedSurface r = repair_surface(in);
  EXPECT_EQ(r.repairs.cut_edges, 1);
  EXPECT_EQ(r.repairs.copied_vertices, 4);  // each end of the edge in three fans
  EXPECT_EQ(r.repairs.parts, 3);
  expect_buildable(in, r);
}

TEST(SurfaceRepair, FacesWithoutAreaOrRepeatedAreDropped) {
  const MeshSource in = soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}}, {{0, 1, 2}, {0, 1, 3}, {1, 2, 0}, {0, 0, 2}});
  const RepairedSurface r = repair_surface(in);
  EXPECT_EQ(r.repairs.dropped_faces, 3);  // collinear, the same corners again, a repeated corner
  EXPECT_EQ(r.mesh.faces.size(), 1u);
  expect_buildable(in, r);
  EXPECT_THROW(repair_surface(soup({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}})), MeshBuildError);
  EXPECT_THROW(repair_surface(soup({{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}}, {{0, 1, 2}})), MeshBuildError);
}

}  // namespace
}  // namespace vdc
