#include "collision/candidates.hpp"

namespace vdc {

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
