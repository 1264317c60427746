// Edge split, flip and collapse (Narain et al. 2012, section 4, after ARCSim's operations).
#include "remesh/operations.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace vdc {

namespace {

// Smallest material area accepted for a new face, relative to its longest edge squared.
constexpr double kMinRelativeArea = 1e-6;

using NodePair = std::pair<int32_t, int32_t>;
NodePair key(NodeId a, NodeId b) { return {std::min(a.idx, b.idx), std::max(a.idx, b.idx)}; }

bool good_material_face(const Mesh& mesh, VertId a, VertId b, VertId c) {
  const Vec2 &ua = mesh.u(a), &ub = mesh.u(b), &uc = mesh.u(c);
  double l2 = std::max({(ub - ua).squaredNorm(), (uc - ub).squaredNorm(), (ua - uc).squaredNorm()});
  return 0.5 * signed_area2(ua, ub, uc) > kMinRelativeArea * l2;
}

Vec3 world_normal_of(const Mesh& mesh, VertId a, VertId b, VertId c) {
  return area_normal(mesh.x(mesh.vert_node(a)), mesh.x(mesh.vert_node(b)), mesh.x(mesh.vert_node(c)));
}

// Replaces `old_faces` by `new_faces` (corner triples), copying face attributes from the
// face each new one came from, and edge attributes from the old edge with the same ends (or
// from `edge_source` for the given node pairs). Fills the face and edge parts of the record.
struct NewFace {
  std::array<VertId, 3> v;
  FaceId from;
};
void replace_faces(Mesh& mesh, const std::vector<FaceId>& old_faces, const std::vector<NewFace>& new_faces,
                   const std::map<NodePair, EdgeId>& edge_source, OpRecord& rec) {
  std::map<NodePair, EdgeId> old_edges = edge_source;
  for (FaceId f : old_faces)
    for (EdgeId e : mesh.face_edges(f)) old_edges.emplace(key(mesh.edge_node(e, 0), mesh.edge_node(e, 1)), e);
  std::vector<EdgeId> before;
  for (const auto& [k, e] : old_edges)
    if (mesh.alive(e) && std::find(before.begin(), before.end(), e) == before.end()) before.push_back(e);
  for (FaceId f : old_faces) {
    mesh.remove_face(f);
    rec.removed_faces.push_back(f);
  }
  for (const NewFace& nf : new_faces) {
    FaceId f = mesh.add_face(nf.v[0], nf.v[1], nf.v[2]);
    mesh.face_attrs().copy(nf.from, f);
    rec.added_faces.push_back(f);
  }
  // Edges that died and edges that were born; a born edge takes the attributes of the old edge
  // with the same ends, if any.
  for (EdgeId e : before)
    if (!mesh.alive(e)) rec.removed_edges.push_back(e);
  for (FaceId f : rec.added_faces)
    for (EdgeId e : mesh.face_edges(f)) {
      if (std::find(before.begin(), before.end(), e) != before.end()) continue;
      if (std::find(rec.added_edges.begin(), rec.added_edges.end(), e) != rec.added_edges.end()) continue;
      rec.added_edges.push_back(e);
      auto it = old_edges.find(key(mesh.edge_node(e, 0), mesh.edge_node(e, 1)));
      if (it != old_edges.end() && it->second != e) mesh.edge_attrs().copy(it->second, e);
    }
}

}  // namespace

bool can_split(const Mesh& mesh, EdgeId e) { return mesh.alive(e); }

OpRecord split_edge(Mesh& mesh, EdgeId e, double t) {
  if (!can_split(mesh, e)) throw std::logic_error("split_edge: edge is not alive");
  OpRecord rec;
  const NodeId n0 = mesh.edge_node(e, 0), n1 = mesh.edge_node(e, 1);
  const NodeId m = mesh.add_node((1 - t) * mesh.x(n0) + t * mesh.x(n1), (1 - t) * mesh.v(n0) + t * mesh.v(n1));
  rec.added_nodes.push_back(m);
  std::vector<FaceId> old_faces;
  std::vector<NewFace> new_faces;
  VertId shared_mid;  // the new vert of side 0, reused by side 1 unless the edge is a seam
  for (int side = 0; side < 2; ++side) {
    FaceId f = mesh.edge_face(e, side);
    if (!f.valid()) continue;
    VertId va = mesh.edge_vert(e, side, 0), vb = mesh.edge_vert(e, side, 1), vc = mesh.opposite_vert(e, side);
    VertId vm;
    if (side == 1 && shared_mid.valid() && va == mesh.edge_vert(e, 0, 0) && vb == mesh.edge_vert(e, 0, 1)) {
      vm = shared_mid;
    } else {
      vm = mesh.add_vert(m, (1 - t) * mesh.u(va) + t * mesh.u(vb));
      mesh.vert_attrs().copy(t < 0.5 ? va : vb, vm);
      rec.added_verts.push_back(vm);
    }
    if (side == 0) shared_mid = vm;
    old_faces.push_back(f);
    // Side 0 runs n0 -> n1 counter-clockwise: (a, b, c); side 1 runs n1 -> n0: (b, a, c).
    if (side == 0) {
      new_faces.push_back({{va, vm, vc}, f});
      new_faces.push_back({{vm, vb, vc}, f});
    } else {
      new_faces.push_back({{vb, vm, vc}, f});
      new_faces.push_back({{vm, va, vc}, f});
    }
  }
  std::map<NodePair, EdgeId> halves{{key(n0, m), e}, {key(m, n1), e}};
  replace_faces(mesh, old_faces, new_faces, halves, rec);
  return rec;
}

