#include "scene/handle.hpp"

#include <algorithm>

namespace vdc {

Vec3 ClothHandle::offset(double t) const {
  if (path.empty()) return Vec3::Zero();
  if (t <= path.front().time) return path.front().offset;
  if (t >= path.back().time) return path.back().offset;
  auto hi = std::upper_bound(path.begin(), path.end(), t, [](double s, const Keyframe& k) { return s < k.time; });
  const std::size_t i = static_cast<std::size_t>(hi - path.begin()) - 1;
  const Keyframe &k0 = path[i], &k1 = path[i + 1];
  auto tangent = [&](std::size_t j) -> Vec3 {
    if (j == 0 || j + 1 >= path.size()) return Vec3::Zero();
    return (path[j + 1].offset - path[j - 1].offset) / (path[j + 1].time - path[j - 1].time);
  };
  const double dt = k1.time - k0.time, s = (t - k0.time) / dt;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * k0.offset + (s3 - 2 * s2 + s) * dt * tangent(i) + (-2 * s3 + 3 * s2) * k1.offset +
         (s3 - s2) * dt * tangent(i + 1);
}

}  // namespace vdc
