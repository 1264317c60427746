// Remeshing loop (Narain et al. 2012, section 4; edge metric eq. 1 of Koh et al. 2014).
#include "remesh/remesher.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace vdc {

namespace {

// The sizing tensors, looked up by name once a pass and handed down (a lookup costs more than
// an edge's metric).
using Sizing = Attribute<VertTag, Mat2>;
const Sizing& sizing(const Mesh& mesh) { return mesh.vert_attrs().get<Mat2>(kSizingAttr); }

double size2(const Mesh& mesh, const Sizing& m, VertId a, VertId b) {
  Vec2 d = mesh.u(a) - mesh.u(b);
  return d.dot(0.5 * (m[a] + m[b]) * d);
}

double edge_size2(const Mesh& mesh, const Sizing& m, EdgeId e) {
  double s2 = 0;
  for (int side = 0; side < 2; ++side)
    if (mesh.edge_face(e, side).valid()) s2 = std::max(s2, size2(mesh, m, mesh.edge_vert(e, side, 0), mesh.edge_vert(e, side, 1)));
  return s2;
}

bool should_flip(const Mesh& mesh, const Sizing& m, EdgeId e, double threshold) {
  if (mesh.is_boundary(e) || mesh.is_seam(e)) return false;
  const VertId vi = mesh.edge_vert(e, 0, 0), vj = mesh.edge_vert(e, 0, 1);
  const VertId vk = mesh.opposite_vert(e, 0), vl = mesh.opposite_vert(e, 1);
  const Mat2 M = 0.25 * (m[vi] + m[vj] + m[vk] + m[vl]);
  const Vec2 ujk = mesh.u(vj) - mesh.u(vk), uik = mesh.u(vi) - mesh.u(vk);
  const Vec2 uil = mesh.u(vi) - mesh.u(vl), ujl = mesh.u(vj) - mesh.u(vl);
  // The angles opposite e, at k and l, measured in the metric, sum to more than pi exactly when
  // sin(k + l) = sin k cos l + cos k sin l < 0. Sines are proportional to the (positive) areas,
  // cosines to M-dot products; the common factors cancel in the sign.
  const double sk = std::abs(cross2(ujk, uik)), sl = std::abs(cross2(uil, ujl));
  const double a = sk * uil.dot(M * ujl) + ujk.dot(M * uik) * sl;
  return a < -threshold * (sk + sl);
}

bool flip_keeps_valid(const Mesh& mesh, const Sizing& m, EdgeId e) {
  return size2(mesh, m, mesh.opposite_vert(e, 0), mesh.opposite_vert(e, 1)) <= 1.0;
}

// Flips every edge that fails the Delaunay test, sweeping until none does (or the pass bound).
int flip_all(Mesh& mesh, const RemeshOptions& o, CrossingGuard* guard) {
  const Sizing& m = sizing(mesh);
  int flips = 0;
  for (int pass = 0; pass < o.max_passes; ++pass) {
    int this_pass = 0;
    std::vector<EdgeId> edges;
    for (EdgeId e : mesh.edges()) edges.push_back(e);
    for (EdgeId e : edges)
      if (mesh.alive(e) && should_flip(mesh, m, e, o.flip_threshold) && can_flip(mesh, e) && flip_keeps_valid(mesh, m, e) &&
          !(guard && guard->adds_crossings(preview_flip(mesh, e)))) {
        const OpRecord done = flip_edge(mesh, e);
        if (guard) guard->add(done);
        ++this_pass;
      }
    flips += this_pass;
    if (this_pass == 0) break;
  }
  return flips;
}

int split_all(Mesh& mesh, const RemeshOptions& o) {
  int splits = 0;
  auto& m = mesh.vert_attrs().get<Mat2>(kSizingAttr);
  for (int pass = 0; pass < o.max_passes; ++pass) {
    std::vector<std::pair<double, EdgeId>> invalid;
    for (EdgeId e : mesh.edges())
      if (double s2 = edge_size2(mesh, m, e); s2 > 1.0) invalid.emplace_back(s2, e);
    if (invalid.empty()) break;
    std::stable_sort(invalid.begin(), invalid.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [s2, e] : invalid) {
      if (!mesh.alive(e) || edge_size2(mesh, m, e) <= 1.0) continue;
      // The sizing of a new vert is the mean of the tensors at the ends of its side.
      OpRecord r = split_edge(mesh, e, 0.5);
      for (VertId v : r.added_verts) {
        Mat2 sum = Mat2::Zero();
        int count = 0;
        for (FaceId f : mesh.vert_faces(v))
          for (VertId w : mesh.face_verts(f))
            if (w != v && (mesh.vert_node(w) == mesh.edge_node(e, 0) || mesh.vert_node(w) == mesh.edge_node(e, 1))) {
              sum += m[w];
              ++count;
            }
        m[v] = count ? Mat2(sum / count) : m[v];
      }
      ++splits;
    }
  }
  return splits;
}

// Whether every edge that collapsing e (removing end `remove`) would create has s^2 at most
// `limit`: the first one over it decides (most candidates fail, and on their first edges).
bool collapse_fits(const Mesh& mesh, const Sizing& m, EdgeId e, int remove, double limit) {
  const NodeId r = mesh.edge_node(e, remove), k = mesh.edge_node(e, 1 - remove);
  for (VertId vr : mesh.node_verts(r)) {
    const VertId vk = collapse_target(mesh, e, remove, vr);
    if (!vk.valid()) return false;
    for (FaceId f : mesh.vert_faces(vr))
      for (VertId w : mesh.face_verts(f))
        if (mesh.vert_node(w) != r && mesh.vert_node(w) != k && size2(mesh, m, vk, w) > limit) return false;
  }
  return true;
}

// Collapses edges, shortest first, in passes; a pass after the first looks only at the edges
// around nodes that the previous pass changed (elsewhere nothing can have become collapsible).
int collapse_all(Mesh& mesh, const RemeshOptions& o, CrossingGuard* guard) {
  const Sizing& m = sizing(mesh);
  int collapses = 0;
  std::vector<EdgeId> pass_edges;
  for (EdgeId e : mesh.edges()) pass_edges.push_back(e);
  std::vector<char> dirty(static_cast<std::size_t>(mesh.node_capacity()), 0);
  for (int pass = 0; pass < o.max_passes && !pass_edges.empty(); ++pass) {
    std::vector<std::pair<double, EdgeId>> candidates;
    for (EdgeId e : pass_edges)
      if (mesh.alive(e)) candidates.emplace_back(edge_size2(mesh, m, e), e);
    std::stable_sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::fill(dirty.begin(), dirty.end(), 0);
    std::vector<NodeId> changed;
    for (const auto& [s2, e] : candidates) {
      if (!mesh.alive(e)) continue;
      for (int remove = 0; remove < 2; ++remove) {
        if (!collapse_fits(mesh, m, e, remove, 1.0 - o.collapse_margin) || !can_collapse(mesh, e, remove, o.border_sag)) continue;
        if (guard && guard->adds_crossings(preview_collapse(mesh, e, remove))) continue;
        const NodeId kept = mesh.edge_node(e, 1 - remove);
        const OpRecord done = collapse_edge(mesh, e, remove, o.border_sag);
        if (guard) guard->add(done);
        ++collapses;
        changed.push_back(kept);
        break;
      }
    }
    // Next pass: the edges within two rings of every kept node.
    std::vector<NodeId> ring;
    for (NodeId k : changed) {
      if (!mesh.alive(k) || dirty[static_cast<std::size_t>(k.idx)]) continue;
      dirty[static_cast<std::size_t>(k.idx)] = 1;
      ring.push_back(k);
    }
    for (std::size_t i = 0, first_ring = ring.size(); i < first_ring; ++i)
      for (EdgeId x : mesh.node_edges(ring[i])) {
        const NodeId other = mesh.edge_node(x, 0) == ring[i] ? mesh.edge_node(x, 1) : mesh.edge_node(x, 0);
        if (!dirty[static_cast<std::size_t>(other.idx)]) {
          dirty[static_cast<std::size_t>(other.idx)] = 1;
          ring.push_back(other);
        }
      }
    pass_edges.clear();
    for (NodeId n : ring)
      for (EdgeId x : mesh.node_edges(n)) pass_edges.push_back(x);
    std::sort(pass_edges.begin(), pass_edges.end(), [](EdgeId a, EdgeId b) { return a.idx < b.idx; });
    pass_edges.erase(std::unique(pass_edges.begin(), pass_edges.end()), pass_edges.end());
  }
  return collapses;
}

}  // namespace

double edge_size2(const Mesh& mesh, EdgeId e) { return edge_size2(mesh, sizing(mesh), e); }

bool should_flip(const Mesh& mesh, EdgeId e, double threshold) { return should_flip(mesh, sizing(mesh), e, threshold); }

bool flip_keeps_valid(const Mesh& mesh, EdgeId e) { return flip_keeps_valid(mesh, sizing(mesh), e); }

RemeshStats remesh(Mesh& mesh, const RemeshOptions& options, const StandingSurfaces* standing, int self) {
  RemeshStats s;
  s.splits = split_all(mesh, options);
  // Splits do not move the surface: the guard starts from the split mesh.
  std::unique_ptr<CrossingGuard> guard;
  if (standing) guard = std::make_unique<CrossingGuard>(mesh, *standing, self);
  s.flips = flip_all(mesh, options, guard.get());
  s.collapses = collapse_all(mesh, options, guard.get());
  s.flips += flip_all(mesh, options, guard.get());
  if (guard) s.refused = guard->refused();
  mesh.compact();
  return s;
}

}  // namespace vdc
