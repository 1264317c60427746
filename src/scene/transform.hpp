// Placement of a mesh in the scene: uniform scale, then rotation about X, Y, Z (degrees, in that
// order), then translation.
#pragma once
#include "core/math.hpp"

namespace vdc {

struct Transform {
  double scale = 1.0;
  Vec3 rotate_degrees = Vec3::Zero();
  Vec3 translate = Vec3::Zero();

  Mat3 rotation() const;
  Vec3 apply(const Vec3& p) const { return rotation() * (scale * p) + translate; }
};

}  // namespace vdc
