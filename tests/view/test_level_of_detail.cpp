// Physics level of detail: the most pixels a metre of a ball spans on screen, and when no camera
// resolves a garment's folds, against figures worked out by hand for front_camera()'s lens.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "view/level_of_detail.hpp"
#include "support/front_camera.hpp"

namespace vdc {
namespace {

using test::front_camera;

// front_camera()'s lens (40 degrees, 1280 x 720) seeing to 100 m, at (0, 0, 5) looking down -z.
Camera far_seeing() {
  Camera c = front_camera();
  c.far = 100;
  return c;
}

// f sqrt(1 + tx^2 + ty^2) for that lens: f = 360 / tan(20 deg) = 989.09 px, ty = tan(20 deg),
// tx = ty 16 / 9: 1231.9 px a metre at a depth of 1 m.
double corner_focal() {
  const double ty = std::tan(20 * M_PI / 180), tx = ty * 16 / 9;
  return 360 / ty * std::sqrt(1 + tx * tx + ty * ty);
}

TEST(LevelOfDetail, TheBallsBoundIsThePinholesStretchAtItsNearestDepth) {
  const Camera c = far_seeing();
  const Frustum frustum(c);
  EXPECT_NEAR(corner_focal(), 1231.9, 0.1);
  // Centre 15 m in front, 0.3 m right and 0.2 m down; radius 1: nearest depth 14 m.
  const Vec3 centre(0.3, -0.2, -10);
  const double bound = most_pixels_per_metre(c, frustum, centre, 1.0);
  EXPECT_NEAR(bound, corner_focal() / 14, 1e-9);
  // Every point of the ball in frame spans at most that (10,000 random points).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int in_frame = 0;
  double most = 0;
  for (int k = 0; k < 10000; ++k) {
    Vec3 d(u(rng), u(rng), u(rng));
    if (d.norm() > 1) continue;
    const Vec3 p = centre + d;
    double depth = 0;
    const Vec2 px = c.project(p, &depth);
    if (px.x() < 0 || px.x() > c.width || px.y() < 0 || px.y() > c.height) continue;
    ++in_frame;
    most = std::max(most, c.pixels_per_metre(p));
  }
  EXPECT_GT(in_frame, 4000);
  EXPECT_LE(most, bound);
  EXPECT_GT(most, 0.78 * bound);  // its nearest points lie near the axis: f / 14 = 70.6 px against 88.0
  // Wholly behind the camera, or beside the frame: nothing in frame.
  EXPECT_EQ(most_pixels_per_metre(c, frustum, Vec3(0, 0, 8), 1.0), 0.0);
  EXPECT_EQ(most_pixels_per_metre(c, frustum, Vec3(30, 0, -10), 1.0), 0.0);
  // Straddling the near plane: the near plane's depth.
  EXPECT_NEAR(most_pixels_per_metre(c, frustum, Vec3(0, 0, 4.5), 1.0), corner_focal() / c.near, 1e-6);
}

// With l_min 4 and folds of 2 cm a garment is beyond resolution where 0.02 f' / z < 2, z >
// 12.319 m (f' = corner_focal()).
TEST(LevelOfDetail, AGarmentIsBeyondResolutionWhereItsFoldsStayUnderHalfTheFloor) {
  const CameraPath still(far_seeing(), {{0.0, Vec3(0, 0, 5), Vec3::Zero(), false}});
  ViewParams p;
  p.l_min = 4;
  p.fold_length = 0.02;
  const std::vector<AnticipationWindow> windows{AnticipationWindow(still, 0.0, 0.04, p)};
  auto at_depth = [](double z, double speed = 0) { return GarmentReach{Vec3(0, 0, 5 - z), 0.5, speed}; };
  EXPECT_NEAR(0.02 * corner_focal() / 2, 12.319, 1e-3);
  EXPECT_TRUE(beyond_resolution(windows, p, at_depth(12.85), 0.2));    // nearest 12.35 m
  EXPECT_FALSE(beyond_resolution(windows, p, at_depth(12.80), 0.2));   // nearest 12.30 m
  // Moving at 10 m/s: within the window's 0.2 s (its last sample 0.19 s on) it may come 1.9 m nearer.
  EXPECT_FALSE(beyond_resolution(windows, p, at_depth(14, 10), 0.2));
  EXPECT_TRUE(beyond_resolution(windows, p, at_depth(14.8, 10), 0.2));
  // No floor, no folds: never.
  ViewParams off = p;
  off.l_min = 0;
  EXPECT_FALSE(beyond_resolution(windows, off, at_depth(90), 0.2));
  off = p;
  off.fold_length = 0;
  EXPECT_FALSE(beyond_resolution(windows, off, at_depth(90), 0.2));
  // A ceiling: a 0.2 m edge at the nearest 19.5 m spans 12.6 px.
  ViewParams ceiling = p;
  ceiling.l_max = 13;
  EXPECT_TRUE(beyond_resolution(windows, ceiling, at_depth(20), 0.2));
  ceiling.l_max = 12;
  EXPECT_FALSE(beyond_resolution(windows, ceiling, at_depth(20), 0.2));
}

TEST(LevelOfDetail, ACutOrASecondCameraThatResolvesTheGarmentKeepsItsLevel) {
  ViewParams p;
  p.l_min = 4;
  const GarmentReach reach{Vec3(0, 0, -15), 0.5, 0.0};  // 20 m from the first camera
  // A cut to a camera 3 m away 0.1 s on, within the window (5 frames of 0.04 s), or 1 s on.
  const CameraPath cut_soon(far_seeing(), {{0.0, Vec3(0, 0, 5), Vec3::Zero(), false}, {0.1, Vec3(0, 0, -12), Vec3(0, 0, -15), true}});
  const CameraPath cut_later(far_seeing(), {{0.0, Vec3(0, 0, 5), Vec3::Zero(), false}, {1.0, Vec3(0, 0, -12), Vec3(0, 0, -15), true}});
  EXPECT_FALSE(beyond_resolution({AnticipationWindow(cut_soon, 0.0, 0.04, p)}, p, reach, 0.2));
  EXPECT_TRUE(beyond_resolution({AnticipationWindow(cut_later, 0.0, 0.04, p)}, p, reach, 0.2));
  // A second camera 3 m away all along.
  const CameraPath far(far_seeing(), {{0.0, Vec3(0, 0, 5), Vec3::Zero(), false}});
  const CameraPath near(far_seeing(), {{0.0, Vec3(0, 0, -12), Vec3(0, 0, -15), false}});
  EXPECT_TRUE(beyond_resolution({AnticipationWindow(far, 0.0, 0.04, p)}, p, reach, 0.2));
  EXPECT_FALSE(beyond_resolution({AnticipationWindow(far, 0.0, 0.04, p), AnticipationWindow(near, 0.0, 0.04, p)}, p, reach, 0.2));
}

TEST(LevelOfDetail, TheReachHoldsEveryNodeAndTheFastestSpeed) {
  const GarmentReach r = garment_reach({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0)}, {Vec3(0, 3, 4), Vec3(1, 0, 0), Vec3::Zero()});
  EXPECT_EQ(r.centre, Vec3(1, 0.5, 0));
  EXPECT_NEAR(r.radius, std::sqrt(1.25), 1e-15);
  EXPECT_EQ(r.speed, 5.0);
}

}  // namespace
}  // namespace vdc
