// Nearest obstacle points of cloth nodes (for obstacle-proximity sizing, Narain et al. 2012).
#include "remesh/obstacle_planes.hpp"

#include <memory>
#include <utility>

#include "collision/distance.hpp"
#include "core/bvh.hpp"

namespace vdc {

namespace {

// The point of obstacle face f (corners at ox) closest to p.
Vec3 closest_on_face(const Vec3& p, const CollisionMesh& obstacle, const std::vector<Vec3>& ox, std::size_t f) {
  const auto& face = obstacle.faces[f];
  const Vec3& a = ox[static_cast<std::size_t>(face[0])];
  const Vec3& b = ox[static_cast<std::size_t>(face[1])];
  const Vec3& c = ox[static_cast<std::size_t>(face[2])];
  const Vec3 w = closest_triangle_weights(p, a, b, c);
  return w[0] * a + w[1] * b + w[2] * c;
}

// Whether a surface point lies within `distance` of p on the far side of p from its nearest
// obstacle point (in the open half-space the plane's normal points into).
bool held_from_far_side(const Vec3& p, const ObstaclePlane& plane, const std::vector<CollisionMesh>& obstacles,
                        const std::vector<std::vector<Vec3>>& obstacle_x, const std::vector<const Bvh*>& trees, double distance) {
  Aabb box;
  box.grow(p);
  box.pad(distance);
  bool held = false;
  for (std::size_t o = 0; o < obstacles.size() && !held; ++o)
    trees[o]->query(box, [&](int32_t fi) {
      if (held) return;
      const Vec3 q = closest_on_face(p, obstacles[o], obstacle_x[o], static_cast<std::size_t>(fi));
      held = (q - p).norm() <= distance && (q - p).dot(plane.normal) > 0;
    });
  return held;
}

}  // namespace

std::vector<ObstaclePlane> nearest_obstacle_planes(const std::vector<Vec3>& points, const std::vector<CollisionMesh>& obstacles,
                                                   const std::vector<std::vector<Vec3>>& obstacle_x, double radius, double hold_distance, int threads,
                                                   const std::vector<const Bvh*>& obstacle_trees) {
  std::vector<ObstaclePlane> planes(points.size());
  std::vector<double> best(points.size(), radius);
  // The face each point's plane comes from (obstacle, face): of two equally near, the first in
  // that order, so that the planes do not depend on the order a hierarchy meets the faces in.
  std::vector<std::pair<std::size_t, int32_t>> best_face(points.size(), {0, -1});
  std::vector<std::unique_ptr<Bvh>> built;
  const std::vector<const Bvh*> trees = face_trees_at(obstacles, obstacle_x, obstacle_trees, threads, built);
  const auto n = static_cast<int64_t>(points.size());
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
  for (int64_t node = 0; node < n; ++node) {
    const auto i = static_cast<std::size_t>(node);
    const Vec3& p = points[i];
    for (std::size_t o = 0; o < obstacles.size(); ++o) {
      const auto& ox = obstacle_x[o];
      const auto& faces = obstacles[o].faces;
      auto corner = [&](std::size_t f, int k) -> const Vec3& { return ox[static_cast<std::size_t>(faces[f][static_cast<std::size_t>(k)])]; };
      trees[o]->nearest(p, best[i], [&](int32_t fi) {
        const auto f = static_cast<std::size_t>(fi);
        const Vec3 q = closest_on_face(p, obstacles[o], ox, f);
        const double d = (p - q).norm();
        const std::pair<std::size_t, int32_t> here{o, fi};
        if (d < best[i] || (d == best[i] && best_face[i].second >= 0 && here < best_face[i])) {
          best_face[i] = here;
          planes[i].point = q;
          planes[i].normal = d > 1e-9 ? Vec3((p - q) / d) : Vec3(area_normal(corner(f, 0), corner(f, 1), corner(f, 2)).normalized());
        }
        return d;
      });
    }
    if (best[i] <= hold_distance && planes[i].normal.squaredNorm() > 0) planes[i].held = held_from_far_side(p, planes[i], obstacles, obstacle_x, trees, hold_distance);
  }
  return planes;
}

}  // namespace vdc
