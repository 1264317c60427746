// The crossing guard: a flip or a collapse that would make cloth cross other geometry is refused,
// by the untangler's own count of intersecting pairs; through the remesher, a coarsened sheet
// stays clear of the layer beside it.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/intersection.hpp"
#include "core/mesh_build.hpp"
#include "remesh/crossing_guard.hpp"
#include "remesh/remesher.hpp"

namespace vdc {
namespace {

std::vector<std::array<int32_t, 3>> face_nodes(const Mesh& mesh) {
  std::vector<std::array<int32_t, 3>> faces;
  for (FaceId f : mesh.faces()) faces.push_back({mesh.face_node(f, 0).idx, mesh.face_node(f, 1).idx, mesh.face_node(f, 2).idx});
  return faces;
}

std::vector<Vec3> positions(const Mesh& mesh) {
  std::vector<Vec3> x(static_cast<std::size_t>(mesh.node_capacity()), Vec3::Zero());
  for (NodeId n : mesh.nodes()) x[static_cast<std::size_t>(n.idx)] = mesh.x(n);
  return x;
}

// Intersecting pairs of a mesh's faces with loose triangles, as untangling counts them.
int crossings_with(const Mesh& mesh, const std::vector<Triangle>& others) {
  std::vector<std::array<int32_t, 3>> faces;
  std::vector<Vec3> x;
  for (const Triangle& t : others) {
    const auto base = static_cast<int32_t>(x.size());
    faces.push_back({base, base + 1, base + 2});
    x.insert(x.end(), t.begin(), t.end());
  }
  return count_intersections_between(face_nodes(mesh), positions(mesh), faces, x);
}

// Loose triangles as an obstacle's.
StandingSurfaces obstacle(std::vector<Triangle> triangles) {
  std::vector<int> owners(triangles.size(), -1);
  return StandingSurfaces(std::move(triangles), std::move(owners));
}

std::vector<Triangle> triangles_of(const Mesh& mesh) {
  std::vector<Triangle> t;
  for (FaceId f : mesh.faces()) t.push_back({mesh.x(mesh.face_node(f, 0)), mesh.x(mesh.face_node(f, 1)), mesh.x(mesh.face_node(f, 2))});
  return t;
}

// A unit square folded along its diagonal n0 = (0,0,0) to n1 = (1,1,0), the other corners lifted
// to z = h: a valley. Flipping to the other diagonal turns it into a ridge at z = h.
constexpr double kFold = 0.1;
Mesh valley() {
  MeshSource s;
  s.positions = {{0, 0, 0}, {1, 0, kFold}, {1, 1, 0}, {0, 1, kFold}};
  s.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.faces = {{{{0, 0}, {1, 1}, {2, 2}}}, {{{0, 0}, {2, 2}, {3, 3}}}};
  return build_mesh(s);
}

// A small level triangle at z = h/2 around (0.25, 0.25): under the valley's faces there (their
// height is h |x - y| <= 0.15 h), cut by the ridge's face, whose height h (x + y) passes h/2.
Triangle under_the_ridge() { return {Vec3(0.15, 0.15, kFold / 2), Vec3(0.35, 0.2, kFold / 2), Vec3(0.2, 0.35, kFold / 2)}; }

TEST(CrossingGuard, RefusesAFlipThatCutsThroughALayer) {
  Mesh mesh = valley();
  const EdgeId e = mesh.find_edge(NodeId(0), NodeId(2));
  ASSERT_TRUE(can_flip(mesh, e));
  EXPECT_EQ(crossings_with(mesh, {under_the_ridge()}), 0);
  const StandingSurfaces nothing = obstacle({}), layer = obstacle({under_the_ridge()});
  CrossingGuard clear(mesh, nothing, 0);
  EXPECT_FALSE(clear.adds_crossings(preview_flip(mesh, e)));
  CrossingGuard guard(mesh, layer, 0);
  EXPECT_TRUE(guard.adds_crossings(preview_flip(mesh, e)));
  EXPECT_EQ(guard.refused(), 1);
  // Done anyway, the flip makes the one crossing pair the guard foresaw.
  flip_edge(mesh, e);
  EXPECT_EQ(crossings_with(mesh, {under_the_ridge()}), 1);
}

TEST(CrossingGuard, ComparesWithTheCrossingsTheOperationRemoves) {
  // Already crossed: an upright triangle through the valley's face x > y near (0.6, 0.2), which
  // the ridge's face x + y < 1 covers too: a flip that keeps the one crossing pair adds none.
  Mesh mesh = valley();
  const EdgeId e = mesh.find_edge(NodeId(0), NodeId(2));
  const Triangle post = {Vec3(0.57, 0.17, -1), Vec3(0.63, 0.17, -1), Vec3(0.6, 0.23, 2)};
  ASSERT_EQ(crossings_with(mesh, {post}), 1);
  const StandingSurfaces standing = obstacle({post});
  CrossingGuard guard(mesh, standing, 0);
  EXPECT_FALSE(guard.adds_crossings(preview_flip(mesh, e)));
  flip_edge(mesh, e);
  EXPECT_EQ(crossings_with(mesh, {post}), 1);
}

TEST(CrossingGuard, RefusesACollapseThatFlattensATentThroughAPost) {
  // A 1 m sheet of 2 x 2 cells (world (u, 0, -v)) whose centre node is lifted 0.2 m: a tent over
  // a small upright triangle reaching 0.05 m up beside the centre. Removing the centre flattens
  // the tent onto y = 0, through the triangle.
  Mesh mesh = build_mesh(make_grid(1, 1, 2, 2));
  NodeId centre;
  for (NodeId n : mesh.nodes())
    if ((mesh.x(n) - Vec3(0.5, 0, -0.5)).norm() < 1e-12) centre = n;
  ASSERT_TRUE(centre.valid());
  mesh.x(centre).y() = 0.2;
  const Triangle post = {Vec3(0.43, -0.05, -0.47), Vec3(0.56, -0.05, -0.47), Vec3(0.5, 0.05, -0.47)};
  ASSERT_EQ(crossings_with(mesh, {post}), 0);
  EdgeId e;
  int remove = 0;
  for (EdgeId x : mesh.node_edges(centre)) {
    const int r = mesh.edge_node(x, 0) == centre ? 0 : 1;
    if (can_collapse(mesh, x, r)) {
      e = x;
      remove = r;
      break;
    }
  }
  ASSERT_TRUE(e.valid());
  const StandingSurfaces nothing = obstacle({}), standing = obstacle({post});
  CrossingGuard clear(mesh, nothing, 0);
  EXPECT_FALSE(clear.adds_crossings(preview_collapse(mesh, e, remove)));
  CrossingGuard guard(mesh, standing, 0);
  EXPECT_TRUE(guard.adds_crossings(preview_collapse(mesh, e, remove)));
  collapse_edge(mesh, e, remove);
  EXPECT_GE(crossings_with(mesh, {post}), 1);
}

TEST(CrossingGuard, SeesTheFacesOperationsMade) {
  // The triangle under the ridge as a piece of the garment itself, split before the flip: the
  // guard must look at the halves the split made (the face it knew is gone).
  MeshSource s;
  const Triangle t = under_the_ridge();
  s.positions = {{0, 0, 0}, {1, 0, kFold}, {1, 1, 0}, {0, 1, kFold}, t[0], t[1], t[2]};
  s.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0}, {2.2, 0}, {2, 0.2}};
  s.faces = {{{{0, 0}, {1, 1}, {2, 2}}}, {{{0, 0}, {2, 2}, {3, 3}}}, {{{4, 4}, {5, 5}, {6, 6}}}};
  Mesh mesh = build_mesh(s);
  const EdgeId e = mesh.find_edge(NodeId(0), NodeId(2));
  const StandingSurfaces nothing = obstacle({});
  CrossingGuard guard(mesh, nothing, 0);
  EXPECT_TRUE(guard.adds_crossings(preview_flip(mesh, e)));
  guard.add(split_edge(mesh, mesh.find_edge(NodeId(4), NodeId(5))));
  guard.add(split_edge(mesh, mesh.find_edge(NodeId(5), NodeId(6))));
  EXPECT_TRUE(guard.adds_crossings(preview_flip(mesh, e)));
  EXPECT_EQ(guard.refused(), 2);
}

