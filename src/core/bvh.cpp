// Axis-aligned bounding-box hierarchy (median split on the longest axis of the centres).
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
  nodes_.reserve(2 * leaf_boxes.size() + 1);
  if (leaf_boxes.empty()) {
    nodes_.push_back(Node{});
    return;
  }
  build(prims, 0, prims.size(), centres);
  rank_.resize(prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i) rank_[static_cast<std::size_t>(prims[i])] = static_cast<int32_t>(i);
  measure_looseness();
}

int32_t Bvh::build(std::vector<int32_t>& prims, std::size_t begin, std::size_t end, const std::vector<Vec3>& centres) {
  const auto index = static_cast<int32_t>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_[static_cast<std::size_t>(index)].first = static_cast<int32_t>(begin);
  nodes_[static_cast<std::size_t>(index)].last = static_cast<int32_t>(end) - 1;
  if (end - begin == 1) {
    nodes_[static_cast<std::size_t>(index)].prim = prims[begin];
    nodes_[static_cast<std::size_t>(index)].box = leaf_box_[static_cast<std::size_t>(prims[begin])];
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
  // Children come after their parent (the build numbers nodes depth first), so one backward
  // pass refits bottom-up, and measures the looseness on the way.
  double inner = 0, leaves = 0;
  for (auto i = static_cast<int64_t>(nodes_.size()) - 1; i >= 0; --i) {
    Node& n = nodes_[static_cast<std::size_t>(i)];
    if (n.left < 0) {
      n.box = leaf_box_[static_cast<std::size_t>(n.prim)];
      leaves += half_area(n.box);
    } else {
      n.box = nodes_[static_cast<std::size_t>(n.left)].box;
      n.box.grow(nodes_[static_cast<std::size_t>(n.right)].box);
      inner += half_area(n.box);
    }
  }
  looseness_ = leaves > 0 ? inner / leaves : inner;
}

void Bvh::measure_looseness() {
  double inner = 0, leaves = 0;
  for (const Node& n : nodes_) (n.left < 0 ? leaves : inner) += half_area(n.box);
  looseness_ = leaves > 0 ? inner / leaves : inner;
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
