// Continuous collision detection: analytic configurations and random sweeps built to collide
// at a known time (inside, on an edge, at a vertex, grazing, coplanar, parallel): a real
// collision is never missed and never reported late; separated motion is never reported.
#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "collision/ccd.hpp"
#include "collision/distance.hpp"

namespace vdc {
namespace {

constexpr double kEta = 1e-9;

TEST(Distance, PointTriangleAndSegmentSegmentKnownValues) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_NEAR(point_triangle_distance(Vec3(0.2, 0.2, 0.5), a, b, c), 0.5, 1e-15);
  EXPECT_NEAR(point_triangle_distance(Vec3(2, 0, 0), a, b, c), 1.0, 1e-15);
  EXPECT_NEAR(point_triangle_distance(Vec3(-1, -1, 0), a, b, c), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(segment_segment_distance(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -1, 1), Vec3(0.5, 1, 1)), 1.0, 1e-15);
  // Parallel, overlapping: distance 0.3.
  EXPECT_NEAR(segment_segment_distance(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.3, 0), Vec3(1.5, 0.3, 0)), 0.3, 1e-15);
  // Parallel, disjoint along the line.
  EXPECT_NEAR(segment_segment_distance(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)), 1.0, 1e-15);
}

// The lines' candidate decides whether two segments' closest points are inside both: on random
// pairs (skew, nearly parallel, parallel, touching at an end), the closest pair is strictly inside
// both exactly when the lines' candidate is, and is then that candidate.
TEST(Distance, ClosestPointsInsideBothSegmentsAreTheLinesClosestPoints) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> U(-1, 1);
  auto inside = [](const Vec2& q) { return q.x() > 1e-6 && q.x() < 1 - 1e-6 && q.y() > 1e-6 && q.y() < 1 - 1e-6; };
  int both_inside = 0, lines_outside = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 a(U(rng), U(rng), U(rng)), b(U(rng), U(rng), U(rng)), c(U(rng), U(rng), U(rng));
    Vec3 d(U(rng), U(rng), U(rng));
    if (k % 4 == 1) d = c + (b - a) * (0.5 + U(rng)) + Vec3::Constant(1e-9 * U(rng));  // nearly parallel
    if (k % 4 == 2) d = c + (b - a) * 0.7;                                             // parallel
    const Vec2 closest = closest_segment_params(a, b, c, d);
    const std::optional<Vec2> lines = closest_line_params(a, b, c, d);
    if (!lines || !inside(*lines)) {
      ++lines_outside;
      EXPECT_FALSE(inside(closest)) << k;
    } else if (inside(closest)) {
      ++both_inside;
      EXPECT_EQ(closest, *lines) << k;
    }
  }
  EXPECT_GT(both_inside, 1000);
  EXPECT_GT(lines_outside, 1000);
}

TEST(Ccd, VertexFallsThroughTriangle) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Impact r = vertex_face_ccd(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -1), a, a, b, b, c, c, kEta);
  ASSERT_TRUE(r.hit);
  EXPECT_NEAR(r.t, 0.5, 1e-12);
  Impact miss = vertex_face_ccd(Vec3(0.8, 0.8, 1), Vec3(0.8, 0.8, -1), a, a, b, b, c, c, kEta);
  EXPECT_FALSE(miss.hit);
}

TEST(Ccd, TangentialContactWithADoubleRootIsFound) {
  // The coplanarity function is -s^2/2 with s = 2t - 1: it touches zero at t = 1/2 without
  // changing sign, where the point (0.25, 0.25, 0) lies inside the triangle.
  const Vec3 a(0, 0, 0), b(1, 0, 0);
  const Vec3 c0(0, 1, -1), c1(0, 1, 1);
  const Vec3 p0(0.25, -0.25, -0.25), p1(0.25, 0.75, 0.25);
  auto k = coplanarity_cubic(b - a, Vec3::Zero(), c0 - a, c1 - c0, p0 - a, p1 - p0);
  for (int i = 0; i <= 20; ++i) {  // never positive: no sign change for a root finder to see
    const double t = i / 20.0;
    EXPECT_LE(((k[3] * t + k[2]) * t + k[1]) * t + k[0], 1e-15) << "t " << t;
  }
  Impact r = vertex_face_ccd(p0, p1, a, a, b, b, c0, c1, kEta);
  ASSERT_TRUE(r.hit);
  // Near a tangency the distance grows only quadratically, so the earliest time within eta
  // lies up to about sqrt(eta) before the touch.
  EXPECT_NEAR(r.t, 0.5, 1e-4);
  EXPECT_LE(r.t, 0.5);
}

TEST(Ccd, VertexSlidingInThePlaneIntoTheTriangle) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Impact r = vertex_face_ccd(Vec3(-1, 0.25, 0), Vec3(1, 0.25, 0), a, a, b, b, c, c, kEta);
  ASSERT_TRUE(r.hit);
  EXPECT_NEAR(r.t, 0.5, 1e-9);  // enters across the edge x = 0 at t = 1/2
}

TEST(Ccd, ParallelEdgesClosingInTheirPlane) {
  // Two parallel edges 1 apart along y, overlapping in x, close at speed 2: contact at t = 1/2.
  Impact r = edge_edge_ccd(Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, -1, 0),
                           Vec3(1.5, 1, 0), Vec3(1.5, -1, 0), kEta);
  ASSERT_TRUE(r.hit);
  EXPECT_NEAR(r.t, 0.5, 1e-9);
  Impact miss = edge_edge_ccd(Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(2.5, 1, 0), Vec3(2.5, -1, 0),
                              Vec3(3.5, 1, 0), Vec3(3.5, -1, 0), kEta);
  EXPECT_FALSE(miss.hit);
}

