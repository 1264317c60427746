// Tests of the two-space mesh (src/core/mesh.*) and of build_mesh / make_grid (src/core/mesh_build.*).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/mesh.hpp"
#include "core/mesh_build.hpp"
#include "support/text.hpp"
#include "support/mesh_checks.hpp"

namespace vdc {
namespace {

using test::expect_valid;

// Edges of an nx by ny grid: horizontal rows, vertical columns and one diagonal per cell.
int grid_edges(int nx, int ny) { return nx * (ny + 1) + ny * (nx + 1) + nx * ny; }

int count_boundary(const Mesh& m) {
  int n = 0;
  for (EdgeId e : m.edges()) n += m.is_boundary(e) ? 1 : 0;
  return n;
}

int count_seams(const Mesh& m) {
  int n = 0;
  for (EdgeId e : m.edges()) n += m.is_seam(e) ? 1 : 0;
  return n;
}

using test::contains;

// The only vert of a node of a seamless mesh. build_mesh numbers verts in order of first use, so
// vert k is in general not the vert of node k.
VertId vert_at(const Mesh& m, int node) {
  const auto& vs = m.node_verts(NodeId(node));
  EXPECT_EQ(vs.size(), 1u) << "node " << node;
  return vs.empty() ? VertId() : vs[0];
}

// Runs build_mesh and returns the MeshBuildError it throws (fails the test if none).
MeshBuildError expect_build_error(const MeshSource& src) {
  try {
    build_mesh(src);
  } catch (const MeshBuildError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "build_mesh threw something other than MeshBuildError: " << e.what();
    return MeshBuildError(-2, "wrong exception");
  }
  ADD_FAILURE() << "build_mesh accepted a mesh it should reject";
  return MeshBuildError(-2, "no exception");
}

// A face whose three corners each get their own uv, laid out counter-clockwise at `origin`
// (every face is then its own pattern piece in material space).
std::array<Corner, 3> own_uv_face(MeshSource& src, int32_t a, int32_t b, int32_t c, Vec2 origin) {
  auto k = static_cast<int32_t>(src.uvs.size());
  src.uvs.push_back(origin);
  src.uvs.push_back(origin + Vec2(1, 0));
  src.uvs.push_back(origin + Vec2(0, 1));
  return {Corner{a, k}, Corner{b, k + 1}, Corner{c, k + 2}};
}

// ----------------------------------------------------------------------------------------------
// Grid

TEST(MeshGrid, CountsAreaNormalsAndValidity) {
  const int nx = 4, ny = 3;
  MeshSource src = make_grid(1, 1, nx, ny);
  EXPECT_EQ(src.positions.size(), 20u);
  EXPECT_EQ(src.uvs.size(), 20u);
  EXPECT_EQ(src.faces.size(), 24u);
  Mesh m = build_mesh(src);
  expect_valid(m);
  EXPECT_TRUE(m.is_compact());
  EXPECT_EQ(m.num_nodes(), 20);
  EXPECT_EQ(m.num_verts(), 20);  // no seam: one vert per node
  EXPECT_EQ(m.num_faces(), 24);
  EXPECT_EQ(grid_edges(nx, ny), 43);
  EXPECT_EQ(m.num_edges(), grid_edges(nx, ny));
  EXPECT_EQ(count_boundary(m), 2 * (nx + ny));
  EXPECT_EQ(count_seams(m), 0);

  double material = 0, world = 0;
  for (FaceId f : m.faces()) {
    EXPECT_GT(m.material_area(f), 0) << "face " << f.idx;
    EXPECT_NEAR(m.material_area(f), 1.0 / (2 * nx * ny), 1e-15);
    material += m.material_area(f);
    world += m.world_area(f);
    Vec3 n = m.world_normal(f);
    EXPECT_NEAR(n.x(), 0, 1e-12) << "face " << f.idx;
    EXPECT_NEAR(n.y(), 1, 1e-12) << "face " << f.idx;
    EXPECT_NEAR(n.z(), 0, 1e-12) << "face " << f.idx;
  }
  EXPECT_NEAR(material, 1.0, 1e-12);
  EXPECT_NEAR(world, 1.0, 1e-12);

  // World space is (u, 0, -v) and every node is used: positions keep their order.
  for (NodeId n : m.nodes()) {
    ASSERT_EQ(m.node_verts(n).size(), 1u);
    VertId v = m.node_verts(n)[0];
    EXPECT_EQ(m.x(n), Vec3(m.u(v).x(), 0.0, -m.u(v).y()));
    EXPECT_EQ(m.x(n), src.positions[static_cast<std::size_t>(n.idx)]);
  }
  // Every edge lists its faces on the correct side and is found from both ends.
  for (EdgeId e : m.edges()) {
    EXPECT_EQ(m.find_edge(m.edge_node(e, 0), m.edge_node(e, 1)), e);
    EXPECT_EQ(m.find_edge(m.edge_node(e, 1), m.edge_node(e, 0)), e);
    int sides = m.edge_face(e, 0).valid() + m.edge_face(e, 1).valid();
    EXPECT_EQ(sides, m.is_boundary(e) ? 1 : 2);
  }
}

TEST(MeshGrid, NonSquareSizes) {
  Mesh m = build_mesh(make_grid(2.0, 0.5, 5, 2));
  expect_valid(m);
  EXPECT_EQ(m.num_nodes(), 18);
  EXPECT_EQ(m.num_faces(), 20);
  EXPECT_EQ(m.num_edges(), grid_edges(5, 2));
  EXPECT_EQ(count_boundary(m), 2 * (5 + 2));
  double area = 0;
  for (FaceId f : m.faces()) area += m.material_area(f);
  EXPECT_NEAR(area, 1.0, 1e-12);
}

TEST(MeshGrid, MeshSourceGivesBackTheSameFaces) {
  MeshSource src = make_grid(1, 1, 3, 2);
  Mesh m = build_mesh(src);
  MeshSource back = mesh_source(m);
  // Every position is used, so nodes keep their indices.
  EXPECT_EQ(back.positions, src.positions);
  ASSERT_EQ(back.faces.size(), src.faces.size());
  ASSERT_EQ(back.uvs.size(), src.uvs.size());
  // Verts are numbered in order of first use, so uv indices may differ, but every corner keeps
  // its position index and its uv value.
  for (std::size_t f = 0; f < src.faces.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(back.faces[f][k].node, src.faces[f][k].node) << "face " << f << " corner " << k;
      EXPECT_EQ(back.uvs[static_cast<std::size_t>(back.faces[f][k].uv)], src.uvs[static_cast<std::size_t>(src.faces[f][k].uv)])
          << "face " << f << " corner " << k;
    }
  // A source already in first-use order comes back exactly.
  MeshSource again = mesh_source(build_mesh(back));
  EXPECT_EQ(again.positions, back.positions);
  EXPECT_EQ(again.uvs, back.uvs);
  EXPECT_EQ(again.faces, back.faces);
}

TEST(MeshGrid, VertsAreNumberedInOrderOfFirstUse) {
  // make_grid(1, 1, 1, 1): faces (0, 1, 3) and (0, 3, 2), so verts are nodes 0, 1, 3, 2.
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));
  ASSERT_EQ(m.num_verts(), 4);
  EXPECT_EQ(m.vert_node(VertId(0)).idx, 0);
  EXPECT_EQ(m.vert_node(VertId(1)).idx, 1);
  EXPECT_EQ(m.vert_node(VertId(2)).idx, 3);
  EXPECT_EQ(m.vert_node(VertId(3)).idx, 2);
}

