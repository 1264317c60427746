// An obstacle's hierarchies, refit from its vertices' boxes and reused where a sweep ended.
#include "collision/obstacle_trees.hpp"

#include <utility>

namespace vdc {

void ObstacleTrees::sweep(const std::vector<std::array<int32_t, 3>>& faces, const std::vector<std::array<int32_t, 2>>& edges,
                          const std::vector<Vec3>& start, const std::vector<Vec3>& end, double pad, int threads) {
  // A primitive's box is the union of its vertices' boxes, so each vertex's path is bounded once.
  std::vector<Aabb> vertex_boxes = leaf_boxes(end.size(), threads, [&](std::size_t i) {
    Aabb b;
    b.grow(start[i]);
    b.grow(end[i]);
    b.pad(pad);
    return b;
  });
  auto box = [&](int32_t i) -> const Aabb& { return vertex_boxes[static_cast<std::size_t>(i)]; };
  faces_ = &face_tree_.update(leaf_boxes(faces.size(), threads, [&](std::size_t i) {
    Aabb b = box(faces[i][0]);
    b.grow(box(faces[i][1]));
    b.grow(box(faces[i][2]));
    return b;
  }), threads);
  edges_ = &edge_tree_.update(leaf_boxes(edges.size(), threads, [&](std::size_t i) {
    Aabb b = box(edges[i][0]);
    b.grow(box(edges[i][1]));
    return b;
  }), threads);
  vertices_ = &vertex_tree_.update_with(std::move(vertex_boxes), face_tree_.rebuilt(), threads);
  vertices_at_points_ = pad == 0.0 && start == end;
  held_ = end;
}

void ObstacleTrees::hold(const std::vector<std::array<int32_t, 3>>& faces, const std::vector<std::array<int32_t, 2>>& edges,
                         const std::vector<Vec3>& x, int threads) {
  if (faces_ == nullptr || held_ != x) {
    sweep(faces, edges, x, x, 0.0, threads);
    return;
  }
  if (vertices_at_points_) return;
  // A vertex's swept path would meet faces a step's motion away from it: the vertices are refit
  // to their points, the faces and edges kept as swept (their boxes are wider than a step's path).
  vertices_ = &vertex_tree_.update_with(leaf_boxes(x.size(), threads, [&](std::size_t i) {
    Aabb b;
    b.grow(x[i]);
    return b;
  }), false, threads);
  vertices_at_points_ = true;
}

}  // namespace vdc
