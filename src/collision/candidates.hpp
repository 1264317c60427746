// The candidate stage of collision handling, the broad phase of Bridson, Fedkiw and Anderson
// 2002 (sections 7.2 and 7.4): the cloth and obstacle primitives whose boxes meet, handed to
// the narrow phase of proximity detection (proximity.cpp) and of impact detection (collider.cpp)
// alike. Pairs that share a cloth node are never candidates. A query primitive's candidates come
// one after another, in the hierarchies' order, from its own query or from the one fixed subtree
// of a simultaneous descent that holds it; queries and subtrees are taken in parallel (a cloth
// edge's cloth and obstacle pairs, where they come from two passes, one pass after the other), so
// a caller writes only to the query primitive's own results, and what it finds does not depend
// on the thread count. Nor on the hierarchies' shape: results met in their order are put in a key
// order (in_key_order) before they are used.
#pragma once
#include <array>
#include <cstdint>
#include <algorithm>
#include <initializer_list>
#include <utility>
#include <vector>

#include "core/bvh.hpp"
#include "core/math.hpp"

namespace vdc {

// The values of keyed results in key order (keys unique): a kept, refit hierarchy and one built
// afresh (after a resumption) meet candidates in different orders, and which edge of a cloth
// pair meets the other; results taken this way do not depend on it.
template <class Key, class T>
std::vector<T> in_key_order(std::vector<std::pair<Key, T>> keyed) {
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<T> values;
  values.reserve(keyed.size());
  for (auto& [key, value] : keyed) values.push_back(std::move(value));
  return values;
}

// Subtrees a cloth hierarchy is split into for a parallel descent with another hierarchy: fixed,
// so that the pairs found, and their order, do not depend on the thread count.
inline constexpr int kCandidateTraversalUnits = 64;

// What one detection searches: the cloth's faces and edges (global node ids), the nodes its
// faces use, hierarchies over the boxes of this detection, and each obstacle's (over its
// vertices, faces and edges).
struct CandidateTrees {
  const std::vector<std::array<int32_t, 3>>& cloth_faces;
  const std::vector<std::array<int32_t, 2>>& cloth_edges;
  const std::vector<char>& node_used;  // per cloth node: a face uses it
  const Bvh& cloth_face_tree;
  const Bvh& cloth_edge_tree;
  const std::vector<const Bvh*>& obstacle_vertex_trees;
  const std::vector<const Bvh*>& obstacle_face_trees;
  const std::vector<const Bvh*>& obstacle_edge_trees;
};

// The cloth-cloth candidates of a proximity search (proximity.cpp), kept for the searches and
// first impact rounds of the steps after it: found with boxes of the positions `x`, one of each
// pair grown by `pad` (twice the band), they hold every pair whose boxes at other positions, one
// grown by d, meet when neither primitive's nodes are farther than (pad - d) / 2 from `x` in any
// coordinate (a box lies within its box at `x` grown by that much). A proximity search (d the
// band) or an impact round (swept boxes, d = 2 eta, each node's farther end counted) then needs
// the hierarchies only for primitives with a node farther than that.
struct KeptClothPairs {
  Eigen::VectorXd x;  // the positions they were found at
  double pad = 0;
  std::vector<std::vector<int32_t>> node_faces;  // per cloth node: the cloth faces not around it it met
  std::vector<std::vector<int32_t>> edge_edges;  // per cloth edge: the edges it met (each pair under one of its two)

