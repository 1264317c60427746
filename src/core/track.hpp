// A keyframed 3-vector: cubic Hermite interpolation through the keys (tangents from the
// neighbouring keys, zero at both ends), held before the first and after the last key.
#pragma once
#include <vector>

#include "core/math.hpp"

namespace vdc {

struct Vec3Key {
  double time = 0;
  Vec3 value = Vec3::Zero();
};

struct Vec3Track {
  std::vector<Vec3Key> keys;  // sorted by time
  bool empty() const { return keys.empty(); }
  Vec3 at(double t) const;
};

}  // namespace vdc
