// Proximity pairs at the start of a step (Bridson, Fedkiw and Anderson 2002, section 7.2): the
// cloth and obstacle primitives closer than the repulsion thickness, with the normal that
// separates them. A cloth vertex pairs with a cloth face only when it is over the face. Obstacles
// have an outside (their faces' normals), so a cloth point that has sunk into an obstacle is
// pushed back out, not further in.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "collision/candidates.hpp"
#include "collision/collider.hpp"
#include "collision/distance.hpp"

namespace vdc {

namespace {

Vec3 unit_or_zero(const Vec3& a) {
  const double n = a.norm();
  return n > 0 ? Vec3(a / n) : Vec3::Zero();
}

// An obstacle's outward unit normal (zero if degenerate) at its current positions x: of a face,
// or the area-weighted average over the faces around a vertex or an edge.
Vec3 face_outward(const CollisionMesh& mesh, const std::vector<Vec3>& x, int32_t f) {
  const auto& t = mesh.faces[static_cast<std::size_t>(f)];
  return unit_or_zero(area_normal(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])], x[static_cast<std::size_t>(t[2])]));
}
Vec3 outward_around(const CollisionMesh& mesh, const FacesAround& around, const std::vector<Vec3>& x, int64_t item) {
  if (item + 1 >= static_cast<int64_t>(around.start.size())) return Vec3::Zero();  // a vertex no face uses
  Vec3 sum = Vec3::Zero();
  for (int32_t k = around.start[static_cast<std::size_t>(item)]; k < around.start[static_cast<std::size_t>(item) + 1]; ++k) {
    const auto& t = mesh.faces[static_cast<std::size_t>(around.faces[static_cast<std::size_t>(k)])];
    sum += area_normal(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])], x[static_cast<std::size_t>(t[2])]);
  }
  return unit_or_zero(sum);
}

// The separating direction of a cloth point from an obstacle point whose outward normal is
// `outward`: straight away when the cloth is outside and not too close to tell, else the normal.
Vec3 obstacle_direction(const Vec3& sep, const Vec3& outward, double band) {
  const double len = sep.norm();
  if (sep.dot(outward) > 0 && len > 0.1 * band) return sep / len;
  return outward;
}

// Whether the nearest so far (distance `kept`, primitive `kept_index`, -1 for none yet with
// `kept` the search radius) stays against a primitive at `dist`: nearer, or as near and
// lower-numbered, so that the order the hierarchies meet them in does not matter.
bool stays(double kept, int32_t kept_index, double dist, int32_t index) {
  if (kept_index < 0) return kept <= dist;
  return kept < dist || (kept == dist && kept_index <= index);
}

using EdgePairKey = std::array<int32_t, 3>;

Aabb box_of(std::initializer_list<Vec3> pts) {
  Aabb b;
  for (const Vec3& p : pts) b.grow(p);
  return b;
}

bool interior(double s) { return s > 1e-6 && s < 1 - 1e-6; }

// Whether two edges' closest points can be inside both (closest_line_params): when not, the
// pair is no edge pair, and the endpoint candidates need not be computed.
bool lines_meet_inside(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  const std::optional<Vec2> lines = closest_line_params(a0, a1, b0, b1);
  return lines && interior(lines->x()) && interior(lines->y());
}

// The collider's primitives and their state at the step's start: what a search pairs.
struct ProximityScene {
  const std::vector<std::array<int32_t, 3>>& cloth_faces;
  const std::vector<std::array<int32_t, 2>>& cloth_edges;
  const std::vector<CollisionMesh>& obstacles;
  const std::vector<std::vector<std::array<int32_t, 2>>>& obstacle_edges;
  const std::vector<ObstacleAdjacency>& adjacency;
  const Eigen::VectorXd& x;
  const Eigen::VectorXd& v;
  const std::vector<char>& fixed;
  const std::vector<std::vector<Vec3>>& obstacle_x;
  const std::vector<std::vector<Vec3>>& obstacle_v;
  double band;
};