// ----------------------------------------------------------------------------------------------
// add_face refusals

struct Snapshot {
  int nodes, verts, edges, faces, node_cap, vert_cap, edge_cap, face_cap;
  std::vector<std::vector<FaceId>> vert_faces;
  std::vector<std::vector<EdgeId>> node_edges;
  explicit Snapshot(const Mesh& m)
      : nodes(m.num_nodes()), verts(m.num_verts()), edges(m.num_edges()), faces(m.num_faces()),
        node_cap(m.node_capacity()), vert_cap(m.vert_capacity()), edge_cap(m.edge_capacity()),
        face_cap(m.face_capacity()) {
    for (VertId v : m.verts()) vert_faces.push_back(m.vert_faces(v));
    for (NodeId n : m.nodes()) node_edges.push_back(m.node_edges(n));
  }
  void expect_same(const Mesh& m) const {
    Snapshot now(m);
    EXPECT_EQ(now.nodes, nodes);
    EXPECT_EQ(now.verts, verts);
    EXPECT_EQ(now.edges, edges);
    EXPECT_EQ(now.faces, faces);
    EXPECT_EQ(now.node_cap, node_cap);
    EXPECT_EQ(now.vert_cap, vert_cap);
    EXPECT_EQ(now.edge_cap, edge_cap);
    EXPECT_EQ(now.face_cap, face_cap);
    EXPECT_EQ(now.vert_faces, vert_faces);
    EXPECT_EQ(now.node_edges, node_edges);
    EXPECT_EQ(m.face_attrs().size(), static_cast<std::size_t>(m.face_capacity()));
    EXPECT_EQ(m.edge_attrs().size(), static_cast<std::size_t>(m.edge_capacity()));
  }
};

// make_grid(1, 1, 1, 1): nodes 0 (0,0), 1 (1,0), 2 (0,1), 3 (1,1); faces 0 = (0, 1, 3), 1 = (0, 3, 2).
TEST(MeshAddFace, RefusesThirdFaceOnEdge) {
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));
  ASSERT_EQ(m.num_faces(), 2);
  EdgeId diag = m.find_edge(NodeId(0), NodeId(3));
  ASSERT_TRUE(diag.valid());
  ASSERT_FALSE(m.is_boundary(diag));
  // A new node above the sheet and a vert for it; face (3, 0, new) would be a third face on 0-3.
  NodeId n = m.add_node(Vec3(0.5, 1.0, -0.5));
  VertId v = m.add_vert(n, Vec2(0.5, -0.5));
  const VertId v0 = vert_at(m, 0), v3 = vert_at(m, 3);
  Snapshot before(m);
  for (auto [a, b, c] : {std::array<VertId, 3>{v3, v0, v}, std::array<VertId, 3>{v0, v3, v},
                         // The refused edge comes second: the new edges n-3 and 0-n must not be created.
                         std::array<VertId, 3>{v, v3, v0}, std::array<VertId, 3>{v, v0, v3}}) {
    try {
      m.add_face(a, b, c);
      ADD_FAILURE() << "third face on an edge accepted: verts " << a.idx << " " << b.idx << " " << c.idx;
    } catch (const TopologyError& e) {
      EXPECT_TRUE(contains(e.what(), "non-manifold")) << e.what();
    }
  }
  before.expect_same(m);
  expect_valid(m);
  EXPECT_EQ(m.edge_face(diag, 0).idx + m.edge_face(diag, 1).idx, 1);  // still faces 0 and 1
  EXPECT_FALSE(m.find_edge(n, NodeId(0)).valid());
  EXPECT_FALSE(m.find_edge(n, NodeId(3)).valid());
}

TEST(MeshAddFace, RefusesSameOrientationFace) {
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));
  // Face 0 runs 0 -> 1 along the boundary edge 0-1 (v = 0 side).
  EdgeId e01 = m.find_edge(NodeId(0), NodeId(1));
  ASSERT_TRUE(e01.valid());
  ASSERT_TRUE(m.is_boundary(e01));
  NodeId n = m.add_node(Vec3(0.5, 0.0, 0.5));
  VertId v = m.add_vert(n, Vec2(0.5, -0.5));
  Snapshot before(m);
  // (new, 0, 1) runs 0 -> 1 like face 0: inconsistent orientation. The bad edge is second so the
  // check must happen before edge new-0 is created.
  try {
    m.add_face(v, vert_at(m, 0), vert_at(m, 1));
    ADD_FAILURE() << "same-orientation face accepted";
  } catch (const TopologyError& e) {
    EXPECT_TRUE(contains(e.what(), "inconsistently oriented")) << e.what();
  }
  before.expect_same(m);
  expect_valid(m);
  EXPECT_TRUE(m.is_boundary(e01));

  // The other orientation is fine: (1, 0, new) is counter-clockwise in material space.
  FaceId f = m.add_face(vert_at(m, 1), vert_at(m, 0), v);
  EXPECT_GT(m.material_area(f), 0);
  expect_valid(m);
  EXPECT_EQ(m.num_faces(), 3);
  EXPECT_EQ(m.num_edges(), 7);
  EXPECT_FALSE(m.is_boundary(e01));
  EXPECT_FALSE(m.is_seam(e01));
  EXPECT_EQ(m.face_attrs().size(), 3u);
  // And now a face on the far side of 0-1 again is a third face.
  NodeId n2 = m.add_node(Vec3(0.5, 0.0, 1.0));
  VertId v2 = m.add_vert(n2, Vec2(0.5, -1.0));
  Snapshot before2(m);
  EXPECT_THROW(m.add_face(vert_at(m, 1), vert_at(m, 0), v2), TopologyError);
  before2.expect_same(m);
  expect_valid(m);
}

