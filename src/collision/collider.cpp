// Collision handling: continuous detection plus impact zones (Bridson et al. 2002, section 7.4;
// Harmon et al. 2008, section 4), iterated until no impact is left.
#include "collision/collider.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <numeric>
#include <optional>
#include <utility>

#include "collision/candidates.hpp"
#include "collision/impact_zone.hpp"
#include "collision/narrow_phase.hpp"

namespace vdc {

namespace {

// Unique edges of a triangle list, and for each face the indices of its three edges (sorted
// by their end nodes, then numbered).
void edges_of(const std::vector<std::array<int32_t, 3>>& faces, std::vector<std::array<int32_t, 2>>& edges,
              std::vector<std::array<int32_t, 3>>& face_edges) {
  struct Side {
    int32_t lo, hi;
    int32_t slot;  // 3 * face + corner
  };
  std::vector<Side> sides;
  sides.reserve(3 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const int32_t a = faces[f][static_cast<std::size_t>(i)], b = faces[f][static_cast<std::size_t>((i + 1) % 3)];
      sides.push_back({std::min(a, b), std::max(a, b), static_cast<int32_t>(3 * f) + i});
    }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) { return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.slot < y.slot; });
  face_edges.resize(faces.size());
  for (std::size_t k = 0; k < sides.size(); ++k) {
    if (k == 0 || sides[k].lo != sides[k - 1].lo || sides[k].hi != sides[k - 1].hi) edges.push_back({sides[k].lo, sides[k].hi});
    face_edges[static_cast<std::size_t>(sides[k].slot / 3)][static_cast<std::size_t>(sides[k].slot % 3)] = static_cast<int32_t>(edges.size()) - 1;
  }
}

// The faces around each of `num_items` items, given each face's three items (its corners or its
// edges).
FacesAround faces_around(const std::vector<std::array<int32_t, 3>>& face_items, std::size_t num_items) {
  FacesAround a;
  a.start.assign(num_items + 1, 0);
  for (const auto& f : face_items)
    for (int32_t k : f) ++a.start[static_cast<std::size_t>(k) + 1];
  std::partial_sum(a.start.begin(), a.start.end(), a.start.begin());
  a.faces.resize(3 * face_items.size());
  std::vector<int32_t> next(a.start.begin(), a.start.end() - 1);
  for (std::size_t f = 0; f < face_items.size(); ++f)
    for (int32_t k : face_items[f]) a.faces[static_cast<std::size_t>(next[static_cast<std::size_t>(k)]++)] = static_cast<int32_t>(f);
  return a;
}

ObstacleAdjacency adjacency_of(const CollisionMesh& mesh, const std::vector<std::array<int32_t, 3>>& face_edges, std::size_t num_edges) {
  int32_t num_vertices = 0;
  for (const auto& f : mesh.faces) num_vertices = std::max({num_vertices, f[0] + 1, f[1] + 1, f[2] + 1});
  return {faces_around(mesh.faces, static_cast<std::size_t>(num_vertices)), faces_around(face_edges, num_edges)};
}

// A point of the scene: a cloth node (obstacle < 0) or an obstacle vertex.
struct PointRef {
  int32_t obstacle;
  int32_t index;
};

// The collider's primitives and their positions at the start and end of the step.
struct SweptScene {
  const std::vector<std::array<int32_t, 3>>& cloth_faces;
  const std::vector<std::array<int32_t, 2>>& cloth_edges;
  const std::vector<CollisionMesh>& obstacles;
  const std::vector<std::vector<std::array<int32_t, 2>>>& obstacle_edges;
  const Eigen::VectorXd& x_start;
  const Eigen::VectorXd& x_end;  // as the last round of projection left it
  const std::vector<char>& fixed;
  const std::vector<std::vector<Vec3>>& obstacle_start;
  const std::vector<std::vector<Vec3>>& obstacle_end;
  double eta;  // the contact tolerance
};

