// Split, flip and collapse: counts, validity, conservation of material area, attributes, and a
// random sequence of all three that must keep every invariant.
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <string>
#include <tuple>
#include <random>

#include "core/mesh_build.hpp"
#include "remesh/operations.hpp"
#include "scene/garments.hpp"
#include "support/mesh_checks.hpp"

namespace vdc {
namespace {

using test::expect_valid;

double material_area(const Mesh& m) {
  double a = 0;
  for (FaceId f : m.faces()) a += m.material_area(f);
  return a;
}

// An interior edge of the grid (both faces present, not a seam).
EdgeId interior_edge(const Mesh& m) {
  for (EdgeId e : m.edges())
    if (!m.is_boundary(e)) return e;
  return EdgeId();
}

TEST(Split, InteriorEdgeAddsANodeTwoFacesThreeEdges) {
  Mesh m = build_mesh(make_grid(1, 1, 4, 4));
  auto& tag = m.face_attrs().add<int>("tag", -1);
  for (FaceId f : m.faces()) tag[f] = f.idx;
  auto& rest = m.edge_attrs().add<double>("rest", 0.0);
  // An edge at the centre node (12 of the 5 x 5 nodes), so no edge around it is on the boundary.
  EdgeId e = m.node_edges(NodeId(12)).front();
  rest[e] = 0.25;
  const int faces = m.num_faces(), edges = m.num_edges(), nodes = m.num_nodes(), verts = m.num_verts();
  const double area = material_area(m);
  const Vec3 mid = 0.5 * (m.x(m.edge_node(e, 0)) + m.x(m.edge_node(e, 1)));
  const int f0 = m.edge_face(e, 0).idx, f1 = m.edge_face(e, 1).idx;
  OpRecord r = split_edge(m, e);
  expect_valid(m);
  EXPECT_EQ(m.num_nodes(), nodes + 1);
  EXPECT_EQ(m.num_verts(), verts + 1);
  EXPECT_EQ(m.num_faces(), faces + 2);
  EXPECT_EQ(m.num_edges(), edges + 3);
  EXPECT_EQ(r.added_faces.size(), 4u);
  EXPECT_EQ(r.removed_faces.size(), 2u);
  EXPECT_EQ(r.removed_edges.size(), 1u);
  EXPECT_EQ(r.added_edges.size(), 4u);
  EXPECT_NEAR(material_area(m), area, 1e-15);
  EXPECT_EQ((m.x(r.added_nodes[0]) - mid).norm(), 0.0);
  // The new faces carry their parent's tag; the two halves of the edge its rest angle.
  for (FaceId f : r.added_faces) EXPECT_TRUE(tag[f] == f0 || tag[f] == f1);
  int halves = 0;
  for (EdgeId x : r.added_edges) halves += rest[x] == 0.25;
  EXPECT_EQ(halves, 2);
}

TEST(Split, BoundaryEdgeAddsOneFace) {
  Mesh m = build_mesh(make_grid(1, 1, 2, 2));
  EdgeId e;
  for (EdgeId x : m.edges())
    if (m.is_boundary(x)) e = x;
  const int faces = m.num_faces(), edges = m.num_edges();
  split_edge(m, e, 0.3);
  expect_valid(m);
  EXPECT_EQ(m.num_faces(), faces + 1);
  EXPECT_EQ(m.num_edges(), edges + 2);
  EXPECT_NEAR(material_area(m), 1.0, 1e-15);
}

TEST(Split, SeamEdgeGivesEachSideItsOwnVert) {
  // Two pattern pieces sewn along positions 1-2: left piece uvs near 0, right piece shifted.
  MeshSource s;
  s.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3(1, 0, -1)};
  s.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(3, 0), Vec2(3, 1), Vec2(4, 1)};
  s.faces = {{Corner{0, 0}, Corner{1, 1}, Corner{2, 2}}, {Corner{1, 3}, Corner{3, 5}, Corner{2, 4}}};
  Mesh m = build_mesh(s);
  EdgeId seam = m.find_edge(NodeId(1), NodeId(2));
  ASSERT_TRUE(m.is_seam(seam));
  OpRecord r = split_edge(m, seam);
  expect_valid(m);
  EXPECT_EQ(r.added_verts.size(), 2u);
  EXPECT_EQ(m.node_verts(r.added_nodes[0]).size(), 2u);
  EXPECT_NEAR(material_area(m), 1.0, 1e-15);
  int seams = 0;
  for (EdgeId e : m.edges()) seams += m.is_seam(e);
  EXPECT_EQ(seams, 2);
}