TEST(MeshAddFace, RefusesRepeatedNodeAndDeadVert) {
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));
  const VertId v0 = vert_at(m, 0), v1 = vert_at(m, 1), v2 = vert_at(m, 2);
  VertId extra = m.add_vert(NodeId(1), Vec2(5, 5));  // a second vert of node 1
  Snapshot before(m);
  EXPECT_THROW(m.add_face(v0, v1, extra), TopologyError);
  EXPECT_THROW(m.add_face(v0, v0, v2), TopologyError);
  EXPECT_THROW(m.add_face(VertId(0), VertId(1), VertId(99)), TopologyError);
  before.expect_same(m);
  m.remove_vert(extra);
  EXPECT_THROW(m.add_face(v1, v0, extra), TopologyError);
  expect_valid(m);
}

TEST(MeshAddFace, RemoveVertAndNodeRefuseWhileInUse) {
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));
  EXPECT_THROW(m.remove_vert(VertId(0)), TopologyError);
  EXPECT_THROW(m.remove_node(NodeId(0)), TopologyError);
  EXPECT_THROW(m.remove_face(FaceId(7)), TopologyError);
  m.remove_face(FaceId(0));
  EXPECT_THROW(m.remove_face(FaceId(0)), TopologyError);
  // Node 1 only belonged to face 0.
  const VertId v1 = vert_at(m, 1);
  EXPECT_TRUE(m.vert_faces(v1).empty());
  EXPECT_THROW(m.remove_node(NodeId(1)), TopologyError);  // still has its vert
  m.remove_vert(v1);
  EXPECT_TRUE(m.node_edges(NodeId(1)).empty());
  m.remove_node(NodeId(1));
  EXPECT_FALSE(m.alive(NodeId(1)));
  EXPECT_THROW(m.remove_node(NodeId(1)), TopologyError);
  expect_valid(m);
  EXPECT_EQ(m.num_nodes(), 3);
  EXPECT_EQ(m.num_verts(), 3);
  EXPECT_EQ(m.num_edges(), 3);
  EXPECT_EQ(m.num_faces(), 1);
}

// ----------------------------------------------------------------------------------------------
// Removal and compaction

