// Two-space garment mesh: nodes in world space, verts in material space, seams where a node has
// several verts. Index handles, tombstones, compaction and attributes that follow both.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/attributes.hpp"
#include "core/handles.hpp"
#include "core/math.hpp"

namespace vdc {

enum NodeFlag : uint32_t {
  kNodeHandle = 1u << 0,  // driven by a handle: remeshing must keep it
};

// Iterates over the live elements of one kind, skipping tombstones.
template <class Tag>
class LiveRange {
 public:
  class Iterator {
   public:
    Iterator(const std::vector<char>* alive, int32_t i) : alive_(alive), i_(i) { skip(); }
    Handle<Tag> operator*() const { return Handle<Tag>(i_); }
    Iterator& operator++() {
      ++i_;
      skip();
      return *this;
    }
    bool operator!=(const Iterator& o) const { return i_ != o.i_; }

   private:
    void skip() {
      while (i_ < static_cast<int32_t>(alive_->size()) && !(*alive_)[static_cast<std::size_t>(i_)]) ++i_;
    }
    const std::vector<char>* alive_;
    int32_t i_;
  };
  explicit LiveRange(const std::vector<char>* alive) : alive_(alive) {}
  Iterator begin() const { return Iterator(alive_, 0); }
  Iterator end() const { return Iterator(alive_, static_cast<int32_t>(alive_->size())); }
  // The live handles in order (for loops that index them, on several threads say).
  std::vector<Handle<Tag>> list() const {
    std::vector<Handle<Tag>> out;
    for (Handle<Tag> h : *this) out.push_back(h);
    return out;
  }

 private:
  const std::vector<char>* alive_;
};

// Old index -> new index for each element kind after compact(); -1 for removed elements.
struct CompactionMap {
  std::vector<int32_t> node, vert, edge, face;
};

struct ValidationReport {
  std::vector<std::string> problems;
  bool ok() const { return problems.empty(); }
  std::string summary(std::size_t max_lines = 10) const;
};

class Mesh {
 public:
  // --- creation and removal (low level; remeshing operations are built from these) ---
  NodeId add_node(const Vec3& x, const Vec3& v = Vec3::Zero());
  VertId add_vert(NodeId node, const Vec2& u);
  // Adds the face (a, b, c), counter-clockwise in material space, creating or reusing its edges.
  // Throws TopologyError if an edge would get a third face or two faces of the same orientation.
  FaceId add_face(VertId a, VertId b, VertId c);
  // Removes the face; edges left without faces are removed with it.
  void remove_face(FaceId f);
  // The vert must have no faces.
  void remove_vert(VertId v);
  // The node must have no verts and no edges.
  void remove_node(NodeId n);
  // Drops tombstones, renumbers densely (order kept) and permutes all attributes.
  CompactionMap compact();
  bool is_compact() const;

  // --- counts and iteration ---
  int32_t num_nodes() const { return live_nodes_; }
  int32_t num_verts() const { return live_verts_; }
  int32_t num_edges() const { return live_edges_; }
  int32_t num_faces() const { return live_faces_; }
  int32_t node_capacity() const { return static_cast<int32_t>(node_alive_.size()); }
  int32_t vert_capacity() const { return static_cast<int32_t>(vert_alive_.size()); }
  int32_t edge_capacity() const { return static_cast<int32_t>(edge_alive_.size()); }
  int32_t face_capacity() const { return static_cast<int32_t>(face_alive_.size()); }
  LiveRange<NodeTag> nodes() const { return LiveRange<NodeTag>(&node_alive_); }
  LiveRange<VertTag> verts() const { return LiveRange<VertTag>(&vert_alive_); }
  LiveRange<EdgeTag> edges() const { return LiveRange<EdgeTag>(&edge_alive_); }
  LiveRange<FaceTag> faces() const { return LiveRange<FaceTag>(&face_alive_); }
  bool alive(NodeId n) const { return in(n.idx, node_alive_); }
  bool alive(VertId v) const { return in(v.idx, vert_alive_); }
  bool alive(EdgeId e) const { return in(e.idx, edge_alive_); }
  bool alive(FaceId f) const { return in(f.idx, face_alive_); }

  // --- node data (world space) ---
  Vec3& x(NodeId n) { return x_[at(n)]; }
  const Vec3& x(NodeId n) const { return x_[at(n)]; }
  Vec3& v(NodeId n) { return v_[at(n)]; }
  const Vec3& v(NodeId n) const { return v_[at(n)]; }
  uint32_t& flags(NodeId n) { return flags_[at(n)]; }
  uint32_t flags(NodeId n) const { return flags_[at(n)]; }
  const std::vector<VertId>& node_verts(NodeId n) const { return node_verts_[at(n)]; }
  const std::vector<EdgeId>& node_edges(NodeId n) const { return node_edges_[at(n)]; }

  // --- vert data (material space) ---
  Vec2& u(VertId v) { return u_[at(v)]; }
  const Vec2& u(VertId v) const { return u_[at(v)]; }
  NodeId vert_node(VertId v) const { return vert_node_[at(v)]; }
  const std::vector<FaceId>& vert_faces(VertId v) const { return vert_faces_[at(v)]; }