  // Empty lists for `num_nodes` nodes and `num_edges` edges, their storage kept.
  void clear(std::size_t num_nodes, std::size_t num_edges) {
    node_faces.resize(num_nodes);
    edge_edges.resize(num_edges);
    for (auto& l : node_faces) l.clear();
    for (auto& l : edge_edges) l.clear();
  }
  // How far from `x` a node may be for its pairs, within d of each other, to be in the lists.
  double reach(double d) const { return 0.5 * (pad - d) - 1e-9; }
  // Per node: whether it is farther than reach(d) from `x` at `a` or at `b` (a step's start and
  // end; both the same for a search at one time), once the mean displacement of the nodes in
  // `used` is taken out: moving every box alike changes no pair that meets.
  std::vector<char> beyond(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double d, const std::vector<char>& used) const;
  // Whether the lists are worth taking with `far` (beyond's answer) gone beyond their reach: at
  // most one node in sixteen of those in `used`. Past that, the far nodes' own queries and the
  // hierarchies over their primitives cost more than a search that meets everything.
  static bool worth_taking(const std::vector<char>& far, const std::vector<char>& used);
};

// The cloth primitives with a node that the last round of impact projection moved (Bridson et
// al. 2002, section 7.4, iterated): only a pair with one of them can hold a new impact. A query
// primitive with a moved node meets everything; the others meet only the moved cloth primitives
// and no obstacle (which did not move). With `KeptClothPairs`, "moved" means gone beyond the
// lists' reach: the others meet the moved cloth primitives, their listed ones that did not move,
// and the obstacles.
class MovedPrimitives {
 public:
  // `face_boxes` and `edge_boxes`: the boxes of the trees' cloth primitives in this round.
  MovedPrimitives(const std::vector<char>& moved, const CandidateTrees& trees, const std::vector<Aabb>& face_boxes,
                  const std::vector<Aabb>& edge_boxes);
  bool any(std::initializer_list<int32_t> nodes) const {
    for (const int32_t n : nodes)
      if (moved_[static_cast<std::size_t>(n)]) return true;
    return false;
  }
  // Calls f(face) for the moved cloth faces (edges) whose boxes meet `box`.
  template <class F>
  void faces_near(const Aabb& box, F&& f) const {
    face_tree_.query(box, [&](int32_t k) { f(faces_[static_cast<std::size_t>(k)]); });
  }
  template <class F>
  void edges_near(const Aabb& box, F&& f) const {
    edge_tree_.query(box, [&](int32_t k) { f(edges_[static_cast<std::size_t>(k)]); });
  }
  // The hierarchy over the moved cloth faces' boxes, and the cloth face of its primitive k.
  const Bvh& face_tree() const { return face_tree_; }
  int32_t face(int32_t k) const { return faces_[static_cast<std::size_t>(k)]; }

