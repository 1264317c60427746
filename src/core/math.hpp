// Small fixed-size linear algebra types shared by every module (Eigen underneath).
#pragma once
#include <array>

#include <Eigen/Core>
#include <Eigen/Dense>

namespace vdc {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using Mat32 = Eigen::Matrix<double, 3, 2>;
using Mat23 = Eigen::Matrix<double, 2, 3>;
using Triangle = std::array<Vec3, 3>;  // a triangle's corners
template <int N>
using VecN = Eigen::Matrix<double, N, 1>;
template <int N>
using MatN = Eigen::Matrix<double, N, N>;

// Twice the signed area of the 2D triangle (a, b, c); positive when counter-clockwise.
inline double signed_area2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// The 2D cross product (z of the 3D cross product of (a, 0) and (b, 0)).
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Six times the signed volume of the tetrahedron (a, b, c, d): positive when d lies on the side
// of the plane (a, b, c) its area normal points to.
inline double orient3(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return (b - a).cross(c - a).dot(d - a); }

// Unnormalized normal (twice the area times the unit normal) of the 3D triangle (a, b, c).
inline Vec3 area_normal(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a).cross(c - a); }

}  // namespace vdc
