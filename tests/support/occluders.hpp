// Shapes the occlusion tests hide things behind, seen by test::front_camera().
#pragma once
#include <cmath>
#include <vector>

#include "core/math.hpp"

namespace vdc::test {

// The square [-1, 1]^2 moved by `dx` along x, in the plane z = 0, facing +z.
inline std::vector<Triangle> wall(double dx = 0) {
  const Vec3 a(-1 + dx, -1, 0), b(1 + dx, -1, 0), c(1 + dx, 1, 0), d(-1 + dx, 1, 0);
  return {Triangle{a, b, c}, Triangle{a, c, d}};
}

// A sphere of radius r at the origin, outward counter-clockwise, from polar angle theta0 to
// theta1 (measured from +z): 0 to pi is the whole ball, pi/2 to pi its half below z = 0.
inline std::vector<Triangle> sphere_band(double r, double theta0, double theta1, int rings = 24, int sectors = 48) {
  auto at = [&](int i, int j) {
    const double theta = theta0 + (theta1 - theta0) * i / rings, phi = 2 * M_PI * j / sectors;
    return Vec3(r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi), r * std::cos(theta));
  };
  std::vector<Triangle> out;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const Vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if ((b - a).cross(c - a).norm() > 1e-12) out.push_back({a, b, c});
      if ((c - a).cross(d - a).norm() > 1e-12) out.push_back({a, c, d});
    }
  return out;
}

inline Vec3 centre(const Triangle& t) { return (t[0] + t[1] + t[2]) / 3.0; }

}  // namespace vdc::test