Vec3 start_of(const SweptScene& s, const PointRef& p) {
  return p.obstacle < 0 ? Vec3(s.x_start.segment<3>(3 * p.index))
                        : s.obstacle_start[static_cast<std::size_t>(p.obstacle)][static_cast<std::size_t>(p.index)];
}
Vec3 end_of(const SweptScene& s, const PointRef& p) {
  return p.obstacle < 0 ? Vec3(s.x_end.segment<3>(3 * p.index))
                        : s.obstacle_end[static_cast<std::size_t>(p.obstacle)][static_cast<std::size_t>(p.index)];
}

// The swept box of primitives over the step, padded by the contact tolerance.
Aabb path_box(const SweptScene& s, std::initializer_list<PointRef> pts) {
  Aabb b;
  for (const PointRef& p : pts) {
    b.grow(start_of(s, p));
    b.grow(end_of(s, p));
  }
  b.pad(s.eta);
  return b;
}

// One round of continuous detection (Bridson et al. 2002, section 7.4): the candidates go to the
// narrow phase (narrow_phase.hpp) as the paths of their points over the step, each query
// primitive's impacts into its own list; the lists are taken in primitive order, so the
// results do not depend on the thread count. Each impact is keyed by (query primitive, obstacle
// or -1, the other primitive), a cloth edge pair by its lower edge, and taken in key order.
//
// The work bound of a round: each query primitive counts the candidates it meets in its own
// slot (the round's total, and so whether it is over, does not depend on the threads), and adds
// them to a shared tally 64 at a time; once the tally, which never runs ahead of the total, is
// past the bound, no candidate is tested any more.
class ImpactRound {
 public:
  ImpactRound(const SweptScene& scene, int64_t budget) : s_(scene), budget_(budget) {}

  // Finds the round's impacts: cloth vertices against cloth and obstacle faces, obstacle
  // vertices against cloth faces, cloth edges against cloth and obstacle edges.
  // `only_moved` and `listed` as for vertex_face_candidates: none in a first round that searches
  // everything, both in one that takes a proximity search's kept pairs, `only_moved` alone in a
  // later round. Obstacle vertices meet every cloth face in a first round.
  void detect(const CandidateTrees& trees, const MovedPrimitives* only_moved, const KeptClothPairs* listed, int threads) {
    vertex_hits_.assign(trees.node_used.size(), Hits{});
    vertex_face_candidates(
        trees, only_moved, listed, threads, [&](int32_t v) { return path_box(s_, {PointRef{-1, v}}); },
        [&](int32_t v, int32_t f) { vf({-1, v}, cloth_tri(f), {v, -1, f}, vertex_hits_[static_cast<std::size_t>(v)]); },
        [&](int32_t v, std::size_t o, int32_t f) {
          vf({-1, v}, obstacle_tri(o, f), {v, static_cast<int32_t>(o), f}, vertex_hits_[static_cast<std::size_t>(v)]);
        });
    obstacle_hits_.assign(s_.obstacles.size(), {});
    for (std::size_t o = 0; o < s_.obstacles.size(); ++o) obstacle_hits_[o].resize(s_.obstacle_start[o].size());
    obstacle_vertex_candidates(
        trees, listed != nullptr ? nullptr : only_moved, 0.0, threads, [&](std::size_t o, int32_t v, int32_t f) {
          vf({static_cast<int32_t>(o), v}, cloth_tri(f), {v, static_cast<int32_t>(o), f}, obstacle_hits_[o][static_cast<std::size_t>(v)]);
        });
    edge_hits_.assign(s_.cloth_edges.size(), Hits{});
    edge_edge_candidates(
        trees, only_moved, listed, 0.0, threads, [&](int32_t met_by, int32_t other) { cloth_edges(met_by, other); },
        [&](std::size_t o, int32_t ea, int32_t eo) { obstacle_edges(o, ea, eo); });
  }

