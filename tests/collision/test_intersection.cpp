// The exact triangle-triangle intersection check that the scene tests rely on.
#include <gtest/gtest.h>

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
    if (plane_separates(s, t) || plane_separates(t, s)) {
      ++separated;
      ASSERT_FALSE(crosses) << "trial " << trial;
    }
    ASSERT_EQ(triangles_intersect(s, t), crosses) << "trial " << trial;
    crossing += crosses ? 1 : 0;
  }
  EXPECT_GT(separated, 50000);
  EXPECT_GT(crossing, 10000);
}

}  // namespace
}  // namespace vdc