// make_grid(1, 1, 2, 2): node k at (k % 3, k / 3) / 2. Faces (as nodes):
// 0 (0,1,4) 1 (0,4,3) 2 (1,2,4) 3 (2,5,4) 4 (3,4,6) 5 (4,7,6) 6 (4,5,8) 7 (4,8,7).
// Verts are numbered in order of first use: nodes 0, 1, 4, 3, 2, 5, 6, 7, 8.
TEST(MeshCompact, RemoveFacesThenCompact) {
  MeshSource src = make_grid(1, 1, 2, 2);
  Mesh m = build_mesh(src);
  ASSERT_EQ(m.num_nodes(), 9);
  ASSERT_EQ(m.num_verts(), 9);
  ASSERT_EQ(m.num_faces(), 8);
  ASSERT_EQ(m.num_edges(), 16);
  auto face_nodes = [&m](FaceId f) {
    return std::array<int, 3>{m.face_node(f, 0).idx, m.face_node(f, 1).idx, m.face_node(f, 2).idx};
  };
  ASSERT_EQ(face_nodes(FaceId(3)), (std::array<int, 3>{2, 5, 4}));
  ASSERT_EQ(face_nodes(FaceId(2)), (std::array<int, 3>{1, 2, 4}));
  const VertId dead_vert = vert_at(m, 2);
  ASSERT_EQ(dead_vert.idx, 4);

  auto& ftag = m.face_attrs().add<int>("tag", -1);
  auto& ntag = m.node_attrs().add<int>("tag", -1);
  auto& vtag = m.vert_attrs().add<int>("tag", -1);
  auto& etag = m.edge_attrs().add<int>("tag", -1);
  auto& npos = m.node_attrs().add<Vec3>("pos", Vec3::Zero());
  for (FaceId f : m.faces()) ftag[f] = f.idx;
  for (NodeId n : m.nodes()) ntag[n] = n.idx, npos[n] = m.x(n);
  for (VertId v : m.verts()) vtag[v] = v.idx;
  for (EdgeId e : m.edges()) etag[e] = e.idx;
  // Remember the old connectivity under the old indices.
  std::vector<std::array<int, 2>> old_edge_nodes;
  for (EdgeId e : m.edges()) old_edge_nodes.push_back({m.edge_node(e, 0).idx, m.edge_node(e, 1).idx});
  std::vector<std::array<VertId, 3>> old_face_verts;
  for (FaceId f : m.faces()) old_face_verts.push_back(m.face_verts(f));
  std::vector<int> old_vert_node;
  for (VertId v : m.verts()) old_vert_node.push_back(m.vert_node(v).idx);

  const EdgeId e25 = m.find_edge(NodeId(2), NodeId(5)), e12 = m.find_edge(NodeId(1), NodeId(2)),
               e24 = m.find_edge(NodeId(2), NodeId(4)), e45 = m.find_edge(NodeId(4), NodeId(5)),
               e14 = m.find_edge(NodeId(1), NodeId(4));
  for (EdgeId e : {e25, e12, e24, e45, e14}) ASSERT_TRUE(e.valid());

  m.remove_face(FaceId(3));
  expect_valid(m);
  EXPECT_FALSE(m.alive(FaceId(3)));
  EXPECT_EQ(m.num_faces(), 7);
  EXPECT_EQ(m.num_edges(), 15);  // only the boundary edge 2-5 goes
  EXPECT_FALSE(m.alive(e25));
  EXPECT_TRUE(m.alive(e24) && m.alive(e45));
  EXPECT_TRUE(m.is_boundary(e24) && m.is_boundary(e45));
  EXPECT_FALSE(m.find_edge(NodeId(2), NodeId(5)).valid());

  m.remove_face(FaceId(2));
  expect_valid(m);
  EXPECT_EQ(m.num_faces(), 6);
  EXPECT_EQ(m.num_edges(), 13);
  EXPECT_FALSE(m.alive(e12));
  EXPECT_FALSE(m.alive(e24));
  EXPECT_TRUE(m.alive(e14) && m.is_boundary(e14));
  // Node 2 is left with nothing.
  EXPECT_TRUE(m.vert_faces(dead_vert).empty());
  EXPECT_TRUE(m.node_edges(NodeId(2)).empty());
  m.remove_vert(dead_vert);
  m.remove_node(NodeId(2));
  expect_valid(m);
  EXPECT_EQ(m.num_nodes(), 8);
  EXPECT_EQ(m.num_verts(), 8);
  EXPECT_FALSE(m.is_compact());
  EXPECT_EQ(m.node_capacity(), 9);
  EXPECT_EQ(m.vert_capacity(), 9);
  EXPECT_EQ(m.face_capacity(), 8);

  // Live ranges skip the tombstones.
  std::vector<int> live_faces;
  for (FaceId f : m.faces()) live_faces.push_back(f.idx);
  EXPECT_EQ(live_faces, (std::vector<int>{0, 1, 4, 5, 6, 7}));

  CompactionMap map = m.compact();
  expect_valid(m);
  EXPECT_TRUE(m.is_compact());
  EXPECT_EQ(map.face, (std::vector<int32_t>{0, 1, -1, -1, 2, 3, 4, 5}));
  EXPECT_EQ(map.node, (std::vector<int32_t>{0, 1, -1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(map.vert, (std::vector<int32_t>{0, 1, 2, 3, -1, 4, 5, 6, 7}));
  ASSERT_EQ(map.edge.size(), 16u);
  int32_t next = 0;
  for (std::size_t i = 0; i < map.edge.size(); ++i) {
    auto ei = static_cast<int32_t>(i);
    if (ei == e25.idx || ei == e12.idx || ei == e24.idx)
      EXPECT_EQ(map.edge[i], -1) << "edge " << i;
    else
      EXPECT_EQ(map.edge[i], next++) << "edge " << i;
  }
  EXPECT_EQ(next, 13);
  EXPECT_EQ(m.num_nodes(), 8);
  EXPECT_EQ(m.num_verts(), 8);
  EXPECT_EQ(m.num_edges(), 13);
  EXPECT_EQ(m.num_faces(), 6);
  EXPECT_EQ(m.node_capacity(), 8);
  EXPECT_EQ(m.vert_capacity(), 8);
  EXPECT_EQ(m.edge_capacity(), 13);
  EXPECT_EQ(m.face_capacity(), 6);

  // Attributes follow their elements.
  ASSERT_EQ(ftag.size(), 6u);
  ASSERT_EQ(ntag.size(), 8u);
  ASSERT_EQ(vtag.size(), 8u);
  ASSERT_EQ(etag.size(), 13u);
  EXPECT_EQ(ftag.raw(), (std::vector<int>{0, 1, 4, 5, 6, 7}));
  EXPECT_EQ(ntag.raw(), (std::vector<int>{0, 1, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(vtag.raw(), (std::vector<int>{0, 1, 2, 3, 5, 6, 7, 8}));
  for (FaceId f : m.faces()) {
    int old = ftag[f];
    EXPECT_EQ(map.face[static_cast<std::size_t>(old)], f.idx);
    for (int k = 0; k < 3; ++k) {
      VertId ov = old_face_verts[static_cast<std::size_t>(old)][static_cast<std::size_t>(k)];
      int on = old_vert_node[static_cast<std::size_t>(ov.idx)];
      EXPECT_EQ(vtag[m.face_vert(f, k)], ov.idx);
      EXPECT_EQ(ntag[m.face_node(f, k)], on);
      EXPECT_EQ(m.u(m.face_vert(f, k)), src.uvs[static_cast<std::size_t>(on)]);
      EXPECT_EQ(m.x(m.face_node(f, k)), src.positions[static_cast<std::size_t>(on)]);
    }
  }
  for (NodeId n : m.nodes()) {
    EXPECT_EQ(map.node[static_cast<std::size_t>(ntag[n])], n.idx);
    EXPECT_EQ(npos[n], m.x(n));
    EXPECT_EQ(m.x(n), src.positions[static_cast<std::size_t>(ntag[n])]);
  }
  for (VertId v : m.verts()) {
    EXPECT_EQ(map.vert[static_cast<std::size_t>(vtag[v])], v.idx);
    EXPECT_EQ(ntag[m.vert_node(v)], old_vert_node[static_cast<std::size_t>(vtag[v])]);
    EXPECT_EQ(m.u(v), src.uvs[static_cast<std::size_t>(ntag[m.vert_node(v)])]);
  }
  for (EdgeId e : m.edges()) {
    const auto& old = old_edge_nodes[static_cast<std::size_t>(etag[e])];
    EXPECT_EQ(map.edge[static_cast<std::size_t>(etag[e])], e.idx);
    EXPECT_EQ(ntag[m.edge_node(e, 0)], old[0]);
    EXPECT_EQ(ntag[m.edge_node(e, 1)], old[1]);
  }

  // The compacted mesh is fully usable: rebuild the removed corner with a fresh node.
  NodeId n2 = m.add_node(Vec3(1.0, 0.0, 0.0));
  VertId v2 = m.add_vert(n2, Vec2(1.0, 0.0));
  EXPECT_EQ(ntag[n2], -1);  // new elements get the default value
  EXPECT_EQ(vtag[v2], -1);
  // Old nodes 1, 4, 5 are now 1, 3, 4.
  FaceId fa = m.add_face(vert_at(m, 1), v2, vert_at(m, 3));
  FaceId fb = m.add_face(v2, vert_at(m, 4), vert_at(m, 3));
  EXPECT_EQ(ftag[fa], -1);
  EXPECT_EQ(ftag[fb], -1);
  expect_valid(m);
  EXPECT_EQ(m.num_faces(), 8);
  EXPECT_EQ(m.num_edges(), 16);
  EXPECT_EQ(count_boundary(m), 8);
  EXPECT_EQ(etag.size(), 16u);
  for (FaceId f : m.faces()) EXPECT_GT(m.material_area(f), 0);
}

TEST(MeshCompact, CompactOfCompactMeshIsIdentity) {
  Mesh m = build_mesh(make_grid(1, 1, 2, 3));
  CompactionMap map = m.compact();
  expect_valid(m);
  for (std::size_t i = 0; i < map.node.size(); ++i) EXPECT_EQ(map.node[i], static_cast<int32_t>(i));
  for (std::size_t i = 0; i < map.edge.size(); ++i) EXPECT_EQ(map.edge[i], static_cast<int32_t>(i));
  EXPECT_EQ(map.node.size(), 12u);
  EXPECT_EQ(map.vert.size(), 12u);
  EXPECT_EQ(map.edge.size(), static_cast<std::size_t>(grid_edges(2, 3)));
  EXPECT_EQ(map.face.size(), 12u);
}

TEST(MeshCompact, CopiedMeshHasIndependentAttributes) {
  Mesh a = build_mesh(make_grid(1, 1, 1, 1));
  auto& tag = a.face_attrs().add<int>("tag", 7);
  Mesh b = a;
  b.face_attrs().get<int>("tag")[FaceId(0)] = 3;
  EXPECT_EQ(tag[FaceId(0)], 7);
  b.remove_face(FaceId(0));
  b.compact();
  EXPECT_EQ(b.face_attrs().get<int>("tag").size(), 1u);
  EXPECT_EQ(tag.size(), 2u);
  expect_valid(a);
  expect_valid(b);
}

// ----------------------------------------------------------------------------------------------
// Property test: random removals, re-additions and compactions keep every invariant.

TEST(MeshProperty, RandomEditsKeepInvariants) {
  MeshSource src = make_grid(1, 1, 6, 6);
  Mesh m = build_mesh(src);
  // Every element carries a uid that never changes; a model keyed by uid checks that attributes
  // follow their elements through compaction.
  auto& node_uid = m.node_attrs().add<int>("uid", -1);
  auto& vert_uid = m.vert_attrs().add<int>("uid", -1);
  auto& edge_key = m.edge_attrs().add<std::pair<int, int>>("nodes", {-1, -1});
  auto& face_uid = m.face_attrs().add<int>("uid", -1);
  std::vector<Vec3> node_pos;
  std::vector<Vec2> vert_uv;
  std::vector<int> vert_node_uid;
  std::map<int, std::array<int, 3>> face_model;  // live face uid -> vert uids
  int next_face_uid = 0;
  for (NodeId n : m.nodes()) {
    node_uid[n] = static_cast<int>(node_pos.size());
    node_pos.push_back(m.x(n));
  }
  for (VertId v : m.verts()) {
    vert_uid[v] = static_cast<int>(vert_uv.size());
    vert_uv.push_back(m.u(v));
    vert_node_uid.push_back(node_uid[m.vert_node(v)]);
  }
  auto key_of = [&](EdgeId e) {
    int a = node_uid[m.edge_node(e, 0)], b = node_uid[m.edge_node(e, 1)];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  auto label_new_edges = [&]() {
    for (EdgeId e : m.edges())
      if (edge_key[e].first < 0) edge_key[e] = key_of(e);
  };
  auto record_face = [&](FaceId f) {
    face_uid[f] = next_face_uid;
    face_model[next_face_uid++] = {vert_uid[m.face_vert(f, 0)], vert_uid[m.face_vert(f, 1)], vert_uid[m.face_vert(f, 2)]};
  };
  label_new_edges();
  for (FaceId f : m.faces()) record_face(f);

  auto check = [&](int op) {
    ValidationReport r = m.validate();
    ASSERT_TRUE(r.ok()) << "after operation " << op << ":\n" << r.summary();
    ASSERT_EQ(m.node_attrs().size(), static_cast<std::size_t>(m.node_capacity()));
    ASSERT_EQ(m.vert_attrs().size(), static_cast<std::size_t>(m.vert_capacity()));
    ASSERT_EQ(m.edge_attrs().size(), static_cast<std::size_t>(m.edge_capacity()));
    ASSERT_EQ(m.face_attrs().size(), static_cast<std::size_t>(m.face_capacity()));
    ASSERT_EQ(node_uid.size(), static_cast<std::size_t>(m.node_capacity()));
    ASSERT_EQ(vert_uid.size(), static_cast<std::size_t>(m.vert_capacity()));
    ASSERT_EQ(edge_key.size(), static_cast<std::size_t>(m.edge_capacity()));
    ASSERT_EQ(face_uid.size(), static_cast<std::size_t>(m.face_capacity()));
    ASSERT_EQ(m.num_faces(), static_cast<int>(face_model.size())) << "op " << op;
    for (NodeId n : m.nodes()) {
      ASSERT_GE(node_uid[n], 0);
      ASSERT_EQ(m.x(n), node_pos[static_cast<std::size_t>(node_uid[n])]) << "op " << op;
      ASSERT_FALSE(m.node_verts(n).empty()) << "op " << op;  // orphans are always removed
    }
    for (VertId v : m.verts()) {
      ASSERT_GE(vert_uid[v], 0);
      ASSERT_EQ(m.u(v), vert_uv[static_cast<std::size_t>(vert_uid[v])]) << "op " << op;
      ASSERT_EQ(node_uid[m.vert_node(v)], vert_node_uid[static_cast<std::size_t>(vert_uid[v])]) << "op " << op;
      ASSERT_FALSE(m.vert_faces(v).empty()) << "op " << op;
    }
    for (EdgeId e : m.edges()) ASSERT_EQ(edge_key[e], key_of(e)) << "op " << op;
    std::set<int> seen;
    for (FaceId f : m.faces()) {
      auto it = face_model.find(face_uid[f]);
      ASSERT_NE(it, face_model.end()) << "op " << op;
      ASSERT_TRUE(seen.insert(face_uid[f]).second);
      for (int k = 0; k < 3; ++k) ASSERT_EQ(vert_uid[m.face_vert(f, k)], it->second[static_cast<std::size_t>(k)]) << "op " << op;
      ASSERT_GT(m.material_area(f), 0);
    }
  };
  check(-1);
  if (HasFatalFailure()) return;

  std::mt19937 rng(20240611u);
  std::vector<std::array<int, 3>> removed;  // vert uids of removed faces, candidates to re-add
  int removals = 0, additions = 0, refusals = 0, compactions = 0;
  for (int op = 0; op < 200; ++op) {
    bool remove = m.num_faces() > 0 && (rng() % 100 < 45 || m.num_verts() < 3);
    if (remove) {
      std::vector<FaceId> live;
      for (FaceId f : m.faces()) live.push_back(f);
      FaceId f = live[rng() % live.size()];
      std::array<VertId, 3> vs = m.face_verts(f);
      removed.push_back(face_model.at(face_uid[f]));
      face_model.erase(face_uid[f]);
      m.remove_face(f);
      // An operation keeps vertices manifold: a removal that leaves a bow-tie is undone.
      bool bow_tie = false;
      for (VertId v : vs) bow_tie = bow_tie || m.fan_count(m.vert_node(v)) > 1;
      if (bow_tie) {
        record_face(m.add_face(vs[0], vs[1], vs[2]));
        label_new_edges();
        removed.pop_back();
        ++refusals;
      }
      for (VertId v : vs) {
        if (bow_tie) break;
        if (!m.alive(v) || !m.vert_faces(v).empty()) continue;
        NodeId n = m.vert_node(v);
        m.remove_vert(v);
        if (m.node_verts(n).empty()) {
          EXPECT_TRUE(m.node_edges(n).empty());
          m.remove_node(n);
        }
      }
      removals += bow_tie ? 0 : 1;
    } else if (m.num_verts() >= 3) {
      std::map<int, VertId> by_uid;
      std::vector<VertId> live;
      for (VertId v : m.verts()) by_uid[vert_uid[v]] = v, live.push_back(v);
      std::array<VertId, 3> vs{};
      bool have = false;
      // Half the time, try to put back a removed face whose verts all survive.
      if (rng() % 2 == 0 && !removed.empty()) {
        for (int tries = 0; tries < 10 && !have; ++tries) {
          const auto& r = removed[rng() % removed.size()];
          if (by_uid.count(r[0]) && by_uid.count(r[1]) && by_uid.count(r[2])) {
            vs = {by_uid[r[0]], by_uid[r[1]], by_uid[r[2]]};
            have = true;
          }
        }
      }
      if (!have) {
        for (VertId& v : vs) v = live[rng() % live.size()];
      }
      double area = 0.5 * signed_area2(m.u(vs[0]), m.u(vs[1]), m.u(vs[2]));
      if (area < 0) std::swap(vs[1], vs[2]);
      if (std::abs(area) < 1e-9) {
        // Degenerate or repeated vert: add_face must still refuse a repeated node cleanly.
        if (vs[0] == vs[1] || vs[1] == vs[2] || vs[0] == vs[2]) {
          Snapshot before(m);
          EXPECT_THROW(m.add_face(vs[0], vs[1], vs[2]), TopologyError);
          before.expect_same(m);
        }
      } else {
        Snapshot before(m);
        try {
          FaceId f = m.add_face(vs[0], vs[1], vs[2]);
          record_face(f);
          label_new_edges();
          bool bow_tie = false;
          for (VertId v : vs) bow_tie = bow_tie || m.fan_count(m.vert_node(v)) > 1;
          if (bow_tie) {  // undone: the face would join two fans at a vertex
            face_model.erase(face_uid[f]);
            m.remove_face(f);
            ++refusals;
          } else {
            ++additions;
          }
        } catch (const TopologyError&) {
          before.expect_same(m);
          ++refusals;
        }
      }
    }
    if ((op + 1) % 20 == 0) {
      const int caps[4] = {m.node_capacity(), m.vert_capacity(), m.edge_capacity(), m.face_capacity()};
      std::vector<char> was_alive_face;
      for (int i = 0; i < caps[3]; ++i) was_alive_face.push_back(m.alive(FaceId(i)));
      std::vector<char> was_alive_node;
      for (int i = 0; i < caps[0]; ++i) was_alive_node.push_back(m.alive(NodeId(i)));
      CompactionMap map = m.compact();
      ++compactions;
      EXPECT_TRUE(m.is_compact());
      ASSERT_EQ(map.node.size(), static_cast<std::size_t>(caps[0]));
      ASSERT_EQ(map.vert.size(), static_cast<std::size_t>(caps[1]));
      ASSERT_EQ(map.edge.size(), static_cast<std::size_t>(caps[2]));
      ASSERT_EQ(map.face.size(), static_cast<std::size_t>(caps[3]));
      int32_t k = 0;
      for (int i = 0; i < caps[3]; ++i)
        EXPECT_EQ(map.face[static_cast<std::size_t>(i)], was_alive_face[static_cast<std::size_t>(i)] ? k++ : -1);
      EXPECT_EQ(k, m.num_faces());
      k = 0;
      for (int i = 0; i < caps[0]; ++i)
        EXPECT_EQ(map.node[static_cast<std::size_t>(i)], was_alive_node[static_cast<std::size_t>(i)] ? k++ : -1);
      EXPECT_EQ(k, m.num_nodes());
    }
    check(op);
    if (HasFatalFailure()) return;
  }
  RecordProperty("removals", removals);
  RecordProperty("additions", additions);
  RecordProperty("refusals", refusals);
  // The sequence must actually exercise every path.
  EXPECT_GT(removals, 25);
  EXPECT_GT(additions, 10);
  EXPECT_GT(refusals, 5);
  EXPECT_EQ(compactions, 10);
  EXPECT_GT(m.num_faces(), 0);
}

// ----------------------------------------------------------------------------------------------
// Seams

// Positions: 0 (0,0,0), 1 (1,0,0), 2 (0,0,-1), 3 (1,0,-1). Triangles (0,1,2) and (1,3,2) share
// positions 1 and 2 in world space but are separate pattern pieces in material space.
MeshSource two_piece_source() {
  MeshSource s;
  s.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3(1, 0, -1)};
  s.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1),          // piece A
           Vec2(2.5, 0), Vec2(2.5, 1), Vec2(1.5, 1)};  // piece B, 0.5 m to the right
  s.faces = {{Corner{0, 0}, Corner{1, 1}, Corner{2, 2}}, {Corner{1, 3}, Corner{3, 4}, Corner{2, 5}}};
  return s;
}

TEST(MeshSeam, TwoPiecesShareAnEdge) {
  Mesh m = build_mesh(two_piece_source());
  expect_valid(m);
  EXPECT_EQ(m.num_nodes(), 4);
  EXPECT_EQ(m.num_verts(), 6);
  EXPECT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.num_edges(), 5);
  EdgeId shared = m.find_edge(NodeId(1), NodeId(2));
  ASSERT_TRUE(shared.valid());
  EXPECT_FALSE(m.is_boundary(shared));
  EXPECT_TRUE(m.is_seam(shared));
  int boundary = 0, seams = 0;
  for (EdgeId e : m.edges()) {
    boundary += m.is_boundary(e);
    seams += m.is_seam(e);
  }
  EXPECT_EQ(boundary, 4);
  EXPECT_EQ(seams, 1);
  EXPECT_EQ(m.node_verts(NodeId(0)).size(), 1u);
  EXPECT_EQ(m.node_verts(NodeId(1)).size(), 2u);
  EXPECT_EQ(m.node_verts(NodeId(2)).size(), 2u);
  EXPECT_EQ(m.node_verts(NodeId(3)).size(), 1u);
  // Each side of the seam sees its own verts at both ends.
  for (int side = 0; side < 2; ++side) {
    FaceId f = m.edge_face(shared, side);
    ASSERT_TRUE(f.valid());
    for (int i = 0; i < 2; ++i) {
      VertId v = m.edge_vert(shared, side, i);
      ASSERT_TRUE(v.valid());
      EXPECT_EQ(m.vert_node(v), m.edge_node(shared, i));
      const auto& fv = m.face_verts(f);
      EXPECT_NE(std::find(fv.begin(), fv.end(), v), fv.end());
    }
  }
  EXPECT_NE(m.edge_vert(shared, 0, 0), m.edge_vert(shared, 1, 0));
  EXPECT_NE(m.edge_vert(shared, 0, 1), m.edge_vert(shared, 1, 1));
  // Opposite nodes are 0 and 3.
  std::set<int> opp = {m.opposite_node(shared, 0).idx, m.opposite_node(shared, 1).idx};
  EXPECT_EQ(opp, (std::set<int>{0, 3}));
  // Material areas are both 0.5 and positive.
  for (FaceId f : m.faces()) EXPECT_DOUBLE_EQ(m.material_area(f), 0.5);
}

TEST(MeshSeam, SeamOnlyAtOneEndStillCounts) {
  // Same as above but the pieces share the uv of position 1: the edge is a seam because of end 2.
  MeshSource s;
  s.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3(1, 0, -1)};
  s.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 1), Vec2(0.2, 1.0)};
  s.faces = {{Corner{0, 0}, Corner{1, 1}, Corner{2, 2}}, {Corner{1, 1}, Corner{3, 3}, Corner{2, 4}}};
  Mesh m = build_mesh(s);
  expect_valid(m);
  EXPECT_EQ(m.num_verts(), 5);
  EdgeId shared = m.find_edge(NodeId(1), NodeId(2));
  ASSERT_TRUE(shared.valid());
  EXPECT_TRUE(m.is_seam(shared));
  EXPECT_EQ(m.node_verts(NodeId(1)).size(), 1u);
  EXPECT_EQ(m.node_verts(NodeId(2)).size(), 2u);
  // And an ordinary interior edge is not a seam.
  Mesh g = build_mesh(make_grid(1, 1, 1, 1));
  EdgeId diag = g.find_edge(NodeId(0), NodeId(3));
  ASSERT_TRUE(diag.valid());
  EXPECT_FALSE(g.is_seam(diag));
}

