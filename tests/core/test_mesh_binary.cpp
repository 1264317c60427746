// Meshes as bytes (src/core/mesh_binary.cpp): a mesh read back is the same mesh, dead slots,
// adjacency order and attributes included, and damaged bytes are refused, never trusted.
#include <gtest/gtest.h>

#include <cstring>

#include "core/binary_io.hpp"
#include "core/mesh_build.hpp"
#include "remesh/operations.hpp"

namespace vdc {
namespace {

// A grid after splits and flips, not compacted: tombstoned faces and edges, adjacency lists in
// the order the operations left them, and attributes of every element kind.
Mesh worked_mesh() {
  Mesh m = build_mesh(make_grid(1, 1, 4, 3));
  for (NodeId n : m.nodes()) m.v(n) = Vec3(0.1 * n.idx, -0.2, 0.05 * n.idx * n.idx);
  int ops = 0;
  for (int round = 0; round < 3; ++round) {
    std::vector<EdgeId> edges;
    for (EdgeId e : m.edges()) edges.push_back(e);
    for (std::size_t i = 0; i < edges.size(); i += 5) {
      if (!m.alive(edges[i])) continue;
      if ((i + static_cast<std::size_t>(round)) % 2 == 0) {
        split_edge(m, edges[i], 0.4);
        ++ops;
      } else if (can_flip(m, edges[i])) {
        flip_edge(m, edges[i]);
        ++ops;
      }
    }
  }
  EXPECT_GT(ops, 10);
  auto& which = m.node_attrs().add<int32_t>("which", -1);
  auto& anchor = m.node_attrs().add<Vec3>("anchor", Vec3::Zero());
  for (NodeId n : m.nodes()) {
    which[n] = n.idx % 3 - 1;
    anchor[n] = m.x(n) * 2;
  }
  auto& sizing = m.vert_attrs().add<Mat2>("sizing", Mat2::Identity());
  for (VertId v : m.verts()) sizing[v] << 1 + v.idx, 0.5, 0.5, 2;
  auto& length = m.edge_attrs().add<double>("length", 0.0);
  for (EdgeId e : m.edges()) length[e] = (m.x(m.edge_node(e, 0)) - m.x(m.edge_node(e, 1))).norm();
  auto& factor = m.face_attrs().add<double>("view_factor", 1.0);
  auto& centre = m.face_attrs().add<Vec2>("centre", Vec2::Zero());
  for (FaceId f : m.faces()) {
    factor[f] = 0.01 * f.idx;
    centre[f] = (m.u(m.face_vert(f, 0)) + m.u(m.face_vert(f, 1)) + m.u(m.face_vert(f, 2))) / 3;
  }
  return m;
}

std::string bytes_of(const Mesh& m) {
  BinaryWriter out;
  m.write_binary(out);
  return out.bytes();
}

Mesh read_back(const std::string& bytes) {
  BinaryReader in(bytes.data(), bytes.size());
  Mesh m = Mesh::read_binary(in);
  EXPECT_TRUE(in.at_end());
  return m;
}

TEST(MeshBinary, ReadsBackTheSameMeshSlotForSlot) {
  const Mesh a = worked_mesh();
  ASSERT_FALSE(a.is_compact());
  const std::string bytes = bytes_of(a);
  const Mesh b = read_back(bytes);
  EXPECT_TRUE(b.validate().ok()) << b.validate().summary();
  EXPECT_EQ(bytes_of(b), bytes);  // every array, so also every dead slot and list order
  EXPECT_EQ(b.num_nodes(), a.num_nodes());
  EXPECT_EQ(b.num_verts(), a.num_verts());
  EXPECT_EQ(b.num_edges(), a.num_edges());
  EXPECT_EQ(b.num_faces(), a.num_faces());
  EXPECT_EQ(b.face_capacity(), a.face_capacity());
  EXPECT_EQ(b.edge_capacity(), a.edge_capacity());
  for (NodeId n : a.nodes()) {
    EXPECT_EQ(b.x(n), a.x(n));
    EXPECT_EQ(b.v(n), a.v(n));
    EXPECT_EQ(b.node_edges(n), a.node_edges(n));
    EXPECT_EQ(b.node_attrs().get<int32_t>("which")[n], a.node_attrs().get<int32_t>("which")[n]);
    EXPECT_EQ(b.node_attrs().get<Vec3>("anchor")[n], a.node_attrs().get<Vec3>("anchor")[n]);
  }
  for (VertId v : a.verts()) {
    EXPECT_EQ(b.u(v), a.u(v));
    EXPECT_EQ(b.vert_faces(v), a.vert_faces(v));
    EXPECT_EQ(b.vert_attrs().get<Mat2>("sizing")[v], a.vert_attrs().get<Mat2>("sizing")[v]);
  }
  for (FaceId f : a.faces()) {
    EXPECT_EQ(b.face_verts(f), a.face_verts(f));
    EXPECT_EQ(b.face_edges(f), a.face_edges(f));
    EXPECT_EQ(b.face_attrs().get<double>("view_factor")[f], a.face_attrs().get<double>("view_factor")[f]);
    EXPECT_EQ(b.face_attrs().get<Vec2>("centre")[f], a.face_attrs().get<Vec2>("centre")[f]);
  }
  for (EdgeId e : a.edges()) EXPECT_EQ(b.edge_attrs().get<double>("length")[e], a.edge_attrs().get<double>("length")[e]);
  // Defaults travel too: a new element takes the same default value.
  Mesh c = b;
  const NodeId n = c.add_node(Vec3::Zero());
  EXPECT_EQ(c.node_attrs().get<int32_t>("which")[n], -1);
}

TEST(MeshBinary, EveryCutOffPrefixIsRefused) {
  const std::string bytes = bytes_of(worked_mesh());
  int refused = 0;
  for (std::size_t n = 0; n < bytes.size(); n += 61) {
    const std::string prefix = bytes.substr(0, n);
    BinaryReader in(prefix.data(), prefix.size());
    EXPECT_THROW(Mesh::read_binary(in), BinaryFormatError) << n << " of " << bytes.size() << " bytes";
    ++refused;
  }
  EXPECT_GT(refused, 50);
}

TEST(MeshBinary, AnImpossibleLengthIsRefusedBeforeAnythingIsAllocated) {
  std::string bytes = bytes_of(worked_mesh());
  // Just after the format number: the length of the node array, made far larger than the data.
  const uint64_t big = uint64_t{1} << 60;
  std::memcpy(bytes.data() + sizeof(uint32_t), &big, sizeof big);
  BinaryReader in(bytes.data(), bytes.size());
  try {
    Mesh::read_binary(in);
    FAIL() << "read a mesh with 2^60 nodes";
  } catch (const BinaryFormatError& e) {
    EXPECT_EQ(e.offset(), sizeof(uint32_t) + sizeof(uint64_t));
    EXPECT_NE(e.problem().find("runs past the end"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vdc