TEST(Flip, DiagonalFlipsAndFlipsBack) {
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));
  EdgeId diag = interior_edge(m);
  ASSERT_TRUE(can_flip(m, diag));
  const NodeId a = m.edge_node(diag, 0), b = m.edge_node(diag, 1);
  OpRecord r = flip_edge(m, diag);
  expect_valid(m);
  EXPECT_EQ(m.num_faces(), 2);
  EXPECT_FALSE(m.find_edge(a, b).valid());
  EdgeId back = interior_edge(m);
  ASSERT_TRUE(can_flip(m, back));
  flip_edge(m, back);
  expect_valid(m);
  EXPECT_TRUE(m.find_edge(a, b).valid());
  EXPECT_NEAR(material_area(m), 1.0, 1e-15);
  for (EdgeId e : m.edges()) {
    if (m.is_boundary(e)) {
      EXPECT_FALSE(can_flip(m, e));
    }
  }
}

TEST(Flip, RefusedWhenTheQuadIsNotConvex) {
  // Faces (0,1,2) and (1,0,3) with 3 placed so that the quad 0,3,1,2 is a dart: the other
  // diagonal would leave the quad.
  MeshSource s;
  s.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, 1), Vec2(-0.3, -0.05)};
  for (const Vec2& u : s.uvs) s.positions.emplace_back(u.x(), 0, -u.y());
  s.faces = {{Corner{0, 0}, Corner{1, 1}, Corner{2, 2}}, {Corner{1, 1}, Corner{0, 0}, Corner{3, 3}}};
  Mesh m = build_mesh(s);
  EXPECT_FALSE(can_flip(m, m.find_edge(NodeId(0), NodeId(1))));
}

TEST(Collapse, InteriorNodeOntoNeighbourKeepsArea) {
  Mesh m = build_mesh(make_grid(1, 1, 4, 4));
  // Node 12 is the centre of the 5x5 grid of nodes.
  NodeId centre(12);
  EdgeId e = m.node_edges(centre).front();
  int remove = m.edge_node(e, 0) == centre ? 0 : 1;
  ASSERT_TRUE(can_collapse(m, e, remove));
  const int faces = m.num_faces();
  OpRecord r = collapse_edge(m, e, remove);
  expect_valid(m);
  EXPECT_FALSE(m.alive(centre));
  EXPECT_EQ(m.num_faces(), faces - 2);
  EXPECT_EQ(r.removed_nodes.size(), 1u);
  EXPECT_NEAR(material_area(m), 1.0, 1e-14);
}

TEST(Collapse, RefusesHandlesCornersAndBoundaryNodesOffTheBoundary) {
  Mesh m = build_mesh(make_grid(1, 1, 4, 4));
  NodeId centre(12);
  m.flags(centre) |= kNodeHandle;
  for (EdgeId e : m.node_edges(centre)) EXPECT_FALSE(can_collapse(m, e, m.edge_node(e, 0) == centre ? 0 : 1));
  NodeId corner(0);
  for (EdgeId e : m.node_edges(corner)) EXPECT_FALSE(can_collapse(m, e, m.edge_node(e, 0) == corner ? 0 : 1));
  // Node 2 is mid-way along the bottom boundary: it may slide along the boundary only.
  NodeId side(2);
  for (EdgeId e : m.node_edges(side)) {
    int remove = m.edge_node(e, 0) == side ? 0 : 1;
    EXPECT_EQ(can_collapse(m, e, remove), m.is_boundary(e)) << "edge to node " << m.edge_node(e, 1 - remove).idx;
  }
}

