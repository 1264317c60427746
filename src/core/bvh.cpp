// Axis-aligned bounding-box hierarchy (median split on the longest axis of the centres, down to
// leaves of at most kLeafSize primitives).
#include "core/bvh.hpp"

#include <algorithm>

namespace vdc {

Bvh::Bvh(const std::vector<Aabb>& leaf_boxes, int threads) : leaf_box_(leaf_boxes) {
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
  if (threads < 2 || prims.size() < kParallelPrimitives) {
    build(nodes_, leaves_, prims, 0, prims.size(), centres);
  } else {
    // The root split here, then its halves side by side: the left half numbered after the root
    // as the one-thread build numbers it, the right half built apart and numbered after it.
    nodes_.push_back(Node{{}, -1, -1, 0, static_cast<int32_t>(prims.size()) - 1});
    const std::size_t mid = split(prims, 0, prims.size(), centres);
    std::vector<Node> right;
    int32_t right_leaves = 0;
#pragma omp parallel sections num_threads(2)
    {
#pragma omp section
      build(nodes_, leaves_, prims, 0, mid, centres);
#pragma omp section
      build(right, right_leaves, prims, mid, prims.size(), centres);
    }
    const auto offset = static_cast<int32_t>(nodes_.size());
    for (Node n : right) {
      if (n.left >= 0) {
        n.left += offset;
        n.right += offset;
      }
      nodes_.push_back(n);
    }
    leaves_ += right_leaves;
    Node& root = nodes_.front();
    root.left = 1;
    root.right = offset;
    root.box = nodes_[1].box;
    root.box.grow(nodes_[static_cast<std::size_t>(offset)].box);
  }
  order_ = std::move(prims);
  rank_.resize(order_.size());
  ranked_box_.resize(order_.size());
  for (std::size_t r = 0; r < order_.size(); ++r) {
    rank_[static_cast<std::size_t>(order_[r])] = static_cast<int32_t>(r);
    ranked_box_[r] = leaf_box_[static_cast<std::size_t>(order_[r])];
  }
  measure_looseness();
}

std::size_t Bvh::split(std::vector<int32_t>& prims, std::size_t begin, std::size_t end, const std::vector<Vec3>& centres) {
  Aabb c;
  for (std::size_t i = begin; i < end; ++i) c.grow(centres[static_cast<std::size_t>(prims[i])]);
  int axis = 0;
  (c.hi - c.lo).maxCoeff(&axis);
  const std::size_t mid = begin + (end - begin) / 2;
  std::nth_element(prims.begin() + static_cast<std::ptrdiff_t>(begin), prims.begin() + static_cast<std::ptrdiff_t>(mid),
                   prims.begin() + static_cast<std::ptrdiff_t>(end), [&](int32_t a, int32_t b) {
                     return centres[static_cast<std::size_t>(a)][axis] < centres[static_cast<std::size_t>(b)][axis];
                   });
  return mid;
}

int32_t Bvh::build(std::vector<Node>& out, int32_t& leaves, std::vector<int32_t>& prims, std::size_t begin, std::size_t end,
                   const std::vector<Vec3>& centres) const {
  const auto index = static_cast<int32_t>(out.size());
  out.push_back(Node{});
  out[static_cast<std::size_t>(index)].first = static_cast<int32_t>(begin);
  out[static_cast<std::size_t>(index)].last = static_cast<int32_t>(end) - 1;
  if (end - begin <= static_cast<std::size_t>(kLeafSize)) {
    Aabb box;
    for (std::size_t i = begin; i < end; ++i) box.grow(leaf_box_[static_cast<std::size_t>(prims[i])]);
    out[static_cast<std::size_t>(index)].box = box;
    ++leaves;
    return index;
  }
  const std::size_t mid = split(prims, begin, end, centres);
  const int32_t left = build(out, leaves, prims, begin, mid, centres);
  const int32_t right = build(out, leaves, prims, mid, end, centres);
  Node& n = out[static_cast<std::size_t>(index)];
  n.left = left;
  n.right = right;
  n.box = out[static_cast<std::size_t>(left)].box;
  n.box.grow(out[static_cast<std::size_t>(right)].box);
  return index;
}

namespace {
// Half the surface area of a box (the surface area heuristic's measure).
double half_area(const Aabb& b) {
  const Vec3 d = (b.hi - b.lo).cwiseMax(0.0);
  return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
}
}  // namespace

void Bvh::refit(std::vector<Aabb> leaf_boxes, int threads) {
  leaf_box_ = std::move(leaf_boxes);
  if (leaf_box_.empty()) return;
  const auto count = static_cast<int32_t>(nodes_.size());
  const auto ranked = static_cast<int64_t>(order_.size());
  auto rank_box = [&](int64_t r) -> const Aabb& {
    return ranked_box_[static_cast<std::size_t>(r)] = leaf_box_[static_cast<std::size_t>(order_[static_cast<std::size_t>(r)])];
  };
  double primitives = 0, nodes = 0;
  if (threads < 2 || leaf_box_.size() < kParallelPrimitives || nodes_.front().left < 0) {
    // Children come after their parent (the build numbers nodes depth first), so one backward
    // pass refits bottom-up, and measures the looseness on the way.
    for (int64_t r = 0; r < ranked; ++r) primitives += half_area(rank_box(r));
    for (int32_t i = count - 1; i >= 0; --i) {
      refit_nodes(i, i + 1);
      nodes += half_area(nodes_[static_cast<std::size_t>(i)].box);
    }
  } else {
    // The root's two subtrees, [1, right) and [right, count), side by side, then the root; the
    // looseness summed afterwards in the one-thread order.
    const int32_t right = nodes_.front().right;
#pragma omp parallel num_threads(2)
    {
#pragma omp for schedule(static)
      for (int64_t r = 0; r < ranked; ++r) rank_box(r);
#pragma omp sections
      {
#pragma omp section
        refit_nodes(1, right);
#pragma omp section
        refit_nodes(right, count);
      }
    }
    refit_nodes(0, 1);
    for (const Aabb& b : ranked_box_) primitives += half_area(b);
    for (int32_t i = count - 1; i >= 0; --i) nodes += half_area(nodes_[static_cast<std::size_t>(i)].box);
  }
  looseness_ = primitives > 0 ? nodes / primitives : nodes;
}

void Bvh::refit_nodes(int32_t first, int32_t last) {
  for (int32_t i = last - 1; i >= first; --i) {
    Node& n = nodes_[static_cast<std::size_t>(i)];
    if (n.left < 0) {
      n.box = Aabb();
      for (int32_t r = n.first; r <= n.last; ++r) n.box.grow(ranked_box_[static_cast<std::size_t>(r)]);
    } else {
      n.box = nodes_[static_cast<std::size_t>(n.left)].box;
      n.box.grow(nodes_[static_cast<std::size_t>(n.right)].box);
    }
  }
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