TEST(CrossingGuard, SeesFacesMadeLongBefore) {
  // As above, but the piece under the ridge split into about sixty faces, then a far piece
  // split as often: the faces that cross have long left the short list for the guard's trees,
  // where the faces the later splits removed are dropped.
  MeshSource s;
  const Triangle t = under_the_ridge();
  const Vec3 far(5, 5, 5);
  s.positions = {{0, 0, 0}, {1, 0, kFold}, {1, 1, 0}, {0, 1, kFold}, t[0], t[1], t[2], far, far + Vec3(0.2, 0, 0), far + Vec3(0, 0.2, 0)};
  s.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0}, {2.2, 0}, {2, 0.2}, {3, 0}, {3.2, 0}, {3, 0.2}};
  s.faces = {{{{0, 0}, {1, 1}, {2, 2}}}, {{{0, 0}, {2, 2}, {3, 3}}}, {{{4, 4}, {5, 5}, {6, 6}}}, {{{7, 7}, {8, 8}, {9, 9}}}};
  Mesh mesh = build_mesh(s);
  const EdgeId e = mesh.find_edge(NodeId(0), NodeId(2));
  const StandingSurfaces nothing = obstacle({});
  CrossingGuard guard(mesh, nothing, 0);
  // Splits every edge of the piece that starts at u = `from` in material space, rounds times.
  auto refine = [&](double from, int rounds) {
    for (int round = 0; round < rounds; ++round) {
      std::vector<EdgeId> edges;
      for (EdgeId x : mesh.edges())
        if (mesh.u(mesh.edge_vert(x, 0, 0)).x() >= from && mesh.u(mesh.edge_vert(x, 0, 0)).x() < from + 1) edges.push_back(x);
      for (EdgeId x : edges)
        if (mesh.alive(x)) guard.add(split_edge(mesh, x));
    }
  };
  refine(2, 4);
  const int piece_faces = mesh.num_faces() - 3;
  refine(3, 4);
  EXPECT_GT(piece_faces, 40);
  EXPECT_GT(mesh.num_faces() - 2 - piece_faces, 40);  // more than the short list holds: it was emptied after the piece
  EXPECT_TRUE(guard.adds_crossings(preview_flip(mesh, e)));
  EXPECT_TRUE(mesh.validate().ok());
}