// ----------------------------------------------------------------------------------------------
// validate() detects breakage

TEST(MeshValidate, DetectsNonFinitePosition) {
  Mesh m = build_mesh(make_grid(1, 1, 2, 2));
  ASSERT_TRUE(m.validate().ok());
  m.x(NodeId(4)).y() = std::numeric_limits<double>::quiet_NaN();
  ValidationReport r = m.validate();
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.summary(), "node 4")) << r.summary();
  EXPECT_TRUE(contains(r.summary(), "non-finite")) << r.summary();
  m.x(NodeId(4)).y() = 0;
  EXPECT_TRUE(m.validate().ok());
  m.v(NodeId(0)).x() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(m.validate().ok());
}

TEST(MeshValidate, DetectsClockwiseOrDegenerateMaterialFace) {
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));
  // Move node 3's vert onto the line through nodes 0 and 1: face 0 (0, 1, 3) becomes degenerate.
  m.u(vert_at(m, 3)) = Vec2(2, 0);
  ValidationReport r = m.validate();
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.summary(), "face 0")) << r.summary();
  // A clockwise face added through the low-level API is reported too.
  Mesh g = build_mesh(make_grid(1, 1, 1, 1));
  NodeId n = g.add_node(Vec3(0.5, 0, 0.5));
  VertId v = g.add_vert(n, Vec2(0.5, 0.5));  // inside the sheet: (1, 0, v) is clockwise
  FaceId f = g.add_face(vert_at(g, 1), vert_at(g, 0), v);
  ValidationReport r2 = g.validate();
  ASSERT_FALSE(r2.ok());
  EXPECT_TRUE(contains(r2.summary(), "face " + std::to_string(f.idx))) << r2.summary();
  EXPECT_TRUE(contains(r2.summary(), "material")) << r2.summary();
}