  // The candidates the round met, summed over its query primitives.
  int64_t met() const {
    int64_t met = 0;
    for (const Hits& h : vertex_hits_) met += h.met;
    for (const auto& per_obstacle : obstacle_hits_)
      for (const Hits& h : per_obstacle) met += h.met;
    for (const Hits& h : edge_hits_) met += h.met;
    return met;
  }

  // The impacts, vertex ones by query vertex, then the edge ones in key order.
  std::vector<ImpactConstraint> impacts() {
    std::vector<ImpactConstraint> found;
    auto take = [&](std::vector<std::pair<Key, ImpactConstraint>> hits) {
      for (ImpactConstraint& c : in_key_order(std::move(hits))) found.push_back(std::move(c));
    };
    for (Hits& h : vertex_hits_) take(std::move(h.found));
    for (auto& per_obstacle : obstacle_hits_)
      for (Hits& h : per_obstacle) take(std::move(h.found));
    std::vector<std::pair<Key, ImpactConstraint>> edge_found;  // a cloth pair under either edge: sorted as one
    for (Hits& h : edge_hits_) edge_found.insert(edge_found.end(), h.found.begin(), h.found.end());
    take(std::move(edge_found));
    return found;
  }

 private:
  using Key = std::array<int32_t, 3>;
  struct Hits {
    std::vector<std::pair<Key, ImpactConstraint>> found;
    int32_t met = 0;  // candidates met by this query primitive
  };

  std::array<PointRef, 3> cloth_tri(int32_t f) const {
    const auto& t = s_.cloth_faces[static_cast<std::size_t>(f)];
    return {PointRef{-1, t[0]}, PointRef{-1, t[1]}, PointRef{-1, t[2]}};
  }
  std::array<PointRef, 3> obstacle_tri(std::size_t o, int32_t f) const {
    const auto& t = s_.obstacles[o].faces[static_cast<std::size_t>(f)];
    const auto oi = static_cast<int32_t>(o);
    return {PointRef{oi, t[0]}, PointRef{oi, t[1]}, PointRef{oi, t[2]}};
  }
  PointPath path(const PointRef& p) const {
    const bool movable = p.obstacle < 0 && !s_.fixed[static_cast<std::size_t>(p.index)];
    return PointPath{start_of(s_, p), end_of(s_, p), movable ? p.index : -1};
  }
  bool within_budget(Hits& out) {
    if ((++out.met & 63) == 0) tally_.fetch_add(64, std::memory_order_relaxed);
    return tally_.load(std::memory_order_relaxed) <= budget_;
  }
  void vf(const PointRef& p, const std::array<PointRef, 3>& tri, const Key& key, Hits& out) {
    if (!within_budget(out)) return;
    if (auto hit = vertex_face_impact(path(p), path(tri[0]), path(tri[1]), path(tri[2]), s_.eta)) out.found.push_back({key, *hit});
  }
  void ee(const PointRef& a, const PointRef& b, const PointRef& c, const PointRef& d, const Key& key, Hits& out) {
    if (!within_budget(out)) return;
    if (auto hit = edge_edge_impact(path(a), path(b), path(c), path(d), s_.eta)) out.found.push_back({key, *hit});
  }
  void cloth_edges(int32_t met_by, int32_t other) {
    const int32_t ea = std::min(met_by, other), eb = std::max(met_by, other);
    const auto& A = s_.cloth_edges[static_cast<std::size_t>(ea)];
    const auto& B = s_.cloth_edges[static_cast<std::size_t>(eb)];
    ee({-1, A[0]}, {-1, A[1]}, {-1, B[0]}, {-1, B[1]}, {ea, -1, eb}, edge_hits_[static_cast<std::size_t>(met_by)]);
  }
  void obstacle_edges(std::size_t o, int32_t ea, int32_t eo) {
    const auto& A = s_.cloth_edges[static_cast<std::size_t>(ea)];
    const auto& B = s_.obstacle_edges[o][static_cast<std::size_t>(eo)];
    const auto oi = static_cast<int32_t>(o);
    ee({-1, A[0]}, {-1, A[1]}, {oi, B[0]}, {oi, B[1]}, {ea, oi, eo}, edge_hits_[static_cast<std::size_t>(ea)]);
  }