TEST(CrossingGuard, LooksAtTheGarmentsOwnStandingFacesAsTheyChange) {
  // The standing surfaces hold the garment's own faces too (owner 0); the guard of garment 0
  // looks at its live faces instead, and the valley's flip crosses nothing of them. The layer
  // under the ridge, as garment 1's, is looked at.
  Mesh mesh = valley();
  const EdgeId e = mesh.find_edge(NodeId(0), NodeId(2));
  std::vector<Triangle> triangles = triangles_of(mesh);
  std::vector<int> owners(triangles.size(), 0);
  const StandingSurfaces alone(triangles, owners);
  CrossingGuard guard(mesh, alone, 0);
  EXPECT_FALSE(guard.adds_crossings(preview_flip(mesh, e)));
  triangles.push_back(under_the_ridge());
  owners.push_back(1);
  const StandingSurfaces beside(triangles, owners);
  CrossingGuard guard_beside(mesh, beside, 0);
  EXPECT_TRUE(guard_beside.adds_crossings(preview_flip(mesh, e)));
}

// A 1 m sheet of 20 x 20 cells corrugated along u (height A cos(2 pi u / 0.5)) above a copy of
// itself 1 cm lower: coarsened to 0.5 m faces, its chords would cut the copy.
Mesh corrugated(double drop) {
  MeshSource s = make_grid(1, 1, 20, 20);
  for (Vec3& p : s.positions) p.y() = 0.04 * std::cos(2 * M_PI * p.x() / 0.5) - drop;
  return build_mesh(s);
}

TEST(CrossingGuard, CoarseningSheetStaysClearOfTheLayerBelow) {
  const Mesh below = corrugated(0.01);
  const std::vector<Triangle> layer = triangles_of(below);
  const StandingSurfaces standing = obstacle(layer);
  auto coarsened = [&](const StandingSurfaces* neighbours, RemeshStats& stats) {
    Mesh mesh = corrugated(0);
    auto& s = mesh.vert_attrs().add<Mat2>(kSizingAttr, Mat2::Identity());
    for (VertId v : mesh.verts()) s[v] = Mat2::Identity() / (0.5 * 0.5);
    stats = remesh(mesh, RemeshOptions{}, neighbours, 0);
    return mesh;
  };
  RemeshStats free_stats, guarded_stats;
  const Mesh free = coarsened(nullptr, free_stats);
  const Mesh guarded = coarsened(&standing, guarded_stats);
  ASSERT_EQ(crossings_with(corrugated(0), layer), 0);
  EXPECT_GT(crossings_with(free, layer), 0) << "the unguarded remesh must cross, or the test shows nothing";
  EXPECT_EQ(free_stats.refused, 0);
  EXPECT_EQ(crossings_with(guarded, layer), 0);
  EXPECT_GT(guarded_stats.refused, 0);
  EXPECT_GT(guarded_stats.collapses, 0);
  EXPECT_TRUE(guarded.validate().ok());
  EXPECT_LT(free.num_faces(), guarded.num_faces());
}

}  // namespace
}  // namespace vdc