bool can_flip(const Mesh& mesh, EdgeId e) {
  if (!mesh.alive(e) || mesh.is_boundary(e) || mesh.is_seam(e)) return false;
  const NodeId c = mesh.opposite_node(e, 0), d = mesh.opposite_node(e, 1);
  if (c == d || mesh.find_edge(c, d).valid()) return false;
  const VertId v0 = mesh.edge_vert(e, 0, 0), v1 = mesh.edge_vert(e, 0, 1);
  const VertId vc = mesh.opposite_vert(e, 0), vd = mesh.opposite_vert(e, 1);
  // The quad n0, d, n1, c is counter-clockwise; the new diagonal joins c and d.
  if (!good_material_face(mesh, v0, vd, vc) || !good_material_face(mesh, vd, v1, vc)) return false;
  const Vec3 n_old = world_normal_of(mesh, v0, v1, vc) + world_normal_of(mesh, v1, v0, vd);
  return world_normal_of(mesh, v0, vd, vc).dot(n_old) > 0 && world_normal_of(mesh, vd, v1, vc).dot(n_old) > 0;
}

OpRecord flip_edge(Mesh& mesh, EdgeId e) {
  if (!can_flip(mesh, e)) throw std::logic_error("flip_edge: flip not allowed");
  OpRecord rec;
  const VertId v0 = mesh.edge_vert(e, 0, 0), v1 = mesh.edge_vert(e, 0, 1);
  const VertId vc = mesh.opposite_vert(e, 0), vd = mesh.opposite_vert(e, 1);
  const FaceId f0 = mesh.edge_face(e, 0), f1 = mesh.edge_face(e, 1);
  replace_faces(mesh, {f0, f1}, {{{v0, vd, vc}, f0}, {{vd, v1, vc}, f1}}, {}, rec);
  return rec;
}

OpPreview preview_flip(const Mesh& mesh, EdgeId e) {
  const NodeId n0 = mesh.edge_node(e, 0), n1 = mesh.edge_node(e, 1);
  const NodeId c = mesh.opposite_node(e, 0), d = mesh.opposite_node(e, 1);
  return {{mesh.edge_face(e, 0), mesh.edge_face(e, 1)}, {{{n0, d, c}}, {{d, n1, c}}}};
}

namespace {

// Faces around the removed node rewritten onto the kept node's vert in the same panel; faces
// that contain both ends (those of e) disappear.
std::vector<NewFace> collapsed_faces(const Mesh& mesh, EdgeId e, int remove, std::vector<FaceId>& old_faces) {
  const NodeId r = mesh.edge_node(e, remove), k = mesh.edge_node(e, 1 - remove);
  std::vector<NewFace> out;
  for (VertId vr : mesh.node_verts(r)) {
    const VertId vk = collapse_target(mesh, e, remove, vr);
    for (FaceId f : mesh.vert_faces(vr)) {
      old_faces.push_back(f);
      auto vs = mesh.face_verts(f);
      bool has_k = false;
      for (VertId v : vs) has_k = has_k || mesh.vert_node(v) == k;
      if (has_k) continue;
      for (VertId& v : vs)
        if (v == vr) v = vk;
      out.push_back({vs, f});
    }
  }
  return out;
}

// A node on the pattern's border (a boundary or a seam) may only slide along it: it has exactly
// two border edges, of one kind, e is one of them, it joins at most two panels, and in each
// panel the border runs on through it nearly straight: its distance from the chord joining its
// two border neighbours is at most border_sag times that chord (round-off when 0).
bool border_allows_collapse(const Mesh& mesh, EdgeId e, NodeId r, double border_sag) {
  std::vector<EdgeId> border;
  for (EdgeId b : mesh.node_edges(r))
    if (mesh.is_boundary(b) || mesh.is_seam(b)) border.push_back(b);
  if (border.empty()) return mesh.node_verts(r).size() == 1;
  if (border.size() != 2 || (border[0] != e && border[1] != e)) return false;
  if (mesh.is_seam(border[0]) != mesh.is_seam(border[1]) || mesh.node_verts(r).size() > 2) return false;
  const double tolerance = std::max(border_sag, 1e-9);
  for (VertId vr : mesh.node_verts(r)) {
    Vec2 d[2];
    for (int i = 0; i < 2; ++i) {
      const NodeId n = mesh.edge_node(border[i], 0) == r ? mesh.edge_node(border[i], 1) : mesh.edge_node(border[i], 0);
      const VertId vn = vert_beside(mesh, vr, n);
      if (!vn.valid()) return false;
      d[i] = mesh.u(vn) - mesh.u(vr);
    }
    if (d[0].dot(d[1]) >= 0) return false;
    if (std::abs(cross2(d[0], d[1])) > tolerance * (d[1] - d[0]).squaredNorm()) return false;
  }
  return true;
}

}  // namespace