TEST(MeshValidate, SummaryTruncates) {
  ValidationReport r;
  // (appended rather than `"p" + std::to_string(i)`, which GCC 12 misreads as an overlapping copy)
  for (int i = 0; i < 15; ++i) r.problems.push_back(std::string("p").append(std::to_string(i)));
  std::string s = r.summary(10);
  EXPECT_TRUE(contains(s, "p9"));
  EXPECT_FALSE(contains(s, "p10"));
  EXPECT_TRUE(contains(s, "5 more"));
}

// ----------------------------------------------------------------------------------------------
// build_mesh rejections: the error names the offending face and the problem.

// A valid first face so that the offending face is never face 0.
MeshSource base_source() {
  MeshSource s;
  s.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, -1)};
  s.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  s.faces = {{Corner{0, 0}, Corner{1, 1}, Corner{2, 2}}};
  return s;
}

TEST(MeshBuild, RejectsNonManifoldEdge) {
  MeshSource s = base_source();
  s.positions.push_back(Vec3(0, 1, 0));   // 3
  s.positions.push_back(Vec3(0, -1, 0));  // 4
  s.faces.push_back(own_uv_face(s, 1, 0, 3, Vec2(3, 0)));  // other side of 0-1: fine
  s.faces.push_back(own_uv_face(s, 1, 0, 4, Vec2(6, 0)));  // third face on 0-1
  MeshBuildError e = expect_build_error(s);
  EXPECT_EQ(e.face, 2);
  EXPECT_TRUE(contains(e.what(), "non-manifold")) << e.what();
  // The same faces without the third one build fine.
  s.faces.pop_back();
  Mesh m = build_mesh(s);
  expect_valid(m);
}