// 400 random splits, flips and collapses on m: every one keeps the mesh valid, material area
// (borders are straight), positive faces and node attributes with their nodes; returns the
// counts of splits, flips, collapses and collapses along a seam done.
std::array<int, 4> random_operations(Mesh& m, std::mt19937& rng, const std::string& what) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  auto& uid = m.node_attrs().add<int>("uid", -1);
  std::map<int, Vec3> position_of;  // uid -> position when created
  int next = 0;
  for (NodeId n : m.nodes()) {
    uid[n] = next;
    position_of[next++] = m.x(n);
  }
  const double area = material_area(m);
  std::array<int, 4> done{0, 0, 0, 0};
  const bool failed_before = ::testing::Test::HasFailure();
  for (int op = 0; op < 400; ++op) {
    std::vector<EdgeId> edges, seams;
    for (EdgeId e : m.edges()) (m.is_seam(e) ? seams : edges).push_back(e);
    // Seams are few: half the picks go to them, when there are any.
    const std::vector<EdgeId>& pool = !seams.empty() && rng() % 2 ? seams : edges;
    EdgeId e = pool[rng() % pool.size()];
    int kind = static_cast<int>(rng() % 3);
    if (kind == 0 && m.num_faces() < 600) {
      OpRecord r = split_edge(m, e, 0.3 + 0.4 * (U(rng) + 1) / 2);
      uid[r.added_nodes[0]] = next;
      position_of[next++] = m.x(r.added_nodes[0]);
      ++done[0];
    } else if (kind == 1 && can_flip(m, e)) {
      flip_edge(m, e);
      ++done[1];
    } else if (kind == 2) {
      int remove = static_cast<int>(rng() % 2);
      if (can_collapse(m, e, remove)) {
        done[3] += m.is_seam(e);
        collapse_edge(m, e, remove);
        ++done[2];
      }
    }
    ValidationReport v = m.validate();
    EXPECT_TRUE(v.ok()) << what << " op " << op << "\n" << v.summary();
    EXPECT_NEAR(material_area(m), area, 1e-12 * area) << what << " op " << op;
    for (FaceId f : m.faces()) EXPECT_GT(m.material_area(f), 0) << what << " op " << op;
    if (op % 50 == 49) m.compact();
    for (NodeId n : m.nodes()) EXPECT_EQ(m.x(n), position_of.at(uid[n])) << what << ": node attributes lost their node";
    if (!failed_before && ::testing::Test::HasFailure()) break;
  }
  return done;
}

TEST(Operations, RandomSequencesKeepEveryInvariant) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    // A grid with jittered interior nodes, world space slightly wavy.
    MeshSource src = make_grid(1, 1, 8, 8);
    for (std::size_t i = 0; i < src.uvs.size(); ++i) {
      Vec2& u = src.uvs[i];
      bool edge = u.x() == 0 || u.y() == 0 || u.x() == 1 || u.y() == 1;
      if (!edge) u += 0.03 * Vec2(U(rng), U(rng));
      src.positions[i] = Vec3(u.x(), 0.05 * std::sin(4 * u.x() + trial), -u.y());
    }
    Mesh m = build_mesh(src);
    const auto [splits, flips, collapses, seam_collapses] = random_operations(m, rng, "grid trial " + std::to_string(trial));
    EXPECT_GT(splits, 50);
    EXPECT_GT(flips, 10);
    EXPECT_GT(collapses, 10);
    EXPECT_EQ(seam_collapses, 0);
  }
}

int count_seam_edges(const Mesh& m) {
  int n = 0;
  for (EdgeId e : m.edges()) n += m.is_seam(e);
  return n;
}

TEST(Operations, RandomSequencesOnASewnTubeKeepEveryInvariantAndTheSeamClosed) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 3; ++trial) {
    Mesh m = build_mesh(make_tube({12, 1.0, 0.2, 0.4, 0.2, 0.1}));
    const auto [splits, flips, collapses, seam_collapses] = random_operations(m, rng, "tube trial " + std::to_string(trial));
    EXPECT_GT(splits, 50);
    EXPECT_GT(collapses, 10);
    EXPECT_GT(seam_collapses, 2);
    // Still one closed tube: the seam runs the full height, nodes on it have a vert each side.
    EXPECT_GE(count_seam_edges(m), 1);
    for (NodeId n : m.nodes()) EXPECT_LE(m.node_verts(n).size(), 2u);
    EXPECT_EQ(m.validate().ok(), true);
  }
}