// One search for the proximity pairs: each kind of pair found by its candidates' callbacks
// (called in parallel, one query primitive's slots each), then taken in a fixed order.
class ProximitySearch {
 public:
  // `kept`: the cloth-cloth pairs listed by an earlier search (taken when cloth_vertices and
  // edges are given the primitives beyond their reach), or to be listed by this one.
  ProximitySearch(const ProximityScene& scene, int32_t num_nodes, KeptClothPairs& kept)
      : s_(scene), kept_(kept), num_obstacles_(scene.obstacles.size()), per_vertex_(2 + num_obstacles_),
        vertex_pairs_(static_cast<std::size_t>(num_nodes) * per_vertex_), slot_face_(vertex_pairs_.size(), -1),
        nearest_obstacle_(static_cast<std::size_t>(num_nodes) * num_obstacles_, scene.band),
        obstacle_vertex_pairs_(num_obstacles_), nearest_cloth_(num_obstacles_), nearest_cloth_face_(num_obstacles_),
        outwards_(num_obstacles_), edge_pairs_(scene.cloth_edges.size()) {
    for (std::size_t o = 0; o < num_obstacles_; ++o) {
      const std::size_t n = s_.obstacle_x[o].size();
      obstacle_vertex_pairs_[o].resize(n);
      nearest_cloth_[o].assign(n, s_.band);
      nearest_cloth_face_[o].assign(n, -1);
      outwards_[o].resize(n);
    }
  }

  // Cloth vertices: the nearest cloth face on each side, the nearest face of each obstacle.
  // Without `far`, every node queries the hierarchies with its box grown by the lists' pad, its
  // cloth faces listed in `kept_`, and the pairs within the band tested; with `far`, the kept
  // lists answer for the nodes that stayed near where they were made.
  void cloth_vertices(const CandidateTrees& trees, const MovedPrimitives* far, int threads) {
    auto face = [&](int32_t i, int32_t f) { cloth_face(i, f); };
    auto obstacle = [&](int32_t i, std::size_t o, int32_t f) { obstacle_face(i, o, f); };
    if (far != nullptr) {
      vertex_face_candidates(trees, far, &kept_, threads, [&](int32_t i) { return point_box(cx(i), s_.band); }, face, obstacle);
      return;
    }
    vertex_face_candidates(
        trees, nullptr, nullptr, threads, [&](int32_t i) { return point_box(cx(i), kept_.pad); },
        [&](int32_t i, int32_t f) {
          kept_.node_faces[static_cast<std::size_t>(i)].push_back(f);
          if (trees.cloth_face_tree.leaf_boxes()[static_cast<std::size_t>(f)].overlaps(point_box(cx(i), s_.band))) face(i, f);
        },
        [&](int32_t i, std::size_t o, int32_t f) {
          if (trees.obstacle_face_trees[o]->leaf_boxes()[static_cast<std::size_t>(f)].overlaps(point_box(cx(i), s_.band))) obstacle(i, o, f);
        });
  }

  // Obstacle vertices: the nearest cloth face. The obstacles' vertex hierarchies hold their
  // vertices' points (ObstacleTrees::hold): grown by the band, each box is the vertex's point box.
  void obstacle_vertices(const CandidateTrees& trees, int threads) {
    obstacle_vertex_candidates(trees, nullptr, s_.band, threads, [&](std::size_t o, int32_t i, int32_t f) { obstacle_vertex_face(o, i, f); });
  }