// Random collisions built backwards from a contact at t*: positions at t* are chosen touching,
// velocities at random (sometimes in the contact plane, sometimes zero for some points), and
// the start and end positions follow.
class CcdSweep : public ::testing::Test {
 protected:
  std::mt19937 rng{2024};
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  Vec3 random_vec(double s) { return Vec3(uniform(-s, s), uniform(-s, s), uniform(-s, s)); }
  // Barycentric coordinates inside, on an edge (one zero) or at a vertex (two zeros).
  Vec3 barycentric() {
    int kind = static_cast<int>(rng() % 3);
    Vec3 w(uniform(0, 1), uniform(0, 1), uniform(0, 1));
    if (kind >= 1) w[rng() % 3] = 0;
    if (kind == 2) {
      w.setZero();
      w[rng() % 3] = 1;
    }
    return w / w.sum();
  }
};

TEST_F(CcdSweep, VertexFaceNeverMissesAConstructedContact) {
  int grazing = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double t_star = uniform(0, 1);
    Vec3 a = random_vec(1), b = random_vec(1), c = random_vec(1);
    if ((b - a).cross(c - a).norm() < 1e-2) continue;
    Vec3 w = barycentric();
    Vec3 p = w[0] * a + w[1] * b + w[2] * c;
    Vec3 n = (b - a).cross(c - a).normalized();
    Vec3 va = random_vec(1), vb = random_vec(1), vc = random_vec(1), vp = random_vec(1);
    if (trial % 4 == 1) {  // grazing: the point moves in the triangle's plane
      vp -= vp.dot(n) * n;
      va -= va.dot(n) * n;
      vb -= vb.dot(n) * n;
      vc -= vc.dot(n) * n;
      ++grazing;
    }
    if (trial % 4 == 2) va = vb = vc = Vec3::Zero();  // static triangle
    auto start = [&](const Vec3& x, const Vec3& v) { return Vec3(x - t_star * v); };
    auto end = [&](const Vec3& x, const Vec3& v) { return Vec3(x + (1 - t_star) * v); };
    Impact r = vertex_face_ccd(start(p, vp), end(p, vp), start(a, va), end(a, va), start(b, vb), end(b, vb), start(c, vc),
                               end(c, vc), 1e-9);
    ASSERT_TRUE(r.hit) << "trial " << trial << " t* " << t_star << " w " << w.transpose();
    ASSERT_LE(r.t, t_star + 1e-9) << "trial " << trial;
  }
  EXPECT_GT(grazing, 500);
}

TEST_F(CcdSweep, EdgeEdgeNeverMissesAConstructedContact) {
  for (int trial = 0; trial < 3000; ++trial) {
    const double t_star = uniform(0, 1);
    Vec3 q = random_vec(1);
    Vec3 u = random_vec(1), v = random_vec(1);
    if (trial % 5 == 3) v = u * uniform(0.5, 2) + 1e-7 * random_vec(1);  // nearly parallel
    // Contact at parameters s and r along each edge, endpoints included.
    double s = trial % 7 == 0 ? 0.0 : uniform(0, 1), r = trial % 11 == 0 ? 1.0 : uniform(0, 1);
    Vec3 a = q - s * u, b = q + (1 - s) * u, c = q - r * v, d = q + (1 - r) * v;
    Vec3 va = random_vec(1), vb = random_vec(1), vc = random_vec(1), vd = random_vec(1);
    if (trial % 5 == 4) vb = va, vd = vc;  // rigid translations
    auto start = [&](const Vec3& x, const Vec3& vel) { return Vec3(x - t_star * vel); };
    auto end = [&](const Vec3& x, const Vec3& vel) { return Vec3(x + (1 - t_star) * vel); };
    // eta 1e-6 of the unit scale: for edges 1e-7 from parallel the closest points lose digits
    // (the distance error grows like machine epsilon over the angle squared, 2e-9 here).
    Impact hit = edge_edge_ccd(start(a, va), end(a, va), start(b, vb), end(b, vb), start(c, vc), end(c, vc), start(d, vd),
                               end(d, vd), 1e-6);
    ASSERT_TRUE(hit.hit) << "trial " << trial << " t* " << t_star << " s " << s << " r " << r << "\n"
                         << start(a, va).transpose() << " | " << end(a, va).transpose() << "\n"
                         << start(b, vb).transpose() << " | " << end(b, vb).transpose() << "\n"
                         << start(c, vc).transpose() << " | " << end(c, vc).transpose() << "\n"
                         << start(d, vd).transpose() << " | " << end(d, vd).transpose();
    // Reported no later than the contact, up to the root's precision: within 1e-13 in t where
    // the cubic crosses cleanly, within 1e-6 where it is nearly flat (nearly parallel edges).
    ASSERT_LE(hit.t, t_star + (trial % 5 == 3 ? 1e-6 : 1e-9)) << "trial " << trial << " late by " << hit.t - t_star;
  }
}

TEST_F(CcdSweep, SeparatedMotionIsNotReported) {
  // Everything stays on either side of the plane z = 0.5 (triangle below, point above).
  for (int trial = 0; trial < 1000; ++trial) {
    Vec3 a0 = random_vec(1), b0 = random_vec(1), c0 = random_vec(1), a1 = random_vec(1), b1 = random_vec(1), c1 = random_vec(1);
    for (Vec3* x : {&a0, &b0, &c0, &a1, &b1, &c1}) x->z() = uniform(-1, 0.4);
    Vec3 p0 = random_vec(1), p1 = random_vec(1);
    p0.z() = uniform(0.6, 1.5);
    p1.z() = uniform(0.6, 1.5);
    EXPECT_FALSE(vertex_face_ccd(p0, p1, a0, a1, b0, b1, c0, c1, 1e-9).hit) << "trial " << trial;
  }
}

}  // namespace
}  // namespace vdc
