// Occlusion in the view factor (view.occlusion): what is hidden behind bodies and opaque cloth
// takes v_occluded, ramping over the erosion margin at the occluder's outline; eq. 4 refines it
// before an occluder moves away; the inside of a garment nothing hides keeps full resolution.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "scene/body.hpp"
#include "scene/figure.hpp"
#include "scene/joint_names.hpp"
#include "view/depth_cache.hpp"
#include "view/depth_image.hpp"
#include "view/view_factor.hpp"
#include "support/front_camera.hpp"
#include "support/occluders.hpp"

namespace vdc {
namespace {

using test::front_camera;
using test::sphere_band;
using test::wall;

// A small triangle facing the camera (+z) with its first corner at p.
Triangle facing_at(const Vec3& p, double r = 0.004) { return {p, Vec3(p + Vec3(r, 0, 0)), Vec3(p + Vec3(0, r, 0))}; }

// Its mirror image, turned away from the camera.
Triangle turned_away_at(const Vec3& p, double r = 0.004) { return {p, Vec3(p + Vec3(0, r, 0)), Vec3(p + Vec3(r, 0, 0))}; }

ViewParams occluding() {
  ViewParams p;
  p.occlusion = true;
  p.v_back = 0.2;
  p.v_occluded = 0.3;  // apart from v_back, to tell which one a face took
  return p;
}

double occluded_factor(const Triangle& t, const ViewParams& p, const DepthImage& image) {
  return face_view(Frustum(front_camera()), t[0], t[1], t[2], p, &image).factor;
}

TEST(Occlusion, ASheetBehindAWallTakesTheHiddenFactor) {
  const ViewParams p = occluding();
  const DepthImage image(front_camera(), wall(), p.occlusion_scale, p.occlusion_erosion);
  const Triangle behind = facing_at(Vec3(0.1, 0.2, -0.5));
  EXPECT_DOUBLE_EQ(occluded_factor(behind, p, image), p.v_occluded);
  const FaceView view = face_view(Frustum(front_camera()), behind[0], behind[1], behind[2], p, &image);
  EXPECT_EQ(view.hidden, 1.0);
  EXPECT_TRUE(view.front);
  EXPECT_DOUBLE_EQ(occluded_factor(turned_away_at(Vec3(0.1, 0.2, -0.5)), p, image), p.v_back);  // hidden and turned away
  EXPECT_EQ(occluded_factor(facing_at(Vec3(0.1, 0.2, 0.5)), p, image), 1.0);    // in front of the wall
  EXPECT_EQ(occluded_factor(facing_at(Vec3(0.1, 0.2, -0.01)), p, image), 1.0);  // behind it by less than occlusion_depth
  EXPECT_EQ(occluded_factor(facing_at(Vec3(2.5, 0.0, -0.5)), p, image), 1.0);   // beside it
  // Without occlusion the depth image changes nothing for a face that faces the camera.
  ViewParams seed = p;
  seed.occlusion = false;
  EXPECT_EQ(occluded_factor(behind, seed, image), 1.0);
}

// The outline's ramp: with an erosion of two pixels the depth image has three levels. The wall's
// right edge is at 640 + f / 5 pixels, f = 360 / tan(20 deg): an eighth of that is 104.72, so
// column 104 is the last the wall covers. A face on the ray through column c's centre, behind
// the wall: c = 105 is beside it (1), c = 104 hidden only unseroded (a third of the way down to
// v_occluded), 103 hidden at erosions 0 and 1 (two thirds), 102 at all three (v_occluded).
TEST(Occlusion, AFaceAtTheOutlineGetsTheRampNotAStep) {
  ViewParams p = occluding();
  p.occlusion_erosion = 2;
  const double f = 360 / std::tan(20 * M_PI / 180), scale = p.occlusion_scale;
  ASSERT_EQ(static_cast<int>(std::ceil(scale * (640 + f / 5) - 0.5)) - 1, 104);
  const DepthImage image(front_camera(), wall(), scale, p.occlusion_erosion);
  ASSERT_EQ(image.levels(), 3);
  auto behind_column = [&](int column) {
    const double depth = 5.5;  // z = -0.5
    return facing_at(Vec3(((column + 0.5) / scale - 640) / f * depth, 0.05, -0.5), 1e-4);
  };
  const double step = (1 - p.v_occluded) / 3;
  EXPECT_DOUBLE_EQ(occluded_factor(behind_column(105), p, image), 1.0);
  EXPECT_DOUBLE_EQ(occluded_factor(behind_column(104), p, image), 1 - step);
  EXPECT_DOUBLE_EQ(occluded_factor(behind_column(103), p, image), 1 - 2 * step);
  EXPECT_DOUBLE_EQ(occluded_factor(behind_column(102), p, image), p.v_occluded);
  EXPECT_DOUBLE_EQ(occluded_factor(behind_column(60), p, image), p.v_occluded);
  // A face whose corners straddle the ramp takes the least hidden one's level.
  const Triangle across{behind_column(105)[0], behind_column(102)[0], Vec3(behind_column(102)[0] + Vec3(0, 0.01, 0))};
  EXPECT_DOUBLE_EQ(occluded_factor(across, p, image), 1.0);
}

// Eq. 4 with a moving occluder: the wall slides away towards -x at 1 m/s, the camera still. A
// face behind it near its right edge is hidden now and seen once the edge has passed: the first
// sample at or after that time gives the factor w(tau) = 1 - tau / T. Worked out by hand at the
// depth image's full size (0.5 cm a pixel at the wall): the face's right corner, x = 1 at 5.5 m,
// is in column floor(640 + f / 5.5); that column is uncovered once the edge's pixel
// 640 + f (1 - tau) / 5 is at or left of its centre.
TEST(Occlusion, AWallSlidingAwayRefinesTheFaceBeforehandAsEq4Prescribes) {
  ViewParams p = occluding();
  p.occlusion_scale = 1;
  p.occlusion_erosion = 0;
  const double frame = 0.04, speed = 1;
  CameraPath path(front_camera(), {{0.0, Vec3(0, 0, 5), Vec3(0, 0, 0), false}});
  const AnticipationWindow window(path, 0.0, frame, p);
  const Triangle t{Vec3(0.98, 0, -0.5), Vec3(1.0, 0, -0.5), Vec3(0.98, 0.02, -0.5)};
  const auto images = occlusion_images(window, [&](DepthImage& image, double tau) { image.draw(wall(-speed * tau)); }, p);
  ASSERT_EQ(images.size(), window.cameras.size());
  const double f = 360 / std::tan(20 * M_PI / 180);
  const double column = std::floor(640 + f * 1.0 / 5.5);
  const double seen_from = 1 - 5 * (column + 0.5 - 640) / f;  // tau at which the edge passes
  ASSERT_GT(seen_from, 0.0);
  ASSERT_LT(seen_from, p.anticipation * frame);
  double expected = p.v_occluded;
  for (std::size_t k = 0; k < window.offsets.size(); ++k)
    if (window.offsets[k] >= seen_from) {
      ASSERT_GT(window.offsets[k] - seen_from, 1e-6) << "the edge passes at a sample's time: choose another face";
      expected = std::max(p.v_occluded, 1 - window.offsets[k] / (p.anticipation * frame));
      break;
    }
  EXPECT_DOUBLE_EQ(occluded_factor(t, p, images.front()), p.v_occluded);
  EXPECT_DOUBLE_EQ(anticipated_view_factor(window, t[0], t[1], t[2], p, &images), expected);
  EXPECT_GT(expected, p.v_occluded + 0.1);  // seen within the window, refined before it is seen
  EXPECT_LT(expected, 1.0);
  // The wall held where it is hides the face over the whole window.
  const auto held = occlusion_images(window, [&](DepthImage& image, double) { image.draw(wall()); }, p);
  EXPECT_DOUBLE_EQ(anticipated_view_factor(window, t[0], t[1], t[2], p, &held), p.v_occluded);
}

// A ball of radius 0.5 at the origin. A cloth patch behind it facing the camera is hidden, as
// are the ball's own far side (turned away: v_back); its near side faces the camera (1).
TEST(Occlusion, BehindABallAndItsFarSide) {
  const ViewParams p = occluding();
  const std::vector<Triangle> ball = sphere_band(0.5, 0, M_PI);
  const DepthImage image(front_camera(), ball, p.occlusion_scale, p.occlusion_erosion);
  EXPECT_DOUBLE_EQ(occluded_factor(facing_at(Vec3(0.05, -0.1, -0.8)), p, image), p.v_occluded);
  EXPECT_EQ(occluded_factor(facing_at(Vec3(0.7, -0.1, -0.8)), p, image), 1.0);  // beside the ball's outline
  int far = 0, near = 0;
  for (const Triangle& t : ball) {
    const Vec3 c = (t[0] + t[1] + t[2]) / 3.0;
    if (c.z() < -0.3) {
      EXPECT_DOUBLE_EQ(occluded_factor(t, p, image), p.v_back) << c.transpose();
      ++far;
    }
    if (c.z() > 0.05) {
      EXPECT_EQ(occluded_factor(t, p, image), 1.0) << c.transpose();
      ++near;
    }
  }
  EXPECT_GT(far, 200);
  EXPECT_GT(near, 400);
}

// The project's figure standing with its legs apart (each thigh 12 degrees out), seen from the
// front at knee height, 4 m away: a patch 0.3 m behind the left knee is hidden by the leg; one in
// the gap between the knees is seen.
TEST(Occlusion, BehindALegAndBetweenTheLegsOfTheFigure) {
  ViewParams p = occluding();
  p.occlusion_scale = 0.5;
  const Skeleton skeleton = figure_skeleton();
  PoseKey apart;
  apart.rotation = {{"LeftUpLeg", Vec3(0, 0, 12)}, {"RightUpLeg", Vec3(0, 0, -12)}};
  const Motion motion = author_motion(skeleton, {apart}, 30, "legs apart");
  const Body body(motion, BodyParams{});
  const Pose pose = motion.frame_pose(0);
  const auto joints = motion.world(pose);
  const Vec3 knee = joints[static_cast<std::size_t>(*find_joint(skeleton, "LeftLeg"))].translation();
  ASSERT_GT(knee.x(), 0.1);  // the figure's left is +x
  const std::vector<Vec3> skin = body.skin(pose);
  std::vector<Triangle> triangles;
  for (const auto& face : body.rest_mesh().faces)
    triangles.push_back({skin[static_cast<std::size_t>(face[0].node)], skin[static_cast<std::size_t>(face[1].node)],
                         skin[static_cast<std::size_t>(face[2].node)]});
  // The gap between the legs at knee height: the innermost body points of either leg there.
  double left_inner = 1, right_inner = -1;
  for (const Vec3& x : skin)
    if (std::abs(x.y() - knee.y()) < 0.02) {
      if (x.x() > 0) left_inner = std::min(left_inner, x.x());
      else right_inner = std::max(right_inner, x.x());
    }
  ASSERT_GT(left_inner - right_inner, 0.1) << "no gap between the knees to look through";
  Camera camera = front_camera();
  camera.position = Vec3(0, knee.y(), knee.z() + 4);
  camera.target = Vec3(0, knee.y(), knee.z());
  const DepthImage image(camera, triangles, p.occlusion_scale, p.occlusion_erosion);
  const Frustum frustum(camera);
  const double behind = knee.z() - 0.3;
  const Triangle hidden = facing_at(Vec3(knee.x() - 0.005, knee.y(), behind), 0.01);
  const Triangle between = facing_at(Vec3(0.5 * (left_inner + right_inner) - 0.002, knee.y(), behind), 0.004);
  EXPECT_DOUBLE_EQ(face_view(frustum, hidden[0], hidden[1], hidden[2], p, &image).factor, p.v_occluded);
  EXPECT_EQ(face_view(frustum, between[0], between[1], between[2], p, &image).factor, 1.0);
}

// A camera inside a skirt (a tube of radius 0.4 around it, outer side out): every face in frame
// is turned away from the camera and nothing hides it, so all keep full resolution; the seed's
// rule gives them all v_back.
TEST(Occlusion, ACameraInsideASkirtSeesItsInsideAtFullResolution) {
  ViewParams p = occluding();
  Camera camera = front_camera();
  camera.position = Vec3(0, 0, 0);
  camera.target = Vec3(0, -1, 0.3);  // looking down into the skirt
  camera.up = Vec3(0, 0, 1);
  std::vector<Triangle> tube;
  const int sectors = 32, rows = 8;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < sectors; ++j) {
      auto at = [&](int r, int s) {
        const double phi = 2 * M_PI * s / sectors;
        return Vec3(0.4 * std::cos(phi), -0.1 - 0.1 * r, 0.4 * std::sin(phi));
      };
      // Outward: (down, around) ordering seen from outside.
      tube.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      tube.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  const DepthImage image(camera, tube, p.occlusion_scale, p.occlusion_erosion);
  const Frustum frustum(camera);
  ViewParams seed = p;
  seed.occlusion = false;
  int in_frame = 0;
  for (const Triangle& t : tube) {
    const Vec3 c = (t[0] + t[1] + t[2]) / 3.0;
    ASSERT_GT(area_normal(t[0], t[1], t[2]).dot(c - Vec3(0, c.y(), 0)), 0) << "not outward";
    const FaceView view = face_view(frustum, t[0], t[1], t[2], p, &image);
    if (view.distance > 0) continue;
    ++in_frame;
    EXPECT_EQ(view.factor, 1.0) << c.transpose();
    EXPECT_DOUBLE_EQ(face_view(frustum, t[0], t[1], t[2], seed).factor, p.v_back);
  }
  EXPECT_GT(in_frame, 100);
}

// The bodies' images are drawn once a sample time for all garment groups, whichever asks first
// and however many ask at once; each gets its own copy to add its garments to.
TEST(DepthCache, DrawsEachTimeOnceForAllWhoAskAndForgetsThePast) {
  DepthCache cache;
  std::atomic<int> drawn = 0;
  auto the_wall = [&] {
    ++drawn;
    return wall();
  };
  std::vector<std::thread> groups;
  std::vector<std::optional<DepthImage>> got(4);
  for (std::size_t g = 0; g < got.size(); ++g) groups.emplace_back([&, g] { got[g].emplace(cache.at(0, 0.1, front_camera(), 0.125, the_wall)); });
  for (auto& t : groups) t.join();
  EXPECT_EQ(drawn, 1);
  for (auto& image : got) {
    image->erode(1);
    EXPECT_TRUE(image->hidden(Vec3(0.1, 0.2, -0.5), 0.02));
  }
  DepthImage mine = cache.at(0, 0.1, front_camera(), 0.125, the_wall);
  mine.draw({facing_at(Vec3(1.2, 0, 1), 1.0)});  // added to the copy only
  mine.erode(0);
  const Vec3 behind_it(1.5, 0.2, 0.5);  // behind that square, beside the wall
  EXPECT_TRUE(mine.hidden(behind_it, 0.02));
  cache.at(0, 0.2, front_camera(), 0.125, the_wall);
  EXPECT_EQ(drawn, 2);
  EXPECT_EQ(cache.size(), 2u);
  cache.forget_before(0.15);
  EXPECT_EQ(cache.size(), 1u);
  cache.at(0, 0.1, front_camera(), 0.125, the_wall);
  EXPECT_EQ(drawn, 3);  // forgotten, drawn again
  DepthImage again = cache.at(0, 0.1, front_camera(), 0.125, the_wall);
  again.erode(0);
  EXPECT_FALSE(again.hidden(behind_it, 0.02));  // the square was added to `mine` only
  EXPECT_EQ(drawn, 3);
}

}  // namespace
}  // namespace vdc