  // Edges: pairs whose closest points are inside both edges, each cloth pair once; the cloth
  // pairs listed or taken from the lists as for the vertices. `edge_boxes`: the cloth edges'.
  void edges(const CandidateTrees& trees, const std::vector<Aabb>& edge_boxes, const MovedPrimitives* far, int threads) {
    auto grown = [&](int32_t e) {
      Aabb b = edge_boxes[static_cast<std::size_t>(e)];
      b.pad(s_.band);
      return b;
    };
    auto cloth = [&](int32_t met_by, int32_t other) { cloth_edge_pair(met_by, other); };
    auto obstacle = [&](std::size_t o, int32_t ea, int32_t eb) { obstacle_edge_pair(o, ea, eb); };
    if (far != nullptr) {
      edge_edge_candidates(trees, far, &kept_, s_.band, threads, cloth, obstacle);
      return;
    }
    edge_edge_candidates(
        trees, nullptr, nullptr, kept_.pad, threads,
        [&](int32_t met_by, int32_t other) {
          kept_.edge_edges[static_cast<std::size_t>(met_by)].push_back(other);
          if (grown(met_by).overlaps(edge_boxes[static_cast<std::size_t>(other)])) cloth(met_by, other);
        },
        [&](std::size_t o, int32_t ea, int32_t eb) {
          if (grown(ea).overlaps(trees.obstacle_edge_trees[o]->leaf_boxes()[static_cast<std::size_t>(eb)])) obstacle(o, ea, eb);
        });
  }

  // Every pair found with a node that moves in the solve: vertex pairs in slot order, then the
  // edge pairs in key order.
  std::vector<ProximityPair> pairs() {
    std::vector<ProximityPair> pairs;
    auto keep = [&](const ProximityPair& p) {
      if (std::any_of(p.nodes.begin(), p.nodes.end(), [](int32_t n) { return n >= 0; })) pairs.push_back(p);
    };
    for (const auto& p : vertex_pairs_)
      if (p) keep(*p);
    for (const auto& list : obstacle_vertex_pairs_)
      for (const auto& p : list)
        if (p) keep(*p);
    std::vector<std::pair<EdgePairKey, ProximityPair>> keyed;
    for (auto& list : edge_pairs_) keyed.insert(keyed.end(), list.begin(), list.end());
    for (const ProximityPair& p : in_key_order(std::move(keyed))) keep(p);
    return pairs;
  }

 private:
  Vec3 cx(int32_t i) const { return Vec3(s_.x.segment<3>(3 * i)); }

  Aabb point_box(const Vec3& p, double pad) const {
    Aabb box = box_of({p});
    box.pad(pad);
    return box;
  }

  // Fills slot j of a pair with cloth node i (a handle becomes a moving fixed point).
  void set_cloth(ProximityPair& p, int j, int32_t i, double w) const {
    const auto ju = static_cast<std::size_t>(j);
    const bool held = s_.fixed[static_cast<std::size_t>(i)] != 0;
    p.nodes[ju] = held ? -1 : i;
    p.weights[ju] = w;
    p.obstacle_velocity[ju] = held ? Vec3(s_.v.segment<3>(3 * i)) : Vec3::Zero();
  }
  void set_obstacle(ProximityPair& p, int j, std::size_t o, int32_t i, double w) const {
    const auto ju = static_cast<std::size_t>(j);
    p.nodes[ju] = -1;
    p.weights[ju] = w;
    p.obstacle_velocity[ju] = s_.obstacle_v[o][static_cast<std::size_t>(i)];
  }

