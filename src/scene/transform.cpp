#include "scene/transform.hpp"

#include <Eigen/Geometry>
#include <numbers>

namespace vdc {

Mat3 Transform::rotation() const {
  const double k = std::numbers::pi / 180.0;
  return (Eigen::AngleAxisd(k * rotate_degrees.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(k * rotate_degrees.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(k * rotate_degrees.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

}  // namespace vdc