TEST(MeshBuild, RejectsInconsistentOrientation) {
  MeshSource s = base_source();
  s.positions.push_back(Vec3(1, 0, -1));  // 3
  // (0, 1, 3) runs 0 -> 1 like face 0.
  s.faces.push_back(own_uv_face(s, 0, 1, 3, Vec2(3, 0)));
  MeshBuildError e = expect_build_error(s);
  EXPECT_EQ(e.face, 1);
  EXPECT_TRUE(contains(e.what(), "inconsistently oriented")) << e.what();
}

TEST(MeshBuild, RejectsBowTieVertex) {
  MeshSource s = base_source();  // face 0 elsewhere
  for (auto& p : s.positions) p += Vec3(10, 0, 0);
  // Two triangles sharing only position 3.
  s.positions.push_back(Vec3(0, 0, 0));    // 3
  s.positions.push_back(Vec3(1, 0, 0));    // 4
  s.positions.push_back(Vec3(1, 0, -1));   // 5
  s.positions.push_back(Vec3(-1, 0, 0));   // 6
  s.positions.push_back(Vec3(-1, 0, 1));   // 7
  s.faces.push_back(own_uv_face(s, 3, 4, 5, Vec2(3, 0)));
  s.faces.push_back(own_uv_face(s, 3, 6, 7, Vec2(6, 0)));
  MeshBuildError e = expect_build_error(s);
  EXPECT_TRUE(e.face == 1 || e.face == 2) << "face " << e.face;
  EXPECT_TRUE(contains(e.what(), "non-manifold")) << e.what();
  // Joining the two fans through a third face sharing their edges makes the vertex manifold:
  // triangles (3,4,5), (3,5,6), (3,6,7) form one fan.
  s.faces.insert(s.faces.begin() + 2, own_uv_face(s, 3, 5, 6, Vec2(9, 0)));
  Mesh m = build_mesh(s);
  expect_valid(m);
}