  // Cloth vertex i against cloth face f. The face each slot holds: of two faces equally near,
  // the lower-numbered one, so that the pairs do not depend on the order the hierarchies meet
  // them in (a kept hierarchy and one built afresh, as after a resumption, meet them in
  // different orders).
  void cloth_face(int32_t i, int32_t f) {
    const double band = s_.band;
    const auto& t = s_.cloth_faces[static_cast<std::size_t>(f)];
    const Vec3 p = cx(i), a = cx(t[0]), b = cx(t[1]), c = cx(t[2]);
    const Vec3 w = closest_triangle_weights(p, a, b, c);
    const Vec3 sep = p - (w[0] * a + w[1] * b + w[2] * c);
    const double dist = sep.norm();
    if (dist >= band) return;
    const Vec3 face_normal = unit_or_zero((b - a).cross(c - a));
    // Only a vertex over the face, its border included (Bridson et al. 2002, section 7.2): a
    // closest point that the border clamps lies in a flat sheet's own plane whenever the band
    // reaches past the vertex's 2-ring, and pushing it would compress the sheet. Edge-edge
    // pairs cover the rest.
    if ((sep - sep.dot(face_normal) * face_normal).norm() > 1e-6 * band) return;
    const Vec3 n = dist > 1e-9 * band ? Vec3(sep / dist) : face_normal;
    if (n.squaredNorm() == 0) return;
    const std::size_t at = static_cast<std::size_t>(i) * per_vertex_ + (n.dot(face_normal) >= 0 ? 0 : 1);
    auto& slot = vertex_pairs_[at];
    if (stays(slot ? slot->distance : band, slot_face_[at], dist, f)) return;
    slot_face_[at] = f;
    ProximityPair pair;
    set_cloth(pair, 0, i, 1.0);
    for (int k = 0; k < 3; ++k) set_cloth(pair, k + 1, t[static_cast<std::size_t>(k)], -w[k]);
    pair.normal = n;
    pair.distance = dist;
    slot = pair;
  }

  // Cloth vertex i against face f of obstacle o.
  void obstacle_face(int32_t i, std::size_t o, int32_t f) {
    const auto& ox = s_.obstacle_x[o];
    const auto& t = s_.obstacles[o].faces[static_cast<std::size_t>(f)];
    const Vec3 p = cx(i);
    const Vec3 &a = ox[static_cast<std::size_t>(t[0])], &b = ox[static_cast<std::size_t>(t[1])], &c = ox[static_cast<std::size_t>(t[2])];
    const Vec3 w = closest_triangle_weights(p, a, b, c);
    const Vec3 sep = p - (w[0] * a + w[1] * b + w[2] * c);
    const double dist = sep.norm();
    double& best = nearest_obstacle_[static_cast<std::size_t>(i) * num_obstacles_ + o];
    int32_t& best_face = slot_face_[static_cast<std::size_t>(i) * per_vertex_ + 2 + o];
    if (stays(best, best_face, dist, f)) return;
    const Vec3 outward = face_outward(s_.obstacles[o], ox, f);
    if (outward.squaredNorm() == 0) return;
    best = dist;
    best_face = f;
    ProximityPair pair;
    set_cloth(pair, 0, i, 1.0);
    for (int k = 0; k < 3; ++k) set_obstacle(pair, k + 1, o, t[static_cast<std::size_t>(k)], -w[k]);
    pair.normal = obstacle_direction(sep, outward, s_.band);
    pair.distance = pair.normal.dot(sep);
    vertex_pairs_[static_cast<std::size_t>(i) * per_vertex_ + 2 + o] = pair;
  }

  // Vertex i of obstacle o against cloth face f; the vertex's outward normal computed once a
  // cloth face is within the band.
  void obstacle_vertex_face(std::size_t o, int32_t i, int32_t f) {
    const auto iu = static_cast<std::size_t>(i);
    const Vec3& p = s_.obstacle_x[o][iu];
    const auto& t = s_.cloth_faces[static_cast<std::size_t>(f)];
    const Vec3 a = cx(t[0]), b = cx(t[1]), c = cx(t[2]);
    const Vec3 w = closest_triangle_weights(p, a, b, c);
    const Vec3 sep = (w[0] * a + w[1] * b + w[2] * c) - p;
    const double dist = sep.norm();
    int32_t& best_face = nearest_cloth_face_[o][iu];
    if (stays(nearest_cloth_[o][iu], best_face, dist, f)) return;
    std::optional<Vec3>& outward = outwards_[o][iu];
    if (!outward) outward = outward_around(s_.obstacles[o], s_.adjacency[o].vertex, s_.obstacle_x[o], i);
    if (outward->squaredNorm() == 0) return;
    nearest_cloth_[o][iu] = dist;
    best_face = f;
    ProximityPair pair;
    for (int k = 0; k < 3; ++k) set_cloth(pair, k, t[static_cast<std::size_t>(k)], w[k]);
    set_obstacle(pair, 3, o, i, -1.0);
    pair.normal = obstacle_direction(sep, *outward, s_.band);
    pair.distance = pair.normal.dot(sep);
    obstacle_vertex_pairs_[o][iu] = pair;
  }

