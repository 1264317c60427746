// The narrow phase's impact constraints against hand-computed contacts: a vertex falling
// through a triangle, the same triangle moving with an obstacle, a miss, and two crossing edges.
#include <gtest/gtest.h>

#include "collision/narrow_phase.hpp"

namespace vdc {
namespace {

constexpr double kImpactEta = 1e-6;

// A still obstacle triangle in the plane z = 0 (no movable node), optionally moving by `motion`.
std::array<PointPath, 3> obstacle_triangle(const Vec3& motion = Vec3::Zero()) {
  return {PointPath{Vec3(0, 0, 0), Vec3(0, 0, 0) + motion, -1}, PointPath{Vec3(1, 0, 0), Vec3(1, 0, 0) + motion, -1},
          PointPath{Vec3(0, 1, 0), Vec3(0, 1, 0) + motion, -1}};
}

TEST(NarrowPhase, AVertexFallingThroughATriangleGivesItsBarycentricConstraint) {
  // Node 7 falls from z = 1 to z = -1 at (0.2, 0.3): it meets the triangle halfway, at the
  // barycentric weights (0.5, 0.2, 0.3), and is pushed back up (+z, the side it came from).
  const PointPath p{Vec3(0.2, 0.3, 1), Vec3(0.2, 0.3, -1), 7};
  const auto tri = obstacle_triangle();
  const auto c = vertex_face_impact(p, tri[0], tri[1], tri[2], kImpactEta);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->nodes, (std::array<int32_t, 4>{7, -1, -1, -1}));
  EXPECT_NEAR(c->weights[0], 1.0, 1e-12);
  EXPECT_NEAR(c->weights[1], -0.5, 1e-9);
  EXPECT_NEAR(c->weights[2], -0.2, 1e-9);
  EXPECT_NEAR(c->weights[3], -0.3, 1e-9);
  EXPECT_LT((c->normal - Vec3(0, 0, 1)).norm(), 1e-12);
  EXPECT_TRUE(c->has_fixed);
  EXPECT_LT(c->fixed_motion.norm(), 1e-15);  // the triangle did not move
  EXPECT_LT((c->fixed[2] - Vec3(1, 0, 0)).norm(), 1e-15);  // fixed points at their end positions
  // From below, the normal points down.
  const PointPath up{Vec3(0.2, 0.3, -1), Vec3(0.2, 0.3, 1), 7};
  const auto c_up = vertex_face_impact(up, tri[0], tri[1], tri[2], kImpactEta);
  ASSERT_TRUE(c_up.has_value());
  EXPECT_LT((c_up->normal - Vec3(0, 0, -1)).norm(), 1e-12);
}

TEST(NarrowPhase, AnObstacleThatMovesCarriesItsDisplacementIntoTheConstraint) {
  // The triangle sinks 0.4 while the vertex falls from 1 to -1: still a contact, and the fixed
  // points' displacement, weighted by |w_j| over their weights, is the triangle's motion.
  const PointPath p{Vec3(0.2, 0.3, 1), Vec3(0.2, 0.3, -1), 3};
  const auto tri = obstacle_triangle(Vec3(0, 0, -0.4));
  const auto c = vertex_face_impact(p, tri[0], tri[1], tri[2], kImpactEta);
  ASSERT_TRUE(c.has_value());
  EXPECT_LT((c->fixed_motion - Vec3(0, 0, -0.4)).norm(), 1e-12);
  // A vertex that stays above the sinking triangle meets nothing.
  const PointPath above{Vec3(0.2, 0.3, 0.5), Vec3(0.2, 0.3, 0.2), 3};
  EXPECT_FALSE(vertex_face_impact(above, tri[0], tri[1], tri[2], kImpactEta).has_value());
}

TEST(NarrowPhase, CrossingEdgesMeetAtTheirClosestPoints) {
  // Edge (a, b) along x at y = 0 falls from z = 1 to z = -1 through edge (c, d) along y at
  // x = 0.25, z = 0: they meet at (0.25, 0, 0), s = 0.625 along (a, b), u = 0.5 along (c, d);
  // all four points movable, the normal from (c, d) towards where (a, b) started (+z).
  const PointPath a{Vec3(-1, 0, 1), Vec3(-1, 0, -1), 0}, b{Vec3(1, 0, 1), Vec3(1, 0, -1), 1};
  const PointPath c{Vec3(0.25, -1, 0), Vec3(0.25, -1, 0), 2}, d{Vec3(0.25, 1, 0), Vec3(0.25, 1, 0), 3};
  const auto k = edge_edge_impact(a, b, c, d, kImpactEta);
  ASSERT_TRUE(k.has_value());
  EXPECT_EQ(k->nodes, (std::array<int32_t, 4>{0, 1, 2, 3}));
  EXPECT_NEAR(k->weights[0], 0.375, 1e-9);
  EXPECT_NEAR(k->weights[1], 0.625, 1e-9);
  EXPECT_NEAR(k->weights[2], -0.5, 1e-9);
  EXPECT_NEAR(k->weights[3], -0.5, 1e-9);
  EXPECT_LT((k->normal - Vec3(0, 0, 1)).norm(), 1e-12);
  EXPECT_FALSE(k->has_fixed);
  // Moved sideways past the end of (c, d), the falling edge misses it.
  const PointPath a2{Vec3(-1, 1.5, 1), Vec3(-1, 1.5, -1), 0}, b2{Vec3(1, 1.5, 1), Vec3(1, 1.5, -1), 1};
  EXPECT_FALSE(edge_edge_impact(a2, b2, c, d, kImpactEta).has_value());
}

}  // namespace
}  // namespace vdc