 private:
  static std::vector<Aabb> boxes_of(const std::vector<int32_t>& items, const std::vector<Aabb>& boxes);
  const std::vector<char>& moved_;
  std::vector<int32_t> faces_, edges_;
  Bvh face_tree_, edge_tree_;
};

// Vertex-face candidates: for every cloth node a face uses (in parallel), cloth_face(v, f) for
// each cloth face not around it whose box meets vertex_box(v), then obstacle_face(v, o, f) for
// each face of each obstacle o that meets it. With `moved`, a node that did not move meets only
// the moved cloth faces; with `listed` too (a first round), also its listed faces that did not
// move and whose boxes meet its box, and the obstacles.
template <class VertexBox, class ClothFace, class ObstacleFace>
void vertex_face_candidates(const CandidateTrees& t, const MovedPrimitives* moved, const KeptClothPairs* listed, int threads,
                            VertexBox&& vertex_box, ClothFace&& cloth_face, ObstacleFace&& obstacle_face) {
  const auto num_nodes = static_cast<int32_t>(t.node_used.size());
#pragma omp parallel for schedule(dynamic, 128) num_threads(threads)
  for (int32_t v = 0; v < num_nodes; ++v) {
    if (!t.node_used[static_cast<std::size_t>(v)]) continue;
    const Aabb box = vertex_box(v);
    auto face = [&](int32_t f) {
      const auto& tri = t.cloth_faces[static_cast<std::size_t>(f)];
      if (tri[0] != v && tri[1] != v && tri[2] != v) cloth_face(v, f);
    };
    const bool all = moved == nullptr || moved->any({v});
    if (all) t.cloth_face_tree.query(box, face);
    else moved->faces_near(box, face);
    if (!all && listed != nullptr)
      for (const int32_t f : listed->node_faces[static_cast<std::size_t>(v)]) {
        const auto& tri = t.cloth_faces[static_cast<std::size_t>(f)];
        if (!moved->any({tri[0], tri[1], tri[2]}) && t.cloth_face_tree.leaf_boxes()[static_cast<std::size_t>(f)].overlaps(box)) cloth_face(v, f);
      }
    if (!all && listed == nullptr) continue;
    for (std::size_t o = 0; o < t.obstacle_face_trees.size(); ++o)
      t.obstacle_face_trees[o]->query(box, [&](int32_t f) { obstacle_face(v, o, f); });
  }
}

// Obstacle vertex-cloth face candidates: obstacle by obstacle, cloth_face(o, v, f) for each
// vertex v and cloth face f whose boxes meet, the vertex's box grown by `pad`; with `moved`, only
// the moved cloth faces. The obstacle's vertex hierarchy descends together with the cloth's from
// fixed subtrees in parallel (most of a body's vertices are far from its garment, and whole limbs
// are passed over at once), each vertex's candidates met by the one subtree that holds it.
template <class ClothFace>
void obstacle_vertex_candidates(const CandidateTrees& t, const MovedPrimitives* moved, double pad, int threads, ClothFace&& cloth_face) {
  const std::vector<const Bvh*> faces{moved != nullptr ? &moved->face_tree() : &t.cloth_face_tree};
  for (std::size_t o = 0; o < t.obstacle_vertex_trees.size(); ++o)
    pairs_by_subtree(*t.obstacle_vertex_trees[o], Within::No, faces, pad, kCandidateTraversalUnits, threads, [](int32_t, int32_t) {},
                     [&](std::size_t, int32_t v, int32_t k) { cloth_face(o, v, moved != nullptr ? moved->face(k) : k); });
}

// Edge-edge candidates: cloth_pair(ea, eb) once for each pair of cloth edges without a shared
// node whose boxes meet, listed under ea, and obstacle_pair(o, ea, eb) for each cloth edge ea and
// edge eb of obstacle o whose boxes meet, a cloth edge's box its box in the cloth edge hierarchy
// grown by `pad`. The cloth edge hierarchy descends together with each obstacle's from fixed
// subtrees in parallel, a cloth edge's obstacle pairs met by the one subtree that holds it; without
// `moved`, with itself too, each cloth pair met from its earlier edge in leaf order and listed by
// the one subtree that holds that edge. With `moved`, every cloth edge queries the cloth
// hierarchy instead, each pair from its lower-numbered edge, and only edges with a moved node meet
// the obstacles, one query each; with `listed` too (a first round), an edge that did not move
// meets its listed edges that did not move (each such pair under the edge it is listed under),
// and every edge meets the obstacles by the descent.
template <class ClothPair, class ObstaclePair>
void edge_edge_candidates(const CandidateTrees& t, const MovedPrimitives* moved, const KeptClothPairs* listed, double pad, int threads,
                          ClothPair&& cloth_pair, ObstaclePair&& obstacle_pair) {
  auto cloth = [&](int32_t ea, int32_t eb) {
    const auto& a = t.cloth_edges[static_cast<std::size_t>(ea)];
    const auto& b = t.cloth_edges[static_cast<std::size_t>(eb)];
    if (a[0] != b[0] && a[0] != b[1] && a[1] != b[0] && a[1] != b[1]) cloth_pair(ea, eb);
  };
  if (moved == nullptr || listed != nullptr)
    pairs_by_subtree(t.cloth_edge_tree, moved == nullptr ? Within::Yes : Within::No, t.obstacle_edge_trees, pad, kCandidateTraversalUnits,
                     threads, cloth, obstacle_pair);
  if (moved == nullptr) return;
  const auto num_edges = static_cast<int32_t>(t.cloth_edges.size());
#pragma omp parallel for schedule(dynamic, 128) num_threads(threads)
  for (int32_t ea = 0; ea < num_edges; ++ea) {
    const auto& a = t.cloth_edges[static_cast<std::size_t>(ea)];
    Aabb box = t.cloth_edge_tree.leaf_boxes()[static_cast<std::size_t>(ea)];
    box.pad(pad);
    auto later = [&](int32_t eb) {
      if (eb > ea) cloth(ea, eb);
    };
    const bool all = moved->any({a[0], a[1]});
    if (all) t.cloth_edge_tree.query(box, later);
    else moved->edges_near(box, later);
    if (!all && listed != nullptr)
      for (const int32_t eb : listed->edge_edges[static_cast<std::size_t>(ea)]) {
        const auto& b = t.cloth_edges[static_cast<std::size_t>(eb)];
        if (!moved->any({b[0], b[1]}) && t.cloth_edge_tree.leaf_boxes()[static_cast<std::size_t>(eb)].overlaps(box)) cloth_pair(ea, eb);
      }
    if (all && listed == nullptr)
      for (std::size_t o = 0; o < t.obstacle_edge_trees.size(); ++o)
        t.obstacle_edge_trees[o]->query(box, [&](int32_t eo) { obstacle_pair(o, ea, eo); });
  }
}

}  // namespace vdc