  // Each edge pair under the edge that met it, keyed by (lower cloth edge, obstacle or -1, the
  // other edge) and computed from the lower cloth edge: the hierarchies decide which edge of a
  // cloth pair meets the other, the key and the pair do not.
  void cloth_edge_pair(int32_t met_by, int32_t other) {
    const int32_t ea = std::min(met_by, other), eb = std::max(met_by, other);
    const auto& A = s_.cloth_edges[static_cast<std::size_t>(ea)];
    const auto& B = s_.cloth_edges[static_cast<std::size_t>(eb)];
    const Vec3 a0 = cx(A[0]), a1 = cx(A[1]), b0 = cx(B[0]), b1 = cx(B[1]);
    if (!lines_meet_inside(a0, a1, b0, b1)) return;
    const Vec2 su = closest_segment_params(a0, a1, b0, b1);
    if (!interior(su.x()) || !interior(su.y())) return;
    const Vec3 sep = (a0 + su.x() * (a1 - a0)) - (b0 + su.y() * (b1 - b0));
    const double dist = sep.norm();
    if (dist >= s_.band || dist <= 1e-9 * s_.band) return;
    ProximityPair pair;
    set_cloth(pair, 0, A[0], 1 - su.x());
    set_cloth(pair, 1, A[1], su.x());
    set_cloth(pair, 2, B[0], -(1 - su.y()));
    set_cloth(pair, 3, B[1], -su.y());
    pair.normal = sep / dist;
    pair.distance = dist;
    edge_pairs_[static_cast<std::size_t>(met_by)].push_back({{ea, -1, eb}, pair});
  }

  void obstacle_edge_pair(std::size_t o, int32_t ea, int32_t eb) {
    const auto& A = s_.cloth_edges[static_cast<std::size_t>(ea)];
    const auto& B = s_.obstacle_edges[o][static_cast<std::size_t>(eb)];
    const auto& ox = s_.obstacle_x[o];
    const Vec3 a0 = cx(A[0]), a1 = cx(A[1]);
    const Vec3 &b0 = ox[static_cast<std::size_t>(B[0])], &b1 = ox[static_cast<std::size_t>(B[1])];
    if (!lines_meet_inside(a0, a1, b0, b1)) return;
    const Vec2 su = closest_segment_params(a0, a1, b0, b1);
    if (!interior(su.x()) || !interior(su.y())) return;
    const Vec3 sep = (a0 + su.x() * (a1 - a0)) - (b0 + su.y() * (b1 - b0));
    if (sep.norm() >= s_.band) return;
    const Vec3 outward = outward_around(s_.obstacles[o], s_.adjacency[o].edge, ox, eb);
    if (outward.squaredNorm() == 0) return;
    ProximityPair pair;
    set_cloth(pair, 0, A[0], 1 - su.x());
    set_cloth(pair, 1, A[1], su.x());
    set_obstacle(pair, 2, o, B[0], -(1 - su.y()));
    set_obstacle(pair, 3, o, B[1], -su.y());
    pair.normal = obstacle_direction(sep, outward, s_.band);
    pair.distance = pair.normal.dot(sep);
    edge_pairs_[static_cast<std::size_t>(ea)].push_back({{ea, static_cast<int32_t>(o), eb}, pair});
  }

