// Physics level of detail for cloth no camera resolves (an extension of Koh, Narain and O'Brien
// 2014, section 3.2's screen-space floor, eqs. 5 to 8).
#include "view/level_of_detail.hpp"

#include <algorithm>
#include <cmath>

#include "core/bvh.hpp"

namespace vdc {

GarmentReach garment_reach(const std::vector<Vec3>& x, const std::vector<Vec3>& v) {
  GarmentReach r;
  if (x.empty()) return r;
  Aabb box;
  for (const Vec3& p : x) box.grow(p);
  r.centre = 0.5 * (box.lo + box.hi);
  for (const Vec3& p : x) r.radius = std::max(r.radius, (p - r.centre).norm());
  for (const Vec3& u : v) r.speed = std::max(r.speed, u.norm());
  return r;
}

double most_pixels_per_metre(const Camera& camera, const Frustum& frustum, const Vec3& centre, double radius) {
  if (ball_outside(frustum, centre, radius)) return 0;
  const Vec3 forward = camera.basis()[2];
  const double depth = std::max((centre - camera.position).dot(forward) - radius, camera.near);
  const double ty = std::tan(0.5 * camera.fov_y_degrees * M_PI / 180.0), tx = ty * camera.width / camera.height;
  return camera.focal_pixels() * std::sqrt(1 + tx * tx + ty * ty) / depth;
}

bool beyond_resolution(const std::vector<AnticipationWindow>& windows, const ViewParams& p, const GarmentReach& reach, double size_max) {
  if (!(p.l_min > 0) || !(p.fold_length > 0)) return false;
  for (const AnticipationWindow& w : windows)
    for (std::size_t s = 0; s < w.cameras.size(); ++s) {
      const double pixels = most_pixels_per_metre(w.cameras[s], w.frusta[s], reach.centre, reach.radius + reach.speed * w.offsets[s]);
      if (p.fold_length * pixels >= 0.5 * p.l_min) return false;
      if (p.l_max > 0 && size_max * pixels >= p.l_max) return false;
    }
  return true;
}

}  // namespace vdc