  // --- faces: corner i is vert i; edge i joins corners i and i+1 ---
  const std::array<VertId, 3>& face_verts(FaceId f) const { return face_verts_[at(f)]; }
  VertId face_vert(FaceId f, int i) const { return face_verts_[at(f)][static_cast<std::size_t>(i)]; }
  NodeId face_node(FaceId f, int i) const { return vert_node(face_vert(f, i)); }
  const std::array<EdgeId, 3>& face_edges(FaceId f) const { return face_edges_[at(f)]; }

  // --- edges: face(e, 0) runs node 0 -> node 1 in its counter-clockwise order, face(e, 1) the
  // other way. Either may be invalid on a boundary, never both. ---
  NodeId edge_node(EdgeId e, int i) const { return edge_nodes_[at(e)][static_cast<std::size_t>(i)]; }
  FaceId edge_face(EdgeId e, int side) const { return edge_faces_[at(e)][static_cast<std::size_t>(side)]; }
  bool is_boundary(EdgeId e) const { return !edge_face(e, 0).valid() || !edge_face(e, 1).valid(); }
  // The vert of face(e, side) at edge node i.
  VertId edge_vert(EdgeId e, int side, int i) const;
  // The node of face(e, side) that is not on the edge.
  NodeId opposite_node(EdgeId e, int side) const;
  VertId opposite_vert(EdgeId e, int side) const;
  // Interior edge whose two faces use different verts at an end: a seam of the pattern.
  bool is_seam(EdgeId e) const;
  // The edge joining two nodes, or an invalid handle.
  EdgeId find_edge(NodeId a, NodeId b) const;

  // Number of separate fans the faces around a node form (1 for a manifold vertex).
  int fan_count(NodeId n) const;

  // --- geometry ---
  double material_area(FaceId f) const;  // signed, positive for a counter-clockwise face
  double world_area(FaceId f) const;
  Vec3 world_normal(FaceId f) const;  // unit normal of the outer side

  // --- attributes, kept in step with topology changes ---
  AttributeSet<NodeTag>& node_attrs() { return node_attrs_; }
  AttributeSet<VertTag>& vert_attrs() { return vert_attrs_; }
  AttributeSet<EdgeTag>& edge_attrs() { return edge_attrs_; }
  AttributeSet<FaceTag>& face_attrs() { return face_attrs_; }
  const AttributeSet<NodeTag>& node_attrs() const { return node_attrs_; }
  const AttributeSet<VertTag>& vert_attrs() const { return vert_attrs_; }
  const AttributeSet<EdgeTag>& edge_attrs() const { return edge_attrs_; }
  const AttributeSet<FaceTag>& face_attrs() const { return face_attrs_; }

  // Checks every invariant: references alive and reciprocal, adjacency lists exact, edges
  // manifold and consistently oriented, vertices manifold (one fan), no duplicate edges, faces
  // non-degenerate in material space.
  ValidationReport validate() const;

  // Every array, in its order, with the attributes: read_binary gives back the same mesh,
  // element for element and adjacency list for adjacency list (mesh_binary.cpp, checkpoints).
  void write_binary(BinaryWriter& out) const;
  // Throws BinaryFormatError when the data is not a mesh written by write_binary.
  static Mesh read_binary(BinaryReader& in);

 private:
  template <class Tag>
  static std::size_t at(Handle<Tag> h) {
    return static_cast<std::size_t>(h.idx);
  }
  static bool in(int32_t i, const std::vector<char>& alive) {
    return i >= 0 && i < static_cast<int32_t>(alive.size()) && alive[static_cast<std::size_t>(i)];
  }
  void attach_face_to_edge(FaceId f, int corner, NodeId a, NodeId b);
  // validate()'s checks, element kind by element kind, each adding what it finds to `problems`.
  void validate_counts(std::vector<std::string>& problems) const;
  void validate_faces(std::vector<std::string>& problems) const;
  void validate_edges(std::vector<std::string>& problems) const;
  void validate_verts(std::vector<std::string>& problems) const;
  void validate_nodes(std::vector<std::string>& problems) const;

  // nodes
  std::vector<char> node_alive_;
  std::vector<Vec3> x_, v_;
  std::vector<uint32_t> flags_;
  std::vector<std::vector<VertId>> node_verts_;
  std::vector<std::vector<EdgeId>> node_edges_;
  // verts
  std::vector<char> vert_alive_;
  std::vector<Vec2> u_;
  std::vector<NodeId> vert_node_;
  std::vector<std::vector<FaceId>> vert_faces_;
  // edges
  std::vector<char> edge_alive_;
  std::vector<std::array<NodeId, 2>> edge_nodes_;
  std::vector<std::array<FaceId, 2>> edge_faces_;
  // faces
  std::vector<char> face_alive_;
  std::vector<std::array<VertId, 3>> face_verts_;
  std::vector<std::array<EdgeId, 3>> face_edges_;

  int32_t live_nodes_ = 0, live_verts_ = 0, live_edges_ = 0, live_faces_ = 0;
  AttributeSet<NodeTag> node_attrs_;
  AttributeSet<VertTag> vert_attrs_;
  AttributeSet<EdgeTag> edge_attrs_;
  AttributeSet<FaceTag> face_attrs_;
};

}  // namespace vdc
