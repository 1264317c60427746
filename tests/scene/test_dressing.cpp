// A character's dressing pose, a capture's leading reference frames and the pre-roll that moves
// the figure from the one into the shot's first pose.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/bvh_motion.hpp"
#include "scene/character.hpp"
#include "scene/dressing.hpp"
#include "scene/figure.hpp"

namespace vdc {
namespace {

// The project's figure, keyed at 120 frames a second as CMU's captures are: a T-pose (arms
// raised 50 degrees to horizontal) in the first frame, the arms down at rest from the next, then
// a slow step to the side.
Motion capture_with_reference_frame() {
  const Skeleton figure = figure_skeleton();
  PoseKey t_pose;
  t_pose.rotation = {{"LeftArm", Vec3(0, 0, 50)}, {"RightArm", Vec3(0, 0, -50)}};
  Motion tee = author_motion(figure, {t_pose}, 120, "tee");
  PoseKey rest, step;
  step.time = 2;
  step.root = Vec3(0.3, 0, 0);
  Motion walk = author_motion(figure, {rest, step}, 120, "walk");
  walk.frames.insert(walk.frames.begin(), tee.frames.front());
  return walk;
}

TEST(Dressing, ACapturesLeadingTPoseIsAReferenceFrame) {
  const Motion capture = capture_with_reference_frame();
  // From the T-pose the hands fall 2 x 0.62 sin(25 deg) = 0.52 m in a 120th of a second: 63 m/s.
  EXPECT_NEAR(largest_joint_distance(capture, capture.frame_pose(0), capture.frame_pose(1)), 2 * 0.62 * std::sin(25 * M_PI / 180), 1e-9);
  EXPECT_EQ(leading_reference_frames(capture), 1);
  // The project's motions start at rest and move smoothly.
  for (const char* name : {"dance", "karate"})
    EXPECT_EQ(leading_reference_frames(read_bvh(std::string(VDCLOTH_SOURCE_DIR) + "/motions/" + name + ".bvh")), 0) << name;
  // A motion of jumps only keeps its last frame.
  Motion jumps = capture;
  jumps.frames = {capture.frames[0], capture.frames[1], capture.frames[0]};
  EXPECT_EQ(leading_reference_frames(jumps), 2);
}

TEST(Dressing, TheDressingPoseIsTheReferenceFrameOrTheRestPoseStoodWhereTheShotStarts) {
  const Motion capture = capture_with_reference_frame();
  const Pose tee = dressing_pose(capture, 1, 1);
  const Pose frame0 = capture.frame_pose(0);
  for (std::size_t j = 0; j < tee.rotation.size(); ++j) {
    EXPECT_TRUE(tee.rotation[j].isApprox(frame0.rotation[j], 1e-15)) << j;
    EXPECT_EQ(tee.translation[j], frame0.translation[j]) << j;
  }
  // Without reference frames: the rest pose, moved to where the last frame stands (0.3 m to the
  // side, lowest joint as high).
  const Pose stood = dressing_pose(capture, 0, 241);
  const auto world = capture.world(stood), there = capture.world(capture.frame_pose(241));
  EXPECT_NEAR(world.front().translation().x(), 0.3, 1e-12);
  EXPECT_NEAR(world.front().translation().z(), there.front().translation().z(), 1e-12);
  double lowest = 1e9, lowest_there = 1e9;
  for (std::size_t j = 0; j < world.size(); ++j) {
    lowest = std::min(lowest, world[j].translation().y());
    lowest_there = std::min(lowest_there, there[j].translation().y());
    EXPECT_TRUE(stood.rotation[j].isApprox(Eigen::Quaterniond::Identity(), 1e-15)) << j;
  }
  EXPECT_NEAR(lowest, lowest_there, 1e-12);
}

TEST(Dressing, ThePrerollEasesFromTheDressingPoseIntoTheFirstPose) {
  EXPECT_EQ(preroll_ease(0), 0);
  EXPECT_EQ(preroll_ease(1), 1);
  EXPECT_DOUBLE_EQ(preroll_ease(0.5), 0.5);
  EXPECT_EQ(preroll_ease(-3), 0);
  EXPECT_EQ(preroll_ease(4), 1);
  // It starts and ends at rest: its derivative 6u(1 - u) is 0 at both ends.
  const double h = 1e-6;
  EXPECT_NEAR((preroll_ease(h) - preroll_ease(0)) / h, 0, 1e-5);
  EXPECT_NEAR((preroll_ease(1) - preroll_ease(1 - h)) / h, 0, 1e-5);
  EXPECT_NEAR((preroll_ease(0.25 + h) - preroll_ease(0.25 - h)) / (2 * h), 6 * 0.25 * 0.75, 1e-8);

  Motion walk = capture_with_reference_frame();
  const Pose tee = walk.frame_pose(0);
  walk.frames.erase(walk.frames.begin());
  const Character character(walk, BodyParams{1.0, 0.05, 0.04}, Transform{}, 0.0, 1.0, std::nullopt, Dressing{tee, 2.0});
  auto index = [&](const std::string& name) {
    for (std::size_t j = 0; j < walk.skeleton.joints.size(); ++j)
      if (walk.skeleton.joints[j].name == name) return static_cast<int>(j);
    return -1;
  };
  const int tip = index("LeftHand_end"), arm = index("LeftArm");
  ASSERT_GE(tip, 0);
  ASSERT_GE(arm, 0);
  auto hand = [&](double t) -> Vec3 { return character.joint_transform(tip, t).translation(); };
  const Vec3 raised = walk.world(tee)[static_cast<std::size_t>(tip)].translation();
  const Vec3 down = walk.world(walk.frame_pose(0))[static_cast<std::size_t>(tip)].translation();
  EXPECT_LT((hand(-5) - raised).norm(), 1e-12);  // before the pre-roll: held in the dressing pose
  EXPECT_LT((hand(-2) - raised).norm(), 1e-12);
  EXPECT_LT((hand(0) - down).norm(), 1e-12);     // at the shot's start: its first pose
  // Half way (ease 0.5), the arm has turned half of its 50 degrees about the shoulder.
  const Vec3 shoulder = walk.world(tee)[static_cast<std::size_t>(arm)].translation();
  const Vec3 a = raised - shoulder, b = down - shoulder, m = hand(-1) - shoulder;
  EXPECT_NEAR(std::acos(a.normalized().dot(m.normalized())), 25 * M_PI / 180, 1e-9);
  EXPECT_NEAR(std::acos(b.normalized().dot(m.normalized())), 25 * M_PI / 180, 1e-9);
  // Without a pre-roll the character is its clip at every time.
  const Character plain(walk, BodyParams{1.0, 0.05, 0.04}, Transform{}, 0.0, 1.0);
  EXPECT_LT((plain.joint_transform(tip, -1).translation() - down).norm(), 1e-12);
  EXPECT_EQ(plain.preroll(), 0);
}

}  // namespace
}  // namespace vdc