  const SweptScene& s_;
  const int64_t budget_;
  std::atomic<int64_t> tally_{0};
  std::vector<Hits> vertex_hits_, edge_hits_;
  std::vector<std::vector<Hits>> obstacle_hits_;
};

}  // namespace

Collider::Collider(const std::vector<std::array<int32_t, 3>>& cloth_faces, std::vector<CollisionMesh> obstacles, int32_t num_nodes)
    : obstacles_(std::move(obstacles)) {
  obstacle_edges_.resize(obstacles_.size());
  obstacle_face_edges_.resize(obstacles_.size());
  for (std::size_t o = 0; o < obstacles_.size(); ++o) {
    edges_of(obstacles_[o].faces, obstacle_edges_[o], obstacle_face_edges_[o]);
    obstacle_adjacency_.push_back(adjacency_of(obstacles_[o], obstacle_face_edges_[o], obstacle_edges_[o].size()));
  }
  obstacle_trees_.resize(obstacles_.size());
  set_cloth(cloth_faces, num_nodes);
}

void Collider::set_cloth(const std::vector<std::array<int32_t, 3>>& cloth_faces, int32_t num_nodes) {
  cloth_faces_ = cloth_faces;
  num_nodes_ = num_nodes;
  cloth_edges_.clear();
  face_edges_.clear();
  edges_of(cloth_faces_, cloth_edges_, face_edges_);
  cloth_face_tree_ = RefitBvh();
  cloth_edge_tree_ = RefitBvh();
  kept_pairs_ = KeptClothPairs();
}

std::vector<const Bvh*> face_trees_at(const std::vector<CollisionMesh>& obstacles, const std::vector<std::vector<Vec3>>& obstacle_x,
                                      const std::vector<const Bvh*>& given, int threads, std::vector<std::unique_ptr<Bvh>>& built) {
  std::vector<const Bvh*> trees;
  for (std::size_t o = 0; o < obstacles.size(); ++o) {
    if (o < given.size() && given[o] != nullptr) {
      trees.push_back(given[o]);
      continue;
    }
    built.push_back(std::make_unique<Bvh>(leaf_boxes(obstacles[o].faces.size(), threads, [&](std::size_t f) {
      Aabb box;
      for (int32_t v : obstacles[o].faces[f]) box.grow(obstacle_x[o][static_cast<std::size_t>(v)]);
      return box;
    })));
    trees.push_back(built.back().get());
  }
  return trees;
}

std::vector<const Bvh*> Collider::obstacle_face_trees(const std::vector<std::vector<Vec3>>& obstacle_x, int threads) {
  std::vector<const Bvh*> trees;
  for (std::size_t o = 0; o < obstacles_.size(); ++o) {
    obstacle_trees_[o].hold(obstacles_[o].faces, obstacle_edges_[o], obstacle_x[o], threads);
    trees.push_back(&obstacle_trees_[o].faces());
  }
  return trees;
}

