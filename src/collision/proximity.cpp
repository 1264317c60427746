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

}  // namespace

std::vector<ProximityPair> Collider::proximities(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const std::vector<char>& fixed,
                                                 const std::vector<std::vector<Vec3>>& obstacle_x,
                                                 const std::vector<std::vector<Vec3>>& obstacle_v, double band, int threads) {
  auto cx = [&](int32_t i) { return Vec3(x.segment<3>(3 * i)); };
  auto box_of = [&](std::initializer_list<Vec3> pts) {
    Aabb b;
    for (const Vec3& p : pts) b.grow(p);
    return b;
  };
  const std::vector<Aabb> face_boxes = leaf_boxes(cloth_faces_.size(), threads, [&](std::size_t i) {
    const auto& f = cloth_faces_[i];
    return box_of({cx(f[0]), cx(f[1]), cx(f[2])});
  });
  const std::vector<Aabb> edge_boxes = leaf_boxes(cloth_edges_.size(), threads, [&](std::size_t i) { return box_of({cx(cloth_edges_[i][0]), cx(cloth_edges_[i][1])}); });
  const Bvh& face_bvh = cloth_face_tree_.update(face_boxes);
  const Bvh& edge_bvh = cloth_edge_tree_.update(edge_boxes);
  const std::size_t num_obstacles = obstacles_.size();
  std::vector<const Bvh*> obstacle_face_bvh, obstacle_edge_bvh;
  for (std::size_t o = 0; o < num_obstacles; ++o) {
    obstacle_trees_[o].hold(obstacles_[o].faces, obstacle_edges_[o], obstacle_x[o], threads);
    obstacle_face_bvh.push_back(&obstacle_trees_[o].faces());
    obstacle_edge_bvh.push_back(&obstacle_trees_[o].edges());
  }

  // Fills slot j of a pair with cloth node i (a handle becomes a moving fixed point).
  auto set_cloth = [&](ProximityPair& p, int j, int32_t i, double w) {
    const auto ju = static_cast<std::size_t>(j);
    const bool held = fixed[static_cast<std::size_t>(i)] != 0;
    p.nodes[ju] = held ? -1 : i;
    p.weights[ju] = w;
    p.obstacle_velocity[ju] = held ? Vec3(v.segment<3>(3 * i)) : Vec3::Zero();
  };
  auto set_obstacle = [&](ProximityPair& p, int j, std::size_t o, int32_t i, double w) {
    const auto ju = static_cast<std::size_t>(j);
    p.nodes[ju] = -1;
    p.weights[ju] = w;
    p.obstacle_velocity[ju] = obstacle_v[o][static_cast<std::size_t>(i)];
  };

  std::vector<char> used(static_cast<std::size_t>(num_nodes_), 0);
  for (const auto& f : cloth_faces_)
    for (int32_t n : f) used[static_cast<std::size_t>(n)] = 1;
  const CandidateTrees trees{cloth_faces_, cloth_edges_, used, face_bvh, edge_bvh, obstacle_face_bvh, obstacle_edge_bvh};
  auto point_box = [&](const Vec3& p) {
    Aabb box = box_of({p});
    box.pad(band);
    return box;
  };

  // Cloth vertices: the nearest cloth face on each side, the nearest face of each obstacle.
  const std::size_t per_vertex = 2 + num_obstacles;
  std::vector<std::optional<ProximityPair>> vertex_pairs(static_cast<std::size_t>(num_nodes_) * per_vertex);
  // The face each slot holds: of two faces equally near, the lower-numbered one, so that the
  // pairs do not depend on the order the hierarchies meet them in (a kept hierarchy and one
  // built afresh, as after a resumption, meet them in different orders).
  std::vector<int32_t> slot_face(vertex_pairs.size(), -1);
  std::vector<double> nearest_obstacle(static_cast<std::size_t>(num_nodes_) * num_obstacles, band);  // per vertex and obstacle
  auto cloth_face = [&](int32_t i, int32_t f) {
    const auto& t = cloth_faces_[static_cast<std::size_t>(f)];
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
    const std::size_t at = static_cast<std::size_t>(i) * per_vertex + (n.dot(face_normal) >= 0 ? 0 : 1);
    auto& slot = vertex_pairs[at];
    if (stays(slot ? slot->distance : band, slot_face[at], dist, f)) return;
    slot_face[at] = f;
    ProximityPair pair;
    set_cloth(pair, 0, i, 1.0);
    for (int k = 0; k < 3; ++k) set_cloth(pair, k + 1, t[static_cast<std::size_t>(k)], -w[k]);
    pair.normal = n;
    pair.distance = dist;
    slot = pair;
  };
  auto obstacle_face = [&](int32_t i, std::size_t o, int32_t f) {
    const auto& ox = obstacle_x[o];
    const auto& t = obstacles_[o].faces[static_cast<std::size_t>(f)];
    const Vec3 p = cx(i);
    const Vec3 &a = ox[static_cast<std::size_t>(t[0])], &b = ox[static_cast<std::size_t>(t[1])], &c = ox[static_cast<std::size_t>(t[2])];
    const Vec3 w = closest_triangle_weights(p, a, b, c);
    const Vec3 sep = p - (w[0] * a + w[1] * b + w[2] * c);
    const double dist = sep.norm();
    double& best = nearest_obstacle[static_cast<std::size_t>(i) * num_obstacles + o];
    int32_t& best_face = slot_face[static_cast<std::size_t>(i) * per_vertex + 2 + o];
    if (stays(best, best_face, dist, f)) return;
    const Vec3 outward = face_outward(obstacles_[o], ox, f);
    if (outward.squaredNorm() == 0) return;
    best = dist;
    best_face = f;
    ProximityPair pair;
    set_cloth(pair, 0, i, 1.0);
    for (int k = 0; k < 3; ++k) set_obstacle(pair, k + 1, o, t[static_cast<std::size_t>(k)], -w[k]);
    pair.normal = obstacle_direction(sep, outward, band);
    pair.distance = pair.normal.dot(sep);
    vertex_pairs[static_cast<std::size_t>(i) * per_vertex + 2 + o] = pair;
  };
  vertex_face_candidates(trees, nullptr, threads, [&](int32_t i) { return point_box(cx(i)); }, cloth_face, obstacle_face);

  // Obstacle vertices: the nearest cloth face.
  std::vector<std::vector<std::optional<ProximityPair>>> obstacle_vertex_pairs(num_obstacles);
  std::vector<std::vector<double>> nearest_cloth(num_obstacles);
  std::vector<std::vector<int32_t>> nearest_cloth_face(num_obstacles);
  std::vector<std::vector<std::optional<Vec3>>> outwards(num_obstacles);  // computed once a vertex has a cloth face within the band
  std::vector<std::size_t> obstacle_vertices;
  for (std::size_t o = 0; o < num_obstacles; ++o) {
    const std::size_t n = obstacle_x[o].size();
    obstacle_vertices.push_back(n);
    obstacle_vertex_pairs[o].resize(n);
    nearest_cloth[o].assign(n, band);
    nearest_cloth_face[o].assign(n, -1);
    outwards[o].resize(n);
  }
  obstacle_vertex_candidates(
      trees, obstacle_vertices, nullptr, threads, [&](std::size_t o, int32_t i) { return point_box(obstacle_x[o][static_cast<std::size_t>(i)]); },
      [&](std::size_t o, int32_t i, int32_t f) {
        const auto iu = static_cast<std::size_t>(i);
        const Vec3& p = obstacle_x[o][iu];
        const auto& t = cloth_faces_[static_cast<std::size_t>(f)];
        const Vec3 a = cx(t[0]), b = cx(t[1]), c = cx(t[2]);
        const Vec3 w = closest_triangle_weights(p, a, b, c);
        const Vec3 sep = (w[0] * a + w[1] * b + w[2] * c) - p;
        const double dist = sep.norm();
        int32_t& best_face = nearest_cloth_face[o][iu];
        if (stays(nearest_cloth[o][iu], best_face, dist, f)) return;
        std::optional<Vec3>& outward = outwards[o][iu];
        if (!outward) outward = outward_around(obstacles_[o], obstacle_adjacency_[o].vertex, obstacle_x[o], i);
        if (outward->squaredNorm() == 0) return;
        nearest_cloth[o][iu] = dist;
        best_face = f;
        ProximityPair pair;
        for (int k = 0; k < 3; ++k) set_cloth(pair, k, t[static_cast<std::size_t>(k)], w[k]);
        set_obstacle(pair, 3, o, i, -1.0);
        pair.normal = obstacle_direction(sep, *outward, band);
        pair.distance = pair.normal.dot(sep);
        obstacle_vertex_pairs[o][iu] = pair;
      });

  // Edges: pairs whose closest points are inside both edges, each cloth pair once.
  auto interior = [](double s) { return s > 1e-6 && s < 1 - 1e-6; };
  // Each pair under the edge that met it, keyed by (lower cloth edge, obstacle or -1, the other
  // edge) and computed from the lower cloth edge: the hierarchies decide which edge of a cloth
  // pair meets the other, the key and the pair do not.
  std::vector<std::vector<std::pair<EdgePairKey, ProximityPair>>> edge_pairs(cloth_edges_.size());
  auto cloth_edge_pair = [&](int32_t met_by, int32_t other) {
    const int32_t ea = std::min(met_by, other), eb = std::max(met_by, other);
    const auto& A = cloth_edges_[static_cast<std::size_t>(ea)];
    const auto& B = cloth_edges_[static_cast<std::size_t>(eb)];
    const Vec3 a0 = cx(A[0]), a1 = cx(A[1]), b0 = cx(B[0]), b1 = cx(B[1]);
    const Vec2 su = closest_segment_params(a0, a1, b0, b1);
    if (!interior(su.x()) || !interior(su.y())) return;
    const Vec3 sep = (a0 + su.x() * (a1 - a0)) - (b0 + su.y() * (b1 - b0));
    const double dist = sep.norm();
    if (dist >= band || dist <= 1e-9 * band) return;
    ProximityPair pair;
    set_cloth(pair, 0, A[0], 1 - su.x());
    set_cloth(pair, 1, A[1], su.x());
    set_cloth(pair, 2, B[0], -(1 - su.y()));
    set_cloth(pair, 3, B[1], -su.y());
    pair.normal = sep / dist;
    pair.distance = dist;
    edge_pairs[static_cast<std::size_t>(met_by)].push_back({{ea, -1, eb}, pair});
  };
  auto obstacle_edge_pair = [&](std::size_t o, int32_t ea, int32_t eb) {
    const auto& A = cloth_edges_[static_cast<std::size_t>(ea)];
    const auto& B = obstacle_edges_[o][static_cast<std::size_t>(eb)];
    const auto& ox = obstacle_x[o];
    const Vec3 a0 = cx(A[0]), a1 = cx(A[1]);
    const Vec3 &b0 = ox[static_cast<std::size_t>(B[0])], &b1 = ox[static_cast<std::size_t>(B[1])];
    const Vec2 su = closest_segment_params(a0, a1, b0, b1);
    if (!interior(su.x()) || !interior(su.y())) return;
    const Vec3 sep = (a0 + su.x() * (a1 - a0)) - (b0 + su.y() * (b1 - b0));
    if (sep.norm() >= band) return;
    const Vec3 outward = outward_around(obstacles_[o], obstacle_adjacency_[o].edge, ox, eb);
    if (outward.squaredNorm() == 0) return;
    ProximityPair pair;
    set_cloth(pair, 0, A[0], 1 - su.x());
    set_cloth(pair, 1, A[1], su.x());
    set_obstacle(pair, 2, o, B[0], -(1 - su.y()));
    set_obstacle(pair, 3, o, B[1], -su.y());
    pair.normal = obstacle_direction(sep, outward, band);
    pair.distance = pair.normal.dot(sep);
    edge_pairs[static_cast<std::size_t>(ea)].push_back({{ea, static_cast<int32_t>(o), eb}, pair});
  };
  edge_edge_candidates(trees, nullptr, band, threads, [](int32_t) { return Aabb(); }, cloth_edge_pair, obstacle_edge_pair);

  std::vector<ProximityPair> pairs;
  auto keep = [&](const ProximityPair& p) {
    if (std::any_of(p.nodes.begin(), p.nodes.end(), [](int32_t n) { return n >= 0; })) pairs.push_back(p);
  };
  for (const auto& p : vertex_pairs)
    if (p) keep(*p);
  for (const auto& list : obstacle_vertex_pairs)
    for (const auto& p : list)
      if (p) keep(*p);
  std::vector<std::pair<EdgePairKey, ProximityPair>> keyed;
  for (auto& list : edge_pairs) keyed.insert(keyed.end(), list.begin(), list.end());
  for (const ProximityPair& p : in_key_order(std::move(keyed))) keep(p);
  return pairs;
}

}  // namespace vdc
