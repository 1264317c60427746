// The exact triangle-triangle intersection check that the scene tests rely on.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "collision/intersection.hpp"

namespace vdc {
namespace {

TEST(Intersection, CrossingAndSeparateTriangles) {
  std::array<Vec3, 3> t{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_TRUE(triangles_intersect(t, {Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), Vec3(2, 2, 0.5)}));
  EXPECT_FALSE(triangles_intersect(t, {Vec3(0.2, 0.2, 0.1), Vec3(0.3, 0.2, 1), Vec3(2, 2, 0.5)}));
  EXPECT_FALSE(triangles_intersect(t, {Vec3(2, 2, -1), Vec3(2, 2, 1), Vec3(3, 3, 0.5)}));
  // Two triangles through each other edge-wise (a ring): each crosses the other.
  EXPECT_TRUE(triangles_intersect(t, {Vec3(0.5, -0.5, 0.5), Vec3(0.5, 0.5, -0.5), Vec3(0.5, 1.5, 0.5)}));
}

// Any edge of either triangle crossing the other: the test without its plane rejection.
bool some_edge_crosses(const std::array<Vec3, 3>& s, const std::array<Vec3, 3>& t) {
  for (int i = 0; i < 3; ++i) {
    const auto i0 = static_cast<std::size_t>(i), i1 = static_cast<std::size_t>((i + 1) % 3);
    if (segment_crosses_triangle(s[i0], s[i1], t[0], t[1], t[2]) || segment_crosses_triangle(t[i0], t[i1], s[0], s[1], s[2])) return true;
  }
  return false;
}

TEST(Intersection, PlaneRejectionNeverHidesACrossing) {
  // Random pairs, many of them nearly touching or nearly coplanar (a triangle of the other's
  // plane lifted by 1e-14 to 1e-2 of its size): wherever the rejection says apart, no edge
  // crosses, and the answer with the rejection is the crossing tests' answer.
  std::mt19937_64 random(71);
  std::uniform_real_distribution<double> unit(-1, 1);
  auto point = [&] { return Vec3(unit(random), unit(random), unit(random)); };
  int separated = 0, crossing = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const std::array<Vec3, 3> s{point(), point(), point()};
    std::array<Vec3, 3> t{point(), point(), point()};
    if (trial % 2 == 1) {
      // t in s's plane, then each corner lifted along the normal by its own small amount.
      const Vec3 n = (s[1] - s[0]).cross(s[2] - s[0]).normalized();
      const double lift = std::pow(10.0, -14 + 12 * (unit(random) + 1) / 2);
      for (Vec3& p : t) p += (lift * (unit(random) > -0.8 ? 1.0 : -1.0) * (1 + unit(random) / 2) - n.dot(p - s[0])) * n;
    }
    const bool crosses = some_edge_crosses(s, t);
    if (PlaneOf(s).separates(t) || PlaneOf(t).separates(s)) {
      ++separated;
      ASSERT_FALSE(crosses) << "trial " << trial;
    }
    ASSERT_EQ(triangles_intersect(s, t), crosses) << "trial " << trial;
    crossing += crosses ? 1 : 0;
  }
  EXPECT_GT(separated, 50000);
  EXPECT_GT(crossing, 10000);
}

TEST(Intersection, APlaneClearsABoxOnlyWhenItSeparatesEveryTriangleInIt) {
  // Random triangles s and boxes, many of the boxes grazing s's plane (lifted 1e-14 to 1e-2 of
  // their size off it): where the plane clears a box, PlaneOf(s).separates(t) holds for triangles t
  // drawn inside the box, corners included.
  std::mt19937_64 random(72);
  std::uniform_real_distribution<double> unit(-1, 1), fraction(0, 1);
  auto point = [&] { return Vec3(unit(random), unit(random), unit(random)); };
  int cleared = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const std::array<Vec3, 3> s{point(), point(), point()};
    const Vec3 n = (s[1] - s[0]).cross(s[2] - s[0]).normalized();
    Aabb box;
    const Vec3 centre = point(), half = 0.3 * Vec3(fraction(random), fraction(random), fraction(random));
    box.grow(Vec3(centre - half));
    box.grow(Vec3(centre + half));
    if (trial % 2 == 1) {
      // Slide the box along the normal until its nearest corner is a small lift off the plane.
      const double reach = n.cwiseAbs().dot(half), lift = std::pow(10.0, -14 + 12 * fraction(random));
      const double shift = reach + lift - n.dot(centre - s[0]);
      box.lo += shift * n;
      box.hi += shift * n;
    }
    if (!PlaneOf(s).clears(box)) continue;
    ++cleared;
    auto inside = [&] {
      Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = fraction(random) < 0.3 ? (fraction(random) < 0.5 ? box.lo[k] : box.hi[k]) : box.lo[k] + fraction(random) * (box.hi[k] - box.lo[k]);
      return p;
    };
    for (int t = 0; t < 20; ++t) ASSERT_TRUE(PlaneOf(s).separates({inside(), inside(), inside()})) << "trial " << trial;
  }
  EXPECT_GT(cleared, 5000);
}

}  // namespace
}  // namespace vdc