OpPreview preview_collapse(const Mesh& mesh, EdgeId e, int remove) {
  OpPreview p;
  for (const NewFace& nf : collapsed_faces(mesh, e, remove, p.removed))
    p.made.push_back({mesh.vert_node(nf.v[0]), mesh.vert_node(nf.v[1]), mesh.vert_node(nf.v[2])});
  return p;
}

VertId vert_beside(const Mesh& mesh, VertId v, NodeId n) {
  for (FaceId f : mesh.vert_faces(v))
    for (VertId w : mesh.face_verts(f))
      if (mesh.vert_node(w) == n) return w;
  return VertId();
}

VertId collapse_target(const Mesh& mesh, EdgeId e, int remove, VertId vr) {
  return vert_beside(mesh, vr, mesh.edge_node(e, 1 - remove));
}

bool can_collapse(const Mesh& mesh, EdgeId e, int remove, double border_sag) {
  if (!mesh.alive(e) || (remove != 0 && remove != 1)) return false;
  const NodeId r = mesh.edge_node(e, remove), k = mesh.edge_node(e, 1 - remove);
  if (mesh.flags(r) & kNodeHandle) return false;
  // Past this, every vert of r has a vert of k beside it: r is interior (one vert, on e's faces)
  // or slides along e, one of the border edges whose far ends were just found in each panel.
  if (!border_allows_collapse(mesh, e, r, border_sag)) return false;
  // Link condition: the only common neighbours of r and k are the opposite nodes of e.
  std::vector<int32_t> nr, nk;
  for (EdgeId x : mesh.node_edges(r)) nr.push_back((mesh.edge_node(x, 0) == r ? mesh.edge_node(x, 1) : mesh.edge_node(x, 0)).idx);
  for (EdgeId x : mesh.node_edges(k)) nk.push_back((mesh.edge_node(x, 0) == k ? mesh.edge_node(x, 1) : mesh.edge_node(x, 0)).idx);
  std::sort(nr.begin(), nr.end());
  std::sort(nk.begin(), nk.end());
  std::vector<int32_t> common;
  std::set_intersection(nr.begin(), nr.end(), nk.begin(), nk.end(), std::back_inserter(common));
  int expected = 0;
  for (int side = 0; side < 2; ++side) expected += mesh.edge_face(e, side).valid() ? 1 : 0;
  if (static_cast<int>(common.size()) != expected) return false;
  // No new face inverted or degenerate in material space, none flipped in world space.
  std::vector<FaceId> old_faces;
  for (const NewFace& nf : collapsed_faces(mesh, e, remove, old_faces)) {
    if (!good_material_face(mesh, nf.v[0], nf.v[1], nf.v[2])) return false;
    const auto& ov = mesh.face_verts(nf.from);
    if (world_normal_of(mesh, nf.v[0], nf.v[1], nf.v[2]).dot(world_normal_of(mesh, ov[0], ov[1], ov[2])) <= 0) return false;
  }
  return true;
}

OpRecord collapse_edge(Mesh& mesh, EdgeId e, int remove, double border_sag) {
  if (!can_collapse(mesh, e, remove, border_sag)) throw std::logic_error("collapse_edge: collapse not allowed");
  OpRecord rec;
  const NodeId r = mesh.edge_node(e, remove);
  const std::vector<VertId> removed_verts = mesh.node_verts(r);
  const NodeId k = mesh.edge_node(e, 1 - remove);
  std::vector<FaceId> old_faces;
  std::vector<NewFace> new_faces = collapsed_faces(mesh, e, remove, old_faces);
  // Edge (k, x) that replaces (r, x) keeps its attributes.
  std::map<NodePair, EdgeId> moved;
  for (EdgeId x : mesh.node_edges(r)) {
    NodeId other = mesh.edge_node(x, 0) == r ? mesh.edge_node(x, 1) : mesh.edge_node(x, 0);
    if (other != k) moved.emplace(key(k, other), x);
  }
  replace_faces(mesh, old_faces, new_faces, moved, rec);
  for (VertId vr : removed_verts) {
    mesh.remove_vert(vr);
    rec.removed_verts.push_back(vr);
  }
  mesh.remove_node(r);
  rec.removed_nodes.push_back(r);
  return rec;
}

}  // namespace vdc