TEST(MeshBuild, RejectsBowTieThroughSharedVert) {
  // The bow-tie also shares the uv at its centre: one vert, two fans.
  MeshSource s;
  s.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, -1), Vec3(-1, 0, 0), Vec3(-1, 0, 1)};
  s.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(-1, 0), Vec2(-1, -1)};
  s.faces = {{Corner{0, 0}, Corner{1, 1}, Corner{2, 2}}, {Corner{0, 0}, Corner{3, 3}, Corner{4, 4}}};
  MeshBuildError e = expect_build_error(s);
  EXPECT_TRUE(e.face == 0 || e.face == 1) << "face " << e.face;
  EXPECT_TRUE(contains(e.what(), "non-manifold")) << e.what();
}

TEST(MeshBuild, RejectsZeroMaterialArea) {
  MeshSource s = base_source();
  s.positions.push_back(Vec3(1, 0, -1));  // 3
  s.uvs.push_back(Vec2(2, 0));            // 3: on the line through uv 0 and uv 1
  s.faces.push_back({Corner{1, 1}, Corner{3, 3}, Corner{2, 0}});
  MeshBuildError e = expect_build_error(s);
  EXPECT_EQ(e.face, 1);
  EXPECT_TRUE(contains(e.what(), "material space")) << e.what();
  EXPECT_TRUE(contains(e.what(), "zero area")) << e.what();
}

TEST(MeshBuild, RejectsZeroWorldArea) {
  MeshSource s = base_source();
  s.positions.push_back(Vec3(2, 0, 0));  // 3: collinear with positions 0 and 1
  s.faces.push_back(own_uv_face(s, 1, 0, 3, Vec2(3, 0)));
  MeshBuildError e = expect_build_error(s);
  EXPECT_EQ(e.face, 1);
  EXPECT_TRUE(contains(e.what(), "world space")) << e.what();
  EXPECT_TRUE(contains(e.what(), "zero area")) << e.what();
}

TEST(MeshBuild, RejectsTinyButNonZeroWorldArea) {
  MeshSource s = base_source();
  s.positions.push_back(Vec3(2, 1e-12, 0));  // relative area 1e-12 / 4, below the threshold
  s.faces.push_back(own_uv_face(s, 1, 0, 3, Vec2(3, 0)));
  MeshBuildError e = expect_build_error(s);
  EXPECT_EQ(e.face, 1);
  EXPECT_TRUE(contains(e.what(), "world space")) << e.what();
  // A small but well-shaped triangle is fine at any scale.
  MeshSource t = base_source();
  for (auto& p : t.positions) p *= 1e-4;
  for (auto& u : t.uvs) u *= 1e-4;
  Mesh m = build_mesh(t);
  expect_valid(m);
}

TEST(MeshBuild, RejectsClockwiseMaterialFace) {
  MeshSource s = base_source();
  s.positions.push_back(Vec3(1, 0, -1));  // 3
  s.uvs.push_back(Vec2(0.2, 0.2));        // 3
  // (1, 3, 2) runs 2 -> 1, opposite to face 0, so it fits topologically; but its uvs
  // (1,0), (0.2,0.2), (0,1) turn clockwise.
  s.faces.push_back({Corner{1, 1}, Corner{3, 3}, Corner{2, 2}});
  MeshBuildError e = expect_build_error(s);
  EXPECT_EQ(e.face, 1);
  EXPECT_TRUE(contains(e.what(), "clockwise")) << e.what();
  EXPECT_TRUE(contains(e.what(), "material space")) << e.what();
  EXPECT_FALSE(contains(e.what(), "zero area")) << e.what();
  // With uv 3 at (1,1) the same face is counter-clockwise and accepted.
  s.uvs.back() = Vec2(1, 1);
  Mesh m = build_mesh(s);
  expect_valid(m);
  EXPECT_EQ(m.num_faces(), 2);
}

TEST(MeshBuild, RejectsRepeatedPositionAndBadIndices) {
  MeshSource s = base_source();
  s.faces.push_back({Corner{1, 1}, Corner{1, 0}, Corner{2, 2}});
  MeshBuildError e = expect_build_error(s);
  EXPECT_EQ(e.face, 1);
  EXPECT_TRUE(contains(e.what(), "degenerate")) << e.what();

  MeshSource s2 = base_source();
  s2.faces.push_back({Corner{1, 1}, Corner{0, 0}, Corner{3, 2}});
  MeshBuildError e2 = expect_build_error(s2);
  EXPECT_EQ(e2.face, 1);
  EXPECT_TRUE(contains(e2.what(), "out of range")) << e2.what();

  MeshSource s3 = base_source();
  s3.faces.push_back({Corner{1, 1}, Corner{0, 0}, Corner{2, -1}});
  MeshBuildError e3 = expect_build_error(s3);
  EXPECT_EQ(e3.face, 1);
  EXPECT_TRUE(contains(e3.what(), "out of range")) << e3.what();
}

TEST(MeshBuild, DropsUnusedPositionsAndSharesVerts) {
  MeshSource s = base_source();
  s.positions.insert(s.positions.begin(), Vec3(5, 5, 5));  // unused position 0
  for (auto& c : s.faces[0]) ++c.node;
  Mesh m = build_mesh(s);
  expect_valid(m);
  EXPECT_EQ(m.num_nodes(), 3);
  EXPECT_EQ(m.num_verts(), 3);
  EXPECT_EQ(m.x(NodeId(0)), Vec3(0, 0, 0));
  // A (node, uv) pair used twice is one vert.
  Mesh g = build_mesh(make_grid(1, 1, 2, 1));
  EXPECT_EQ(g.num_verts(), 6);
}

}  // namespace
}  // namespace vdc
