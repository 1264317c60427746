// A mesh as bytes and back, exactly: the arrays behind every element and adjacency list, so a
// checkpointed simulation resumes on the mesh it stopped with.
#include <string>

#include "core/mesh.hpp"

namespace vdc {

namespace {
constexpr uint32_t kMeshFormat = 1;

// Every handle names an element below `capacity` (or none, -1, where `may_be_none`).
template <class Container>
bool all_in_range(const Container& handles, std::size_t capacity, bool may_be_none = false) {
  for (const auto& h : handles)
    if (h.idx < (may_be_none ? -1 : 0) || h.idx >= static_cast<int32_t>(capacity)) return false;
  return true;
}

int32_t count_alive(const std::vector<char>& alive) {
  int32_t n = 0;
  for (char a : alive) n += a ? 1 : 0;
  return n;
}
}  // namespace

void Mesh::write_binary(BinaryWriter& out) const {
  out.value(kMeshFormat);
  out.array(node_alive_);
  out.array(x_);
  out.array(v_);
  out.array(flags_);
  out.nested(node_verts_);
  out.nested(node_edges_);
  out.array(vert_alive_);
  out.array(u_);
  out.array(vert_node_);
  out.nested(vert_faces_);
  out.array(edge_alive_);
  out.array(edge_nodes_);
  out.array(edge_faces_);
  out.array(face_alive_);
  out.array(face_verts_);
  out.array(face_edges_);
  node_attrs_.write(out);
  vert_attrs_.write(out);
  edge_attrs_.write(out);
  face_attrs_.write(out);
}

Mesh Mesh::read_binary(BinaryReader& in) {
  if (in.value<uint32_t>() != kMeshFormat) in.fail("not a mesh of format " + std::to_string(kMeshFormat));
  Mesh m;
  m.node_alive_ = in.array<char>();
  m.x_ = in.array<Vec3>();
  m.v_ = in.array<Vec3>();
  m.flags_ = in.array<uint32_t>();
  m.node_verts_ = in.nested<VertId>();
  m.node_edges_ = in.nested<EdgeId>();
  m.vert_alive_ = in.array<char>();
  m.u_ = in.array<Vec2>();
  m.vert_node_ = in.array<NodeId>();
  m.vert_faces_ = in.nested<FaceId>();
  m.edge_alive_ = in.array<char>();
  m.edge_nodes_ = in.array<std::array<NodeId, 2>>();
  m.edge_faces_ = in.array<std::array<FaceId, 2>>();
  m.face_alive_ = in.array<char>();
  m.face_verts_ = in.array<std::array<VertId, 3>>();
  m.face_edges_ = in.array<std::array<EdgeId, 3>>();
  const std::size_t nodes = m.node_alive_.size(), verts = m.vert_alive_.size(), edges = m.edge_alive_.size(),
                    faces = m.face_alive_.size();
  const bool sizes_agree = m.x_.size() == nodes && m.v_.size() == nodes && m.flags_.size() == nodes && m.node_verts_.size() == nodes &&
                           m.node_edges_.size() == nodes && m.u_.size() == verts && m.vert_node_.size() == verts &&
                           m.vert_faces_.size() == verts && m.edge_nodes_.size() == edges && m.edge_faces_.size() == edges &&
                           m.face_verts_.size() == faces && m.face_edges_.size() == faces;
  if (!sizes_agree) in.fail("the mesh's arrays disagree on its element counts");
  bool ok = all_in_range(m.vert_node_, nodes);
  for (const auto& list : m.node_verts_) ok = ok && all_in_range(list, verts);
  for (const auto& list : m.node_edges_) ok = ok && all_in_range(list, edges);
  for (const auto& list : m.vert_faces_) ok = ok && all_in_range(list, faces);
  for (const auto& e : m.edge_nodes_) ok = ok && all_in_range(e, nodes);
  for (const auto& e : m.edge_faces_) ok = ok && all_in_range(e, faces, true);  // a boundary edge has one face
  for (const auto& f : m.face_verts_) ok = ok && all_in_range(f, verts);
  for (const auto& f : m.face_edges_) ok = ok && all_in_range(f, edges);
  if (!ok) in.fail("the mesh refers to an element it does not have");
  m.live_nodes_ = count_alive(m.node_alive_);
  m.live_verts_ = count_alive(m.vert_alive_);
  m.live_edges_ = count_alive(m.edge_alive_);
  m.live_faces_ = count_alive(m.face_alive_);
  m.node_attrs_.resize(nodes);
  m.vert_attrs_.resize(verts);
  m.edge_attrs_.resize(edges);
  m.face_attrs_.resize(faces);
  m.node_attrs_.read(in);
  m.vert_attrs_.read(in);
  m.edge_attrs_.read(in);
  m.face_attrs_.read(in);
  const ValidationReport report = m.validate();
  if (!report.ok()) in.fail("the mesh is not valid: " + report.summary(1));
  return m;
}

}  // namespace vdc