CollisionStats Collider::resolve(const Eigen::VectorXd& x_start, Eigen::VectorXd& x_end, const std::vector<double>& mass,
                                 const std::vector<char>& fixed, const std::vector<std::vector<Vec3>>& obstacle_start,
                                 const std::vector<std::vector<Vec3>>& obstacle_end, const CollisionParams& params) {
  CollisionStats stats;
  const SweptScene scene{cloth_faces_, cloth_edges_, obstacles_, obstacle_edges_, x_start, x_end, fixed, obstacle_start, obstacle_end,
                         1e-3 * params.thickness};
  std::vector<const Bvh*> obstacle_vertex_bvh, obstacle_face_bvh, obstacle_edge_bvh;
  for (std::size_t o = 0; o < obstacles_.size(); ++o) {
    obstacle_trees_[o].sweep(obstacles_[o].faces, obstacle_edges_[o], obstacle_start[o], obstacle_end[o], scene.eta, params.threads);
    obstacle_vertex_bvh.push_back(&obstacle_trees_[o].vertices());
    obstacle_face_bvh.push_back(&obstacle_trees_[o].faces());
    obstacle_edge_bvh.push_back(&obstacle_trees_[o].edges());
  }
  std::vector<char> cloth_node_used(static_cast<std::size_t>(num_nodes_), 0);
  for (const auto& f : cloth_faces_)
    for (int32_t n : f) cloth_node_used[static_cast<std::size_t>(n)] = 1;
  ImpactZones zones(num_nodes_);
  std::vector<char> moved(static_cast<std::size_t>(num_nodes_), 1);
  bool clear = false;
  const int64_t budget = static_cast<int64_t>(params.max_candidates_per_primitive) *
                         static_cast<int64_t>(num_nodes_ + static_cast<int32_t>(cloth_edges_.size()));
  for (int round = 0; round < params.max_iterations && !clear; ++round) {
    ++stats.iterations;
    const std::vector<Aabb> face_boxes = leaf_boxes(cloth_faces_.size(), params.threads, [&](std::size_t i) {
      const auto& f = cloth_faces_[i];
      return path_box(scene, {{-1, f[0]}, {-1, f[1]}, {-1, f[2]}});
    });
    const std::vector<Aabb> edge_boxes = leaf_boxes(cloth_edges_.size(), params.threads, [&](std::size_t i) {
      const auto& e = cloth_edges_[i];
      return path_box(scene, {{-1, e[0]}, {-1, e[1]}});
    });
    const CandidateTrees trees{cloth_faces_, cloth_edges_, cloth_node_used, cloth_face_tree_.update(face_boxes, params.threads),
                               cloth_edge_tree_.update(edge_boxes, params.threads), obstacle_vertex_bvh, obstacle_face_bvh, obstacle_edge_bvh};
    // After the first round only pairs with a node that a projection moved can hold a new impact.
    // In the first, the lists of the last proximity search made hold the cloth pairs of the
    // nodes that stay near where it was made, taken while most nodes do.
    std::optional<MovedPrimitives> moved_primitives;
    std::vector<char> far;  // in a listed first round: the nodes that go beyond the lists' reach
    if (round == 0 && kept_pairs_.x.size() == x_start.size()) far = kept_pairs_.beyond(x_start, x_end, 2 * scene.eta, cloth_node_used);
    const bool listed = !far.empty() && KeptClothPairs::worth_taking(far, cloth_node_used);
    if (listed) moved_primitives.emplace(far, trees, face_boxes, edge_boxes);
    if (round > 0) moved_primitives.emplace(moved, trees, face_boxes, edge_boxes);
    ImpactRound detection(scene, budget);
    detection.detect(trees, moved_primitives ? &*moved_primitives : nullptr, listed ? &kept_pairs_ : nullptr, params.threads);
    const int64_t met = detection.met();
    stats.candidates = std::max(stats.candidates, met);
    if (met > budget) {
      // Too far a motion to detect in this step: every cloth node not held keeps its start
      // position, a step in which the cloth stands still (the step's recovery first halves it).
      stats.over_budget = true;
      stats.fallbacks += 1;
      for (int32_t n = 0; n < num_nodes_; ++n)
        if (!fixed[static_cast<std::size_t>(n)]) x_end.segment<3>(3 * n) = x_start.segment<3>(3 * n);
      return stats;
    }
    const std::vector<ImpactConstraint> found = detection.impacts();
    stats.impacts += static_cast<int>(found.size());
    if (found.empty()) {
      clear = true;
      break;
    }
    zones.add(found);
    zones.project(x_end, mass, params.impact_separation, 1e-3 * params.thickness, moved);
  }
  if (!clear) stats.fallbacks += zones.fall_back(x_start, x_end);
  return stats;
}

}  // namespace vdc
