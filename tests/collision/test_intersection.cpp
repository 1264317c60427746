// The exact triangle-triangle intersection check that the scene tests rely on.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace vdc