bool on_rim(const Mesh& m, NodeId n) {
  for (EdgeId e : m.node_edges(n))
    if (m.is_boundary(e)) return true;
  return false;
}

// The nodes of a straight cylinder's back seam strictly between its two rims.
std::vector<NodeId> inner_seam_nodes(const Mesh& m) {
  std::vector<NodeId> out;
  for (NodeId n : m.nodes())
    if (m.node_verts(n).size() == 2 && !on_rim(m, n)) out.push_back(n);
  return out;
}

TEST(Collapse, SeamNodeSlidesAlongTheSeamMergingBothOfItsVerts) {
  Mesh m = build_mesh(make_tube({12, 1.0, 0.2, 0.4, 0.2, 0.1}));
  const std::vector<NodeId> seam = inner_seam_nodes(m);
  ASSERT_GE(seam.size(), 3u);
  const NodeId r = seam[1];
  int seams_at_r = 0;
  for (EdgeId e : m.node_edges(r)) {
    const int remove = m.edge_node(e, 0) == r ? 0 : 1;
    // Off the seam it stays; along the seam it may go.
    EXPECT_EQ(can_collapse(m, e, remove), m.is_seam(e)) << "edge to node " << m.edge_node(e, 1 - remove).idx;
    seams_at_r += m.is_seam(e);
  }
  ASSERT_EQ(seams_at_r, 2);
  EdgeId along;
  for (EdgeId e : m.node_edges(r))
    if (m.is_seam(e)) along = e;
  const int faces = m.num_faces(), verts = m.num_verts(), nodes = m.num_nodes(), seam_edges = count_seam_edges(m);
  const double area = material_area(m);
  OpRecord rec = collapse_edge(m, along, m.edge_node(along, 0) == r ? 0 : 1);
  expect_valid(m);
  EXPECT_EQ(m.num_nodes(), nodes - 1);
  EXPECT_EQ(m.num_verts(), verts - 2);
  EXPECT_EQ(m.num_faces(), faces - 2);
  EXPECT_EQ(rec.removed_verts.size(), 2u);
  EXPECT_EQ(count_seam_edges(m), seam_edges - 1);
  EXPECT_NEAR(material_area(m), area, 1e-12 * area);
}

TEST(Collapse, SeamEndsStay) {
  Mesh m = build_mesh(make_tube({12, 1.0, 0.2, 0.4, 0.2, 0.1}));
  int ends = 0;
  for (NodeId n : m.nodes()) {
    if (m.node_verts(n).size() != 2 || !on_rim(m, n)) continue;
    ++ends;
    for (EdgeId e : m.node_edges(n)) EXPECT_FALSE(can_collapse(m, e, m.edge_node(e, 0) == n ? 0 : 1, 0.5));
  }
  EXPECT_EQ(ends, 2);
}

TEST(Collapse, CurvedBoundaryNodeGoesOnlyWithinTheSagBound) {
  // Node 2, mid-way along the bottom of a 4 x 4 grid, pushed out of the line by d: its border
  // neighbours are 0.5 apart, so it lies d / 0.5 of the chord from it.
  for (const auto& [d, border_sag, allowed] : std::vector<std::tuple<double, double, bool>>{
           {0.01, 0.025, true}, {0.0124, 0.025, true}, {0.0126, 0.025, false}, {0.01, 0.0, false}, {-0.01, 0.025, true}}) {
    MeshSource src = make_grid(1, 1, 4, 4);
    src.uvs[2].y() -= d;
    Mesh m = build_mesh(src);
    const NodeId side(2);
    const EdgeId along = m.find_edge(side, NodeId(1));
    ASSERT_TRUE(along.valid());
    EXPECT_EQ(can_collapse(m, along, m.edge_node(along, 0) == side ? 0 : 1, border_sag), allowed) << "d " << d << " sag " << border_sag;
  }
}

}  // namespace
}  // namespace vdc
