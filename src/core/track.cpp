#include "core/track.hpp"

#include <algorithm>

namespace vdc {

Vec3 Vec3Track::at(double t) const {
  if (keys.empty()) return Vec3::Zero();
  if (t <= keys.front().time) return keys.front().value;
  if (t >= keys.back().time) return keys.back().value;
  auto hi = std::upper_bound(keys.begin(), keys.end(), t, [](double s, const Vec3Key& k) { return s < k.time; });
  const std::size_t i = static_cast<std::size_t>(hi - keys.begin()) - 1;
  const Vec3Key &k0 = keys[i], &k1 = keys[i + 1];
  auto tangent = [&](std::size_t j) -> Vec3 {
    if (j == 0 || j + 1 >= keys.size()) return Vec3::Zero();
    return (keys[j + 1].value - keys[j - 1].value) / (keys[j + 1].time - keys[j - 1].time);
  };
  const double dt = k1.time - k0.time, s = (t - k0.time) / dt;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * k0.value + (s3 - 2 * s2 + s) * dt * tangent(i) + (-2 * s3 + 3 * s2) * k1.value +
         (s3 - s2) * dt * tangent(i + 1);
}

}  // namespace vdc
