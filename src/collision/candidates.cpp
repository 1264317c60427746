#include "collision/candidates.hpp"

#include <algorithm>

namespace vdc {

// Which nodes have left the neighbour lists' reach (Verlet 1967's lists, with the common motion taken out).
std::vector<char> KeptClothPairs::beyond(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double d, const std::vector<char>& used) const {
  Vec3 shift = Vec3::Zero();
  double count = 0;
  for (std::size_t n = 0; n < used.size(); ++n)
    if (used[n]) {
      const auto i = static_cast<Eigen::Index>(3 * n);
      shift += 0.5 * (a.segment<3>(i) + b.segment<3>(i)) - x.segment<3>(i);
      count += 1;
    }
  if (count > 0) shift /= count;
  std::vector<char> far(used.size(), 0);
  const double r = reach(d);
  for (std::size_t n = 0; n < far.size(); ++n) {
    const auto i = static_cast<Eigen::Index>(3 * n);
    const Vec3 home = x.segment<3>(i) + shift;
    far[n] = std::max((a.segment<3>(i) - home).cwiseAbs().maxCoeff(), (b.segment<3>(i) - home).cwiseAbs().maxCoeff()) > r;
  }
  return far;
}

bool KeptClothPairs::worth_taking(const std::vector<char>& far, const std::vector<char>& used) {
  std::size_t beyond = 0, in_use = 0;
  for (std::size_t n = 0; n < used.size(); ++n) {
    in_use += used[n] != 0;
    beyond += used[n] != 0 && far[n] != 0;
  }
  return 16 * beyond <= in_use;
}

std::vector<Aabb> MovedPrimitives::boxes_of(const std::vector<int32_t>& items, const std::vector<Aabb>& boxes) {
  std::vector<Aabb> out;
  out.reserve(items.size());
  for (const int32_t i : items) out.push_back(boxes[static_cast<std::size_t>(i)]);
  return out;
}

namespace {

// The primitives (faces or edges) with a moved node, in order.
template <std::size_t N>
std::vector<int32_t> with_moved_node(const std::vector<std::array<int32_t, N>>& items, const std::vector<char>& moved) {
  std::vector<int32_t> out;
  for (std::size_t i = 0; i < items.size(); ++i)
    for (const int32_t n : items[i])
      if (moved[static_cast<std::size_t>(n)]) {
        out.push_back(static_cast<int32_t>(i));
        break;
      }
  return out;
}

}  // namespace

MovedPrimitives::MovedPrimitives(const std::vector<char>& moved, const CandidateTrees& trees, const std::vector<Aabb>& face_boxes,
                                 const std::vector<Aabb>& edge_boxes)
    : moved_(moved),
      faces_(with_moved_node(trees.cloth_faces, moved)),
      edges_(with_moved_node(trees.cloth_edges, moved)),
      face_tree_(boxes_of(faces_, face_boxes)),
      edge_tree_(boxes_of(edges_, edge_boxes)) {}

}  // namespace vdc