  const ProximityScene& s_;
  KeptClothPairs& kept_;
  const std::size_t num_obstacles_, per_vertex_;
  std::vector<std::optional<ProximityPair>> vertex_pairs_;  // per cloth vertex: two cloth sides, then each obstacle
  std::vector<int32_t> slot_face_;          // the face each slot holds
  std::vector<double> nearest_obstacle_;    // per cloth vertex and obstacle
  std::vector<std::vector<std::optional<ProximityPair>>> obstacle_vertex_pairs_;
  std::vector<std::vector<double>> nearest_cloth_;
  std::vector<std::vector<int32_t>> nearest_cloth_face_;
  std::vector<std::vector<std::optional<Vec3>>> outwards_;
  std::vector<std::vector<std::pair<EdgePairKey, ProximityPair>>> edge_pairs_;  // under the edge that met them
};

}  // namespace

std::vector<ProximityPair> Collider::proximities(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const std::vector<char>& fixed,
                                                 const std::vector<std::vector<Vec3>>& obstacle_x,
                                                 const std::vector<std::vector<Vec3>>& obstacle_v, double band, int threads) {
  auto cx = [&](int32_t i) { return Vec3(x.segment<3>(3 * i)); };
  const std::vector<Aabb> face_boxes = leaf_boxes(cloth_faces_.size(), threads, [&](std::size_t i) {
    const auto& f = cloth_faces_[i];
    return box_of({cx(f[0]), cx(f[1]), cx(f[2])});
  });
  const std::vector<Aabb> edge_boxes = leaf_boxes(cloth_edges_.size(), threads, [&](std::size_t i) { return box_of({cx(cloth_edges_[i][0]), cx(cloth_edges_[i][1])}); });
  const Bvh& face_bvh = cloth_face_tree_.update(face_boxes, threads);
  const Bvh& edge_bvh = cloth_edge_tree_.update(edge_boxes, threads);
  std::vector<const Bvh*> obstacle_vertex_bvh, obstacle_face_bvh, obstacle_edge_bvh;
  for (std::size_t o = 0; o < obstacles_.size(); ++o) {
    obstacle_trees_[o].hold(obstacles_[o].faces, obstacle_edges_[o], obstacle_x[o], threads);
    obstacle_vertex_bvh.push_back(&obstacle_trees_[o].vertices());
    obstacle_face_bvh.push_back(&obstacle_trees_[o].faces());
    obstacle_edge_bvh.push_back(&obstacle_trees_[o].edges());
  }
  std::vector<char> used(static_cast<std::size_t>(num_nodes_), 0);
  for (const auto& f : cloth_faces_)
    for (int32_t n : f) used[static_cast<std::size_t>(n)] = 1;
  const CandidateTrees trees{cloth_faces_, cloth_edges_, used, face_bvh, edge_bvh, obstacle_vertex_bvh, obstacle_face_bvh, obstacle_edge_bvh};
  const ProximityScene scene{cloth_faces_, cloth_edges_, obstacles_, obstacle_edges_, obstacle_adjacency_, x, v, fixed,
                             obstacle_x, obstacle_v, band};
  // The kept lists answer while at most one node in sixteen has gone beyond their reach; else
  // this search makes them again, reaching a band past its own.
  std::vector<char> far;
  std::optional<MovedPrimitives> far_primitives;
  if (kept_pairs_.x.size() == x.size() && kept_pairs_.pad == 2 * band) {
    far = kept_pairs_.beyond(x, x, band, used);
    if (KeptClothPairs::worth_taking(far, used)) far_primitives.emplace(far, trees, face_boxes, edge_boxes);
  }
  if (!far_primitives) {
    kept_pairs_.clear(static_cast<std::size_t>(num_nodes_), cloth_edges_.size());
    kept_pairs_.x = x;
    kept_pairs_.pad = 2 * band;
  }
  const MovedPrimitives* listed = far_primitives ? &*far_primitives : nullptr;
  ProximitySearch search(scene, num_nodes_, kept_pairs_);
  search.cloth_vertices(trees, listed, threads);
  search.obstacle_vertices(trees, threads);
  search.edges(trees, edge_boxes, listed, threads);
  return search.pairs();
}

}  // namespace vdc
