#include "core/mesh.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "core/error.hpp"

namespace vdc {

namespace {

// "face 12", as validate() names an element.
std::string element_name(const char* kind, int32_t i) { return std::string(kind) + " " + std::to_string(i); }

template <class T>
void erase_one(std::vector<T>& list, T value) {
  auto it = std::find(list.begin(), list.end(), value);
  if (it != list.end()) list.erase(it);
}

// Builds new_to_old and old_to_new from an alive mask.
void dense_order(const std::vector<char>& alive, std::vector<int32_t>& new_to_old, std::vector<int32_t>& old_to_new) {
  new_to_old.clear();
  old_to_new.assign(alive.size(), -1);
  for (std::size_t i = 0; i < alive.size(); ++i) {
    if (!alive[i]) continue;
    old_to_new[i] = static_cast<int32_t>(new_to_old.size());
    new_to_old.push_back(static_cast<int32_t>(i));
  }
}

template <class T>
void keep(std::vector<T>& data, const std::vector<int32_t>& new_to_old) {
  std::vector<T> out;
  out.reserve(new_to_old.size());
  for (int32_t old : new_to_old) out.push_back(std::move(data[static_cast<std::size_t>(old)]));
  data = std::move(out);
}

template <class Tag>
Handle<Tag> remap(Handle<Tag> h, const std::vector<int32_t>& old_to_new) {
  return h.valid() ? Handle<Tag>(old_to_new[static_cast<std::size_t>(h.idx)]) : h;
}

}  // namespace

std::string ValidationReport::summary(std::size_t max_lines) const {
  std::ostringstream s;
  for (std::size_t i = 0; i < problems.size() && i < max_lines; ++i) s << problems[i] << "\n";
  if (problems.size() > max_lines) s << "... and " << problems.size() - max_lines << " more\n";
  return s.str();
}

NodeId Mesh::add_node(const Vec3& x, const Vec3& v) {
  NodeId n(static_cast<int32_t>(node_alive_.size()));
  node_alive_.push_back(1);
  x_.push_back(x);
  v_.push_back(v);
  flags_.push_back(0);
  node_verts_.emplace_back();
  node_edges_.emplace_back();
  node_attrs_.resize(node_alive_.size());
  ++live_nodes_;
  return n;
}

VertId Mesh::add_vert(NodeId node, const Vec2& u) {
  if (!alive(node)) throw TopologyError("add_vert: node " + std::to_string(node.idx) + " is not alive");
  VertId v(static_cast<int32_t>(vert_alive_.size()));
  vert_alive_.push_back(1);
  u_.push_back(u);
  vert_node_.push_back(node);
  vert_faces_.emplace_back();
  node_verts_[at(node)].push_back(v);
  vert_attrs_.resize(vert_alive_.size());
  ++live_verts_;
  return v;
}

EdgeId Mesh::find_edge(NodeId a, NodeId b) const {
  for (EdgeId e : node_edges_[at(a)]) {
    const auto& en = edge_nodes_[at(e)];
    if ((en[0] == a && en[1] == b) || (en[0] == b && en[1] == a)) return e;
  }
  return EdgeId();
}

void Mesh::attach_face_to_edge(FaceId f, int corner, NodeId a, NodeId b) {
  EdgeId e = find_edge(a, b);
  if (!e.valid()) {
    e = EdgeId(static_cast<int32_t>(edge_alive_.size()));
    edge_alive_.push_back(1);
    edge_nodes_.push_back({a, b});
    edge_faces_.push_back({FaceId(), FaceId()});
    node_edges_[at(a)].push_back(e);
    node_edges_[at(b)].push_back(e);
    edge_attrs_.resize(edge_alive_.size());
    ++live_edges_;
  }
  int side = edge_nodes_[at(e)][0] == a ? 0 : 1;
  edge_faces_[at(e)][static_cast<std::size_t>(side)] = f;
  face_edges_[at(f)][static_cast<std::size_t>(corner)] = e;
}

FaceId Mesh::add_face(VertId a, VertId b, VertId c) {
  const std::array<VertId, 3> vs{a, b, c};
  std::array<NodeId, 3> ns;
  for (int i = 0; i < 3; ++i) {
    if (!alive(vs[static_cast<std::size_t>(i)]))
      throw TopologyError("add_face: vert " + std::to_string(vs[static_cast<std::size_t>(i)].idx) + " is not alive");
    ns[static_cast<std::size_t>(i)] = vert_node(vs[static_cast<std::size_t>(i)]);
  }
  if (ns[0] == ns[1] || ns[1] == ns[2] || ns[2] == ns[0])
    throw TopologyError("face uses the same node twice");
  // Check every edge before changing anything, so a refused face leaves the mesh untouched.
  for (int i = 0; i < 3; ++i) {
    NodeId p = ns[static_cast<std::size_t>(i)], q = ns[static_cast<std::size_t>((i + 1) % 3)];
    EdgeId e = find_edge(p, q);
    if (!e.valid()) continue;
    int side = edge_nodes_[at(e)][0] == p ? 0 : 1;
    const auto& ef = edge_faces_[at(e)];
    if (ef[0].valid() && ef[1].valid())
      throw TopologyError("non-manifold edge between nodes " + std::to_string(p.idx) + " and " +
                          std::to_string(q.idx) + " (a third face)");
    if (ef[static_cast<std::size_t>(side)].valid())
      throw TopologyError("inconsistently oriented faces at edge between nodes " + std::to_string(p.idx) + " and " +
                          std::to_string(q.idx));
  }
  FaceId f(static_cast<int32_t>(face_alive_.size()));
  face_alive_.push_back(1);
  face_verts_.push_back(vs);
  face_edges_.push_back({EdgeId(), EdgeId(), EdgeId()});
  face_attrs_.resize(face_alive_.size());
  ++live_faces_;
  for (int i = 0; i < 3; ++i) {
    attach_face_to_edge(f, i, ns[static_cast<std::size_t>(i)], ns[static_cast<std::size_t>((i + 1) % 3)]);
    vert_faces_[at(vs[static_cast<std::size_t>(i)])].push_back(f);
  }
  return f;
}

void Mesh::remove_face(FaceId f) {
  if (!alive(f)) throw TopologyError("remove_face: face " + std::to_string(f.idx) + " is not alive");
  for (int i = 0; i < 3; ++i) {
    EdgeId e = face_edges_[at(f)][static_cast<std::size_t>(i)];
    auto& ef = edge_faces_[at(e)];
    for (auto& slot : ef)
      if (slot == f) slot = FaceId();
    if (!ef[0].valid() && !ef[1].valid()) {
      edge_alive_[at(e)] = 0;
      erase_one(node_edges_[at(edge_nodes_[at(e)][0])], e);
      erase_one(node_edges_[at(edge_nodes_[at(e)][1])], e);
      --live_edges_;
    }
    erase_one(vert_faces_[at(face_verts_[at(f)][static_cast<std::size_t>(i)])], f);
  }
  face_alive_[at(f)] = 0;
  --live_faces_;
}

void Mesh::remove_vert(VertId v) {
  if (!alive(v)) throw TopologyError("remove_vert: vert " + std::to_string(v.idx) + " is not alive");
  if (!vert_faces_[at(v)].empty()) throw TopologyError("remove_vert: vert still has faces");
  erase_one(node_verts_[at(vert_node_[at(v)])], v);
  vert_alive_[at(v)] = 0;
  --live_verts_;
}

void Mesh::remove_node(NodeId n) {
  if (!alive(n)) throw TopologyError("remove_node: node " + std::to_string(n.idx) + " is not alive");
  if (!node_verts_[at(n)].empty() || !node_edges_[at(n)].empty())
    throw TopologyError("remove_node: node still has verts or edges");
  node_alive_[at(n)] = 0;
  --live_nodes_;
}

bool Mesh::is_compact() const {
  return live_nodes_ == node_capacity() && live_verts_ == vert_capacity() && live_edges_ == edge_capacity() &&
         live_faces_ == face_capacity();
}

CompactionMap Mesh::compact() {
  CompactionMap map;
  std::vector<int32_t> n2o_node, n2o_vert, n2o_edge, n2o_face;
  dense_order(node_alive_, n2o_node, map.node);
  dense_order(vert_alive_, n2o_vert, map.vert);
  dense_order(edge_alive_, n2o_edge, map.edge);
  dense_order(face_alive_, n2o_face, map.face);

  keep(x_, n2o_node);
  keep(v_, n2o_node);
  keep(flags_, n2o_node);
  keep(node_verts_, n2o_node);
  keep(node_edges_, n2o_node);
  for (auto& list : node_verts_)
    for (auto& h : list) h = remap(h, map.vert);
  for (auto& list : node_edges_)
    for (auto& h : list) h = remap(h, map.edge);

  keep(u_, n2o_vert);
  keep(vert_node_, n2o_vert);
  keep(vert_faces_, n2o_vert);
  for (auto& h : vert_node_) h = remap(h, map.node);
  for (auto& list : vert_faces_)
    for (auto& h : list) h = remap(h, map.face);

  keep(edge_nodes_, n2o_edge);
  keep(edge_faces_, n2o_edge);
  for (auto& arr : edge_nodes_)
    for (auto& h : arr) h = remap(h, map.node);
  for (auto& arr : edge_faces_)
    for (auto& h : arr) h = remap(h, map.face);

  keep(face_verts_, n2o_face);
  keep(face_edges_, n2o_face);
  for (auto& arr : face_verts_)
    for (auto& h : arr) h = remap(h, map.vert);
  for (auto& arr : face_edges_)
    for (auto& h : arr) h = remap(h, map.edge);

  node_alive_.assign(n2o_node.size(), 1);
  vert_alive_.assign(n2o_vert.size(), 1);
  edge_alive_.assign(n2o_edge.size(), 1);
  face_alive_.assign(n2o_face.size(), 1);
  node_attrs_.permute(n2o_node);
  vert_attrs_.permute(n2o_vert);
  edge_attrs_.permute(n2o_edge);
  face_attrs_.permute(n2o_face);
  return map;
}

VertId Mesh::edge_vert(EdgeId e, int side, int i) const {
  FaceId f = edge_face(e, side);
  if (!f.valid()) return VertId();
  NodeId n = edge_node(e, i);
  for (VertId v : face_verts(f))
    if (vert_node(v) == n) return v;
  return VertId();
}

VertId Mesh::opposite_vert(EdgeId e, int side) const {
  FaceId f = edge_face(e, side);
  if (!f.valid()) return VertId();
  for (VertId v : face_verts(f)) {
    NodeId n = vert_node(v);
    if (n != edge_node(e, 0) && n != edge_node(e, 1)) return v;
  }
  return VertId();
}

NodeId Mesh::opposite_node(EdgeId e, int side) const {
  VertId v = opposite_vert(e, side);
  return v.valid() ? vert_node(v) : NodeId();
}

bool Mesh::is_seam(EdgeId e) const {
  if (is_boundary(e)) return false;
  return edge_vert(e, 0, 0) != edge_vert(e, 1, 0) || edge_vert(e, 0, 1) != edge_vert(e, 1, 1);
}

int Mesh::fan_count(NodeId n) const {
  // Union-find over the faces at the node, joined through the interior edges at the node.
  std::map<int32_t, int32_t> local;
  for (VertId v : node_verts(n))
    for (FaceId f : vert_faces(v)) local.emplace(f.idx, static_cast<int32_t>(local.size()));
  std::vector<int32_t> parent(local.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&parent](int32_t i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)];
    return i;
  };
  for (EdgeId e : node_edges(n)) {
    FaceId a = edge_face(e, 0), b = edge_face(e, 1);
    if (a.valid() && b.valid() && local.count(a.idx) && local.count(b.idx))
      parent[static_cast<std::size_t>(root(local[a.idx]))] = root(local[b.idx]);
  }
  int fans = 0;
  for (std::size_t i = 0; i < parent.size(); ++i) fans += root(static_cast<int32_t>(i)) == static_cast<int32_t>(i);
  return fans;
}

