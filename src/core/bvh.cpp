// Axis-aligned bounding-box hierarchy (median split on the longest axis of the centres, down to
// leaves of at most kLeafSize primitives).
#include "core/bvh.hpp"

#include <algorithm>

namespace vdc {

Bvh::Bvh(const std::vector<Aabb>& leaf_boxes) : leaf_box_(leaf_boxes) {
  std::vector<int32_t> prims(leaf_boxes.size());
  std::vector<Vec3> centres(leaf_boxes.size());
  for (std::size_t i = 0; i < leaf_boxes.size(); ++i) {
    prims[i] = static_cast<int32_t>(i);
    centres[i] = 0.5 * (leaf_boxes[i].lo + leaf_boxes[i].hi);
  }
  nodes_.reserve(leaf_boxes.size() / 2 + 2);
  if (leaf_boxes.empty()) {
    nodes_.push_back(Node{});
    return;
  }
  build(prims, 0, prims.size(), centres);
  order_ = std::move(prims);
  rank_.resize(order_.size());
  ranked_box_.resize(order_.size());
  for (std::size_t r = 0; r < order_.size(); ++r) {
    rank_[static_cast<std::size_t>(order_[r])] = static_cast<int32_t>(r);
    ranked_box_[r] = leaf_box_[static_cast<std::size_t>(order_[r])];
  }
  measure_looseness();
}

int32_t Bvh::build(std::vector<int32_t>& prims, std::size_t begin, std::size_t end, const std::vector<Vec3>& centres) {
  const auto index = static_cast<int32_t>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_[static_cast<std::size_t>(index)].first = static_cast<int32_t>(begin);
  nodes_[static_cast<std::size_t>(index)].last = static_cast<int32_t>(end) - 1;
  if (end - begin <= static_cast<std::size_t>(kLeafSize)) {
    Aabb box;
    for (std::size_t i = begin; i < end; ++i) box.grow(leaf_box_[static_cast<std::size_t>(prims[i])]);
    nodes_[static_cast<std::size_t>(index)].box = box;
    ++leaves_;
    return index;
  }
  Aabb c;
  for (std::size_t i = begin; i < end; ++i) c.grow(centres[static_cast<std::size_t>(prims[i])]);
  int axis = 0;
  (c.hi - c.lo).maxCoeff(&axis);
  const std::size_t mid = begin + (end - begin) / 2;
  std::nth_element(prims.begin() + static_cast<std::ptrdiff_t>(begin), prims.begin() + static_cast<std::ptrdiff_t>(mid),
                   prims.begin() + static_cast<std::ptrdiff_t>(end), [&](int32_t a, int32_t b) {
                     return centres[static_cast<std::size_t>(a)][axis] < centres[static_cast<std::size_t>(b)][axis];
                   });
  const int32_t left = build(prims, begin, mid, centres);
  const int32_t right = build(prims, mid, end, centres);
  Node& n = nodes_[static_cast<std::size_t>(index)];
  n.left = left;
  n.right = right;
  n.box = nodes_[static_cast<std::size_t>(left)].box;
  n.box.grow(nodes_[static_cast<std::size_t>(right)].box);
  return index;
}

namespace {
// Half the surface area of a box (the surface area heuristic's measure).
double half_area(const Aabb& b) {
  const Vec3 d = (b.hi - b.lo).cwiseMax(0.0);
  return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
}
}  // namespace

void Bvh::refit(std::vector<Aabb> leaf_boxes) {
  leaf_box_ = std::move(leaf_boxes);
  if (leaf_box_.empty()) return;
  double primitives = 0;
  for (std::size_t r = 0; r < order_.size(); ++r) {
    ranked_box_[r] = leaf_box_[static_cast<std::size_t>(order_[r])];
    primitives += half_area(ranked_box_[r]);
  }
  // Children come after their parent (the build numbers nodes depth first), so one backward
  // pass refits bottom-up, and measures the looseness on the way.
  double nodes = 0;
  for (auto i = static_cast<int64_t>(nodes_.size()) - 1; i >= 0; --i) {
    Node& n = nodes_[static_cast<std::size_t>(i)];
    if (n.left < 0) {
      n.box = Aabb();
      for (int32_t r = n.first; r <= n.last; ++r) n.box.grow(ranked_box_[static_cast<std::size_t>(r)]);
    } else {
      n.box = nodes_[static_cast<std::size_t>(n.left)].box;
      n.box.grow(nodes_[static_cast<std::size_t>(n.right)].box);
    }
    nodes += half_area(n.box);
  }
  looseness_ = primitives > 0 ? nodes / primitives : nodes;
}

void Bvh::measure_looseness() {
  double nodes = 0, primitives = 0;
  for (const Node& n : nodes_) nodes += half_area(n.box);
  for (const Aabb& b : ranked_box_) primitives += half_area(b);
  looseness_ = primitives > 0 ? nodes / primitives : nodes;
}

std::vector<int32_t> Bvh::subtrees(int count) const {
  std::vector<int32_t> units;
  if (leaf_box_.empty()) return units;
  units.push_back(0);
  // Split every splittable unit, level by level, until there are enough (leaf order kept).
  while (static_cast<int>(units.size()) < count) {
    std::vector<int32_t> next;
    for (int32_t u : units) {
      const Node& n = nodes_[static_cast<std::size_t>(u)];
      if (n.left < 0) next.push_back(u);
      else next.insert(next.end(), {n.left, n.right});
    }
    if (next.size() == units.size()) break;
    units = std::move(next);
  }
  return units;
}

}  // namespace vdc
