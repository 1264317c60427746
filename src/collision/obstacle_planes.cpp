// Nearest obstacle points of cloth nodes (for obstacle-proximity sizing, Narain et al. 2012).
#include "collision/obstacle_planes.hpp"

#include "collision/distance.hpp"
#include "core/bvh.hpp"

namespace vdc {

std::vector<ObstaclePlane> nearest_obstacle_planes(const std::vector<Vec3>& points, const std::vector<CollisionMesh>& obstacles,
                                                   const std::vector<std::vector<Vec3>>& obstacle_x, double radius) {
  std::vector<ObstaclePlane> planes(points.size());
  std::vector<double> best(points.size(), radius);
  for (std::size_t o = 0; o < obstacles.size(); ++o) {
    const auto& ox = obstacle_x[o];
    const auto& faces = obstacles[o].faces;
    auto corner = [&](std::size_t f, int k) -> const Vec3& { return ox[static_cast<std::size_t>(faces[f][static_cast<std::size_t>(k)])]; };
    std::vector<Aabb> boxes(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (int k = 0; k < 3; ++k) boxes[f].grow(corner(f, k));
    const Bvh tree(boxes);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec3& p = points[i];
      Aabb box;
      box.grow(p);
      box.pad(best[i]);
      tree.query(box, [&](int32_t fi) {
        const auto f = static_cast<std::size_t>(fi);
        const Vec3 w = closest_triangle_weights(p, corner(f, 0), corner(f, 1), corner(f, 2));
        const Vec3 q = w[0] * corner(f, 0) + w[1] * corner(f, 1) + w[2] * corner(f, 2);
        const double d = (p - q).norm();
        if (d >= best[i]) return;
        const Vec3 face_normal = area_normal(corner(f, 0), corner(f, 1), corner(f, 2)).normalized();
        best[i] = d;
        planes[i].point = q;
        planes[i].normal = d > 1e-9 ? Vec3((p - q) / d) : face_normal;
      });
    }
  }
  return planes;
}

}  // namespace vdc