double Mesh::material_area(FaceId f) const {
  const auto& vs = face_verts(f);
  return 0.5 * signed_area2(u(vs[0]), u(vs[1]), u(vs[2]));
}

double Mesh::world_area(FaceId f) const {
  return 0.5 * area_normal(x(face_node(f, 0)), x(face_node(f, 1)), x(face_node(f, 2))).norm();
}

Vec3 Mesh::world_normal(FaceId f) const {
  Vec3 n = area_normal(x(face_node(f, 0)), x(face_node(f, 1)), x(face_node(f, 2)));
  double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

ValidationReport Mesh::validate() const {
  ValidationReport r;
  validate_counts(r.problems);
  validate_faces(r.problems);
  validate_edges(r.problems);
  validate_verts(r.problems);
  validate_nodes(r.problems);
  return r;
}

void Mesh::validate_counts(std::vector<std::string>& problems) const {
  auto bad = [&problems](const std::string& s) { problems.push_back(s); };
  if (node_attrs_.size() != node_alive_.size() || vert_attrs_.size() != vert_alive_.size() ||
      edge_attrs_.size() != edge_alive_.size() || face_attrs_.size() != face_alive_.size())
    bad("attribute arrays out of step with element arrays");
  auto count = [](const std::vector<char>& a) { return static_cast<int32_t>(std::count(a.begin(), a.end(), 1)); };
  if (count(node_alive_) != live_nodes_ || count(vert_alive_) != live_verts_ || count(edge_alive_) != live_edges_ ||
      count(face_alive_) != live_faces_)
    bad("live element counts out of step");
}

void Mesh::validate_faces(std::vector<std::string>& problems) const {
  auto bad = [&problems](const std::string& s) { problems.push_back(s); };
  for (FaceId f : faces()) {
    const auto& vs = face_verts(f);
    bool refs_ok = true;
    for (VertId v : vs)
      if (!alive(v)) {
        bad(element_name("face", f.idx) + " references dead vert " + std::to_string(v.idx));
        refs_ok = false;
      }
    if (!refs_ok) continue;
    for (int i = 0; i < 3; ++i) {
      VertId v = vs[static_cast<std::size_t>(i)];
      const auto& vf = vert_faces(v);
      if (std::count(vf.begin(), vf.end(), f) != 1) bad(element_name("vert", v.idx) + " does not list " + element_name("face", f.idx) + " once");
      NodeId a = vert_node(v), b = face_node(f, (i + 1) % 3);
      EdgeId e = face_edges(f)[static_cast<std::size_t>(i)];
      if (!alive(e)) {
        bad(element_name("face", f.idx) + " references dead edge");
        continue;
      }
      int side = edge_node(e, 0) == a && edge_node(e, 1) == b ? 0 : (edge_node(e, 0) == b && edge_node(e, 1) == a ? 1 : -1);
      if (side < 0)
        bad(element_name("face", f.idx) + " edge " + std::to_string(i) + " does not join its corner nodes");
      else if (edge_face(e, side) != f)
        bad(element_name("edge", e.idx) + " does not list " + element_name("face", f.idx) + " on the side it runs");
    }
    if (face_node(f, 0) == face_node(f, 1) || face_node(f, 1) == face_node(f, 2) || face_node(f, 0) == face_node(f, 2))
      bad(element_name("face", f.idx) + " repeats a node");
    if (!(material_area(f) > 0)) bad(element_name("face", f.idx) + " has non-positive material-space area");
  }
}

void Mesh::validate_edges(std::vector<std::string>& problems) const {
  auto bad = [&problems](const std::string& s) { problems.push_back(s); };
  for (EdgeId e : edges()) {
    NodeId a = edge_node(e, 0), b = edge_node(e, 1);
    if (!alive(a) || !alive(b)) {
      bad(element_name("edge", e.idx) + " references a dead node");
      continue;
    }
    if (a == b) bad(element_name("edge", e.idx) + " joins a node to itself");
    if (!edge_face(e, 0).valid() && !edge_face(e, 1).valid()) bad(element_name("edge", e.idx) + " has no face");
    for (int side = 0; side < 2; ++side) {
      FaceId f = edge_face(e, side);
      if (!f.valid()) continue;
      if (!alive(f)) {
        bad(element_name("edge", e.idx) + " references dead face");
        continue;
      }
      const auto& fe = face_edges(f);
      if (std::find(fe.begin(), fe.end(), e) == fe.end()) bad(element_name("face", f.idx) + " does not list " + element_name("edge", e.idx));
    }
    for (NodeId n : {a, b}) {
      const auto& ne = node_edges(n);
      if (std::count(ne.begin(), ne.end(), e) != 1) bad(element_name("node", n.idx) + " does not list " + element_name("edge", e.idx) + " once");
    }
  }
}

void Mesh::validate_verts(std::vector<std::string>& problems) const {
  auto bad = [&problems](const std::string& s) { problems.push_back(s); };
  for (VertId v : verts()) {
    NodeId n = vert_node(v);
    if (!alive(n)) {
      bad(element_name("vert", v.idx) + " references dead node");
      continue;
    }
    const auto& nv = node_verts(n);
    if (std::count(nv.begin(), nv.end(), v) != 1) bad(element_name("node", n.idx) + " does not list " + element_name("vert", v.idx) + " once");
    for (FaceId f : vert_faces(v)) {
      if (!alive(f)) {
        bad(element_name("vert", v.idx) + " lists dead face");
        continue;
      }
      const auto& fv = face_verts(f);
      if (std::find(fv.begin(), fv.end(), v) == fv.end()) bad(element_name("vert", v.idx) + " lists a face that does not use it");
    }
  }
}

void Mesh::validate_nodes(std::vector<std::string>& problems) const {
  auto bad = [&problems](const std::string& s) { problems.push_back(s); };
  for (NodeId n : nodes()) {
    std::set<int32_t> neighbours;
    for (EdgeId e : node_edges(n)) {
      if (!alive(e)) {
        bad(element_name("node", n.idx) + " lists dead edge");
        continue;
      }
      NodeId other = edge_node(e, 0) == n ? edge_node(e, 1) : edge_node(e, 0);
      if (edge_node(e, 0) != n && edge_node(e, 1) != n) bad(element_name("node", n.idx) + " lists an edge not touching it");
      if (!neighbours.insert(other.idx).second) bad(element_name("node", n.idx) + " has two edges to " + element_name("node", other.idx));
    }
    for (VertId v : node_verts(n))
      if (!alive(v) || vert_node(v) != n) bad(element_name("node", n.idx) + " lists a vert that is not its own");
    if (!x(n).allFinite() || !v(n).allFinite()) bad(element_name("node", n.idx) + " has a non-finite position or velocity");
    if (!node_edges(n).empty() && fan_count(n) != 1) bad(element_name("node", n.idx) + " is a non-manifold vertex (its faces form several fans)");
  }
}

}  // namespace vdc
