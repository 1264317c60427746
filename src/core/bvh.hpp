// Bounding-volume hierarchy of axis-aligned boxes over triangles: built by median splits into
// leaves of a few primitives, refit in place when positions move (boxes may be swept: the union
// over a step), rebuilt when the topology changes. Queries list the primitives whose own boxes
// overlap, within one tree or between two: which they are never depends on the tree's shape.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "core/math.hpp"

namespace vdc {

struct Aabb {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void grow(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void grow(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  void pad(double d) {
    lo.array() -= d;
    hi.array() += d;
  }
  bool overlaps(const Aabb& b) const { return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all(); }
  // Distance from p to the box (0 inside).
  double distance(const Vec3& p) const { return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm(); }
};

// One box per primitive, box_of(i) for i in [0, n), computed on `threads` threads.
template <class BoxOf>
std::vector<Aabb> leaf_boxes(std::size_t n, int threads, BoxOf&& box_of) {
  std::vector<Aabb> boxes(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int64_t i = 0; i < static_cast<int64_t>(n); ++i) boxes[static_cast<std::size_t>(i)] = box_of(static_cast<std::size_t>(i));
  return boxes;
}

class Bvh {
 public:
  // One box per primitive (a triangle's swept, padded box, say). Builds the tree; with two
  // threads or more a large tree's two halves are built side by side (the same tree).
  explicit Bvh(const std::vector<Aabb>& leaf_boxes, int threads = 1);
  // New boxes for the same primitives, in the same order: refits without changing the tree
  // (a large tree's two halves side by side with two threads or more, the same boxes).
  void refit(std::vector<Aabb> leaf_boxes, int threads = 1);
  const std::vector<Aabb>& leaf_boxes() const { return leaf_box_; }

  // Calls f(i, j) with i < j for every pair of primitives of this tree whose boxes overlap.
  template <class F>
  void self_pairs(F&& f) const {
    later_pairs_under(0, 0.0, [&](int32_t i, int32_t j) { f(std::min(i, j), std::max(i, j)); });
  }
  // Calls f(i, j) for every primitive i of this tree and j of `other` whose boxes overlap.
  template <class F>
  void pairs_with(const Bvh& other, F&& f) const {
    pairs_under(0, other, 0.0, f);
  }

  // Units of work for a parallel traversal: disjoint subtrees (node indices) that together hold
  // every primitive, at least `count` of them when the tree has that many leaves. The
  // partition depends only on the tree and `count`, never on the thread count.
  std::vector<int32_t> subtrees(int count) const;
  // Calls f(i, j) for every primitive i under node `subtree` of this tree and j of `other` whose
  // boxes overlap once this tree's boxes are grown by `pad`: both hierarchies descended at once,
  // which tests far fewer boxes than one query per primitive.
  template <class F>
  void pairs_under(int32_t subtree, const Bvh& other, double pad, F&& f) const {
    descend(subtree, other, pad, false, f);
  }
  // As pairs_under against this tree itself, each overlapping pair once: j after i in leaf
  // order (subtrees wholly before i are not entered).
  template <class F>
  void later_pairs_under(int32_t subtree, double pad, F&& f) const {
    descend(subtree, *this, pad, true, f);
  }
  // Calls f(i) for every primitive whose box overlaps `box`.
  template <class F>
  void query(const Aabb& box, F&& f) const {
    query_if([&](const Aabb& b) { return b.overlaps(box); }, f);
  }
  // Calls f(i) for every primitive whose box `accept(box)` takes, entering only the nodes whose
  // boxes it takes (so a primitive is skipped whenever a box holding it is not taken).
  template <class Accept, class F>
  void query_if(Accept&& accept, F&& f) const {
    traverse([&](const Aabb& b, int32_t) { return accept(b); }, f, [](const Aabb&, const Aabb&) { return false; });
  }
  // As query, but only primitives after `prim` in the tree's leaf order: when every primitive
  // of a tree queries the tree, each overlapping pair is met once, from its earlier member, and
  // the subtrees wholly before `prim` are not entered at all.
  template <class F>
  void query_later(const Aabb& box, int32_t prim, F&& f) const {
    const int32_t rank = rank_[static_cast<std::size_t>(prim)];
    traverse([&](const Aabb& b, int32_t last) { return last > rank && b.overlaps(box); }, f, [](const Aabb&, const Aabb&) { return false; });
  }

  // Branch and bound for the nearest primitive to p: `dist(i)` returns primitive i's distance
  // and is called only for primitives whose box is no farther than the best so far, which
  // starts at `best` (a search radius) and ends as the smallest distance found. Every primitive
  // as near as the nearest is met, whatever the tree's shape, so a caller can break ties.
  template <class F>
  void nearest(const Vec3& p, double& best, F&& dist) const {
    traverse([&](const Aabb& b, int32_t) { return b.distance(p) <= best; }, [&](int32_t prim) { best = std::min(best, dist(prim)); },
             [&](const Aabb& l, const Aabb& r) { return l.distance(p) <= r.distance(p); });
  }

  int32_t size() const { return static_cast<int32_t>(leaf_box_.size()); }
  int32_t leaves() const { return leaves_; }
  // Primitives a leaf holds at most: a leaf pair's primitives are tested pair by pair in one
  // loop, cheaper than the two levels of node pairs above them that one-primitive leaves cost.
  static constexpr int32_t kLeafSize = 4;
  const Aabb& root_box() const { return nodes_.front().box; }
  // How loose the tree is: the surface area of its nodes' boxes over that of its primitives'
  // (the cost a query pays to reach a primitive, after the surface area heuristic). Refits of moving
  // primitives raise it; a fresh build sets the baseline.
  double looseness() const { return looseness_; }

 private:
  // Depth first with a fixed stack (the median split keeps the depth at most ceil(log2 n) + 1,
  // far below its 128 entries): descends into nodes whose box and last leaf-order rank
  // `enter(box, last)` accepts, tests each primitive of a leaf the same way with its own box and
  // rank, calls `leaf` on those accepted, and visits the left child first when
  // `left_first(left box, right box)`.
  template <class Enter, class Leaf, class LeftFirst>
  void traverse(Enter&& enter, Leaf&& leaf, LeftFirst&& left_first) const {
    if (leaf_box_.empty()) return;
    std::array<int32_t, 128> stack;
    int top = 0;
    stack[static_cast<std::size_t>(top++)] = 0;
    while (top > 0) {
      const Node& n = nodes_[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
      if (!enter(n.box, n.last)) continue;
      if (n.left < 0) {
        for (int32_t r = n.first; r <= n.last; ++r)
          if (enter(ranked_box_[static_cast<std::size_t>(r)], r)) leaf(order_[static_cast<std::size_t>(r)]);
        continue;
      }
      const bool lf = left_first(nodes_[static_cast<std::size_t>(n.left)].box, nodes_[static_cast<std::size_t>(n.right)].box);
      stack[static_cast<std::size_t>(top++)] = lf ? n.right : n.left;
      stack[static_cast<std::size_t>(top++)] = lf ? n.left : n.right;
    }
  }

  struct Node {
    Aabb box;
    int32_t left = -1, right = -1;  // children; -1 for a leaf
    int32_t first = -1, last = -1;  // the first and last primitives under the node, in leaf order
  };
  // Trees of fewer primitives are built and refit on one thread: below this the work is a few
  // tens of microseconds, what starting a second thread costs.
  static constexpr std::size_t kParallelPrimitives = 2048;
  // Splits prims[begin, end) at its median along the longest axis of the centres: the middle.
  static std::size_t split(std::vector<int32_t>& prims, std::size_t begin, std::size_t end, const std::vector<Vec3>& centres);
  // The subtree over prims[begin, end), its nodes appended to `out` depth first (children
  // numbered from out's size); returns its root's index in `out`.
  int32_t build(std::vector<Node>& out, int32_t& leaves, std::vector<int32_t>& prims, std::size_t begin, std::size_t end,
                const std::vector<Vec3>& centres) const;
  // Refits nodes [first, last) bottom-up: a whole subtree, whose children follow their parent.
  void refit_nodes(int32_t first, int32_t last);
  void measure_looseness();
  // Simultaneous descent from node a of this tree and the root of `other`: pairs whose boxes
  // overlap (this tree's grown by pad); with `later`, only pairs whose `other` primitive comes
  // after this tree's in leaf order (other is then this tree). Splits the larger box first; a
  // pair of leaves tests its primitives' own boxes, so the pairs found are the same whatever the
  // trees' shapes.
  template <class F>
  void descend(int32_t a, const Bvh& other, double pad, bool later, F&& f) const {
    if (leaf_box_.empty() || other.leaf_box_.empty()) return;
    std::array<std::pair<int32_t, int32_t>, 256> stack;
    int top = 0;
    stack[static_cast<std::size_t>(top++)] = {a, 0};
    while (top > 0) {
      const auto [ia, ib] = stack[static_cast<std::size_t>(--top)];
      const Node& na = nodes_[static_cast<std::size_t>(ia)];
      const Node& nb = other.nodes_[static_cast<std::size_t>(ib)];
      if (later && nb.last <= na.first) continue;
      if (!padded_overlap(na.box, nb.box, pad)) continue;
      if (na.left < 0 && nb.left < 0) {
        for (int32_t ra = na.first; ra <= na.last; ++ra) {
          const Aabb& box = ranked_box_[static_cast<std::size_t>(ra)];
          for (int32_t rb = later ? std::max(nb.first, ra + 1) : nb.first; rb <= nb.last; ++rb)
            if (padded_overlap(box, other.ranked_box_[static_cast<std::size_t>(rb)], pad))
              f(order_[static_cast<std::size_t>(ra)], other.order_[static_cast<std::size_t>(rb)]);
        }
        continue;
      }
      const bool split_a = nb.left < 0 || (na.left >= 0 && (na.box.hi - na.box.lo).squaredNorm() >= (nb.box.hi - nb.box.lo).squaredNorm());
      if (split_a) {
        stack[static_cast<std::size_t>(top++)] = {na.right, ib};
        stack[static_cast<std::size_t>(top++)] = {na.left, ib};
      } else {
        stack[static_cast<std::size_t>(top++)] = {ia, nb.right};
        stack[static_cast<std::size_t>(top++)] = {ia, nb.left};
      }
    }
  }
  // Whether box a grown by pad overlaps box b.
  [[gnu::always_inline]] static bool padded_overlap(const Aabb& a, const Aabb& b, double pad) {
    return a.lo.x() - pad <= b.hi.x() && a.lo.y() - pad <= b.hi.y() && a.lo.z() - pad <= b.hi.z() && b.lo.x() <= a.hi.x() + pad &&
           b.lo.y() <= a.hi.y() + pad && b.lo.z() <= a.hi.z() + pad;
  }

  std::vector<Node> nodes_;
  std::vector<Aabb> leaf_box_;    // by primitive
  std::vector<Aabb> ranked_box_;  // the same boxes in leaf order, where leaf pairs read them
  std::vector<int32_t> order_;    // by leaf order: the primitive (depth first, left first)
  std::vector<int32_t> rank_;     // by primitive: its place in leaf order
  int32_t leaves_ = 0;
  double looseness_ = 0;
};

// Every overlapping pair between `tree` and each of `others`, cross_pair(o, i, j), and with
// `Within` also every pair within `tree` once, self_pair(i, j), `tree`'s boxes grown by `pad`:
// descents from `units` fixed subtrees of `tree` on `threads` threads. All pairs of a primitive i
// of `tree` come from the one subtree that holds it, in an order that does not depend on the
// thread count, so per-primitive outputs need no lock.
enum class Within { Yes, No };
template <class SelfPair, class CrossPair>
void pairs_by_subtree(const Bvh& tree, Within within, const std::vector<const Bvh*>& others, double pad, int units, int threads,
                      SelfPair&& self_pair, CrossPair&& cross_pair) {
  const std::vector<int32_t> roots = tree.subtrees(units);
  const auto n = static_cast<int64_t>(roots.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int64_t u = 0; u < n; ++u) {
    const int32_t root = roots[static_cast<std::size_t>(u)];
    if (within == Within::Yes) tree.later_pairs_under(root, pad, self_pair);
    for (std::size_t o = 0; o < others.size(); ++o)
      tree.pairs_under(root, *others[o], pad, [&](int32_t i, int32_t j) { cross_pair(o, i, j); });
  }
}

// A hierarchy kept over a sequence of box updates for the same primitives: refit on each update,
// rebuilt from scratch when refits have loosened it past `max_loosening` times its looseness when
// built (a body whose limbs swing apart, say), and whenever the number of primitives changes.
class RefitBvh {
 public:
  explicit RefitBvh(double max_loosening = 1.2) : max_loosening_(max_loosening) {}
  const Bvh& update(std::vector<Aabb> leaf_boxes, int threads = 1) {
    const Bvh& tree = update_with(std::move(leaf_boxes), false, threads);
    if (rebuilt_ || tree.looseness() <= max_loosening_ * built_looseness_) return tree;
    return rebuild(tree.leaf_boxes(), threads);
  }
  // As update, but rebuilt only when `rebuild_now` (or the number of primitives changed), never
  // by its own looseness: for boxes of next to no area (a vertex's path over a step, or its
  // point), whose looseness measures their speed rather than the tree. A vertex hierarchy is
  // rebuilt when the face hierarchy over the same vertices is.
  const Bvh& update_with(std::vector<Aabb> leaf_boxes, bool rebuild_now, int threads = 1) {
    if (!rebuild_now && tree_ && tree_->size() == static_cast<int32_t>(leaf_boxes.size())) {
      tree_->refit(std::move(leaf_boxes), threads);
      rebuilt_ = false;
      return *tree_;
    }
    return rebuild(std::move(leaf_boxes), threads);
  }
  // Whether the last update built the tree afresh.
  bool rebuilt() const { return rebuilt_; }

 private:
  const Bvh& rebuild(std::vector<Aabb> leaf_boxes, int threads) {
    tree_ = std::make_unique<Bvh>(leaf_boxes, threads);
    built_looseness_ = tree_->looseness();
    rebuilt_ = true;
    return *tree_;
  }

  double max_loosening_;
  double built_looseness_ = 0;
  bool rebuilt_ = false;
  std::unique_ptr<Bvh> tree_;
};

}  // namespace vdc
