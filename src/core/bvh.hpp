// Bounding-volume hierarchy of axis-aligned boxes over triangles: built by median splits, refit
// in place when positions move (boxes may be swept: the union over a step), rebuilt when the
// topology changes. Queries list overlapping leaf pairs within one tree or between two.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
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
  // One box per primitive (a triangle's swept, padded box, say). Builds the tree.
  explicit Bvh(const std::vector<Aabb>& leaf_boxes);
  // New boxes for the same primitives, in the same order: refits without changing the tree.
  void refit(const std::vector<Aabb>& leaf_boxes);

  // Calls f(i, j) with i < j for every pair of primitives of this tree whose boxes overlap.
  void self_pairs(const std::function<void(int32_t, int32_t)>& f) const;
  // Calls f(i, j) for every primitive i of this tree and j of `other` whose boxes overlap.
  void pairs_with(const Bvh& other, const std::function<void(int32_t, int32_t)>& f) const;
  // Calls f(i) for every primitive whose box overlaps `box`.
  template <class F>
  void query(const Aabb& box, F&& f) const {
    traverse([&](const Node& n) { return n.box.overlaps(box); }, f, [](const Aabb&, const Aabb&) { return false; });
  }
  // As query, but only primitives after `prim` in the tree's leaf order: when every primitive
  // of a tree queries the tree, each overlapping pair is met once, from its earlier member, and
  // the subtrees wholly before `prim` are not entered at all.
  template <class F>
  void query_later(const Aabb& box, int32_t prim, F&& f) const {
    const int32_t rank = rank_[static_cast<std::size_t>(prim)];
    traverse([&](const Node& n) { return n.last > rank && n.box.overlaps(box); }, f, [](const Aabb&, const Aabb&) { return false; });
  }

  // Branch and bound for the nearest primitive to p: `dist(i)` returns primitive i's distance
  // and is called only for primitives whose box is nearer than the best so far, which starts
  // at `best` (a search radius) and ends as the smallest distance found.
  template <class F>
  void nearest(const Vec3& p, double& best, F&& dist) const {
    traverse([&](const Node& n) { return n.box.distance(p) < best; }, [&](int32_t prim) { best = std::min(best, dist(prim)); },
             [&](const Aabb& l, const Aabb& r) { return l.distance(p) <= r.distance(p); });
  }

  int32_t size() const { return static_cast<int32_t>(leaf_box_.size()); }
  const Aabb& root_box() const { return nodes_.front().box; }
  // How loose the tree is: the surface area of its inner nodes' boxes over that of its leaves'
  // (the cost a query pays to reach a leaf, after the surface area heuristic). Refits of moving
  // primitives raise it; a fresh build sets the baseline.
  double looseness() const { return looseness_; }

 private:
  // Depth first with a fixed stack (the median split keeps the depth at most ceil(log2 n) + 1,
  // far below its 128 entries): descends into nodes that `enter` accepts, calls `leaf` on
  // primitives, and visits the left child first when `left_first(left box, right box)`.
  template <class Enter, class Leaf, class LeftFirst>
  void traverse(Enter&& enter, Leaf&& leaf, LeftFirst&& left_first) const {
    if (leaf_box_.empty()) return;
    std::array<int32_t, 128> stack;
    int top = 0;
    stack[static_cast<std::size_t>(top++)] = 0;
    while (top > 0) {
      const Node& n = nodes_[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
      if (!enter(n)) continue;
      if (n.left < 0) {
        leaf(n.prim);
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
    int32_t prim = -1;              // the primitive of a leaf
    int32_t last = -1;              // the last leaf under the node, in leaf order
  };
  int32_t build(std::vector<int32_t>& prims, std::size_t begin, std::size_t end, const std::vector<Vec3>& centres);
  void refit_node(int32_t n);
  void measure_looseness();
  void self_node(int32_t a, const std::function<void(int32_t, int32_t)>& f) const;
  void cross(int32_t a, const Bvh& other, int32_t b, const std::function<void(int32_t, int32_t)>& f, bool self) const;

  std::vector<Node> nodes_;
  std::vector<Aabb> leaf_box_;
  std::vector<int32_t> rank_;  // by primitive: its place in leaf order (depth first, left first)
  double looseness_ = 0;
};

// A hierarchy kept over a sequence of box updates for the same primitives: refit on each update,
// rebuilt from scratch when refits have loosened it past `max_loosening` times its looseness when
// built (a body whose limbs swing apart, say), and whenever the number of primitives changes.
class RefitBvh {
 public:
  explicit RefitBvh(double max_loosening = 1.2) : max_loosening_(max_loosening) {}
  const Bvh& update(const std::vector<Aabb>& leaf_boxes) {
    if (tree_ && tree_->size() == static_cast<int32_t>(leaf_boxes.size())) {
      tree_->refit(leaf_boxes);
      if (tree_->looseness() <= max_loosening_ * built_looseness_) return *tree_;
    }
    tree_ = std::make_unique<Bvh>(leaf_boxes);
    built_looseness_ = tree_->looseness();
    return *tree_;
  }

 private:
  double max_loosening_;
  double built_looseness_ = 0;
  std::unique_ptr<Bvh> tree_;
};

}  // namespace vdc
