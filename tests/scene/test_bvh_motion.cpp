// BVH motion files: a hand-built hierarchy with known transforms, round trip through the
// writer, interpolation between frames, errors with their lines, and CMU motion capture files
// (Debian's assimp-testmodels) checked against their headers and a hand computation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/error.hpp"
#include "scene/bvh_motion.hpp"

namespace vdc {
namespace {

// Root at (1, 2, 3) turned 90 degrees about Z; its child one unit along x turned 90 degrees about
// X (then 0 about Y); an end site one unit along y.
const char* kChain = R"(HIERARCHY
ROOT Root
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Child
  {
    OFFSET 1 0 0
    CHANNELS 3 Xrotation Yrotation Zrotation
    End Site
    {
      OFFSET 0 1 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.5
1 2 3 90 0 0 90 0 0
1 2 3 0 0 0 0 0 0
)";

TEST(BvhMotion, HandBuiltChainHasTheExpectedWorldPositions) {
  Motion m = parse_bvh(kChain, "chain.bvh");
  ASSERT_EQ(m.skeleton.joints.size(), 3u);
  EXPECT_EQ(m.skeleton.num_channels, 9);
  EXPECT_EQ(m.frames.size(), 2u);
  EXPECT_EQ(m.frame_time, 0.5);
  EXPECT_TRUE(m.skeleton.joints[2].end_site);
  const auto w = m.world(m.frame_pose(0));
  // Child: (1,2,3) + Rz(90) (1,0,0) = (1,3,3). End: child + Rz(90) Rx(90) (0,1,0) = (1,3,3) + Rz(90) (0,0,1) = (1,3,4).
  EXPECT_LT((w[1].translation() - Vec3(1, 3, 3)).norm(), 1e-12);
  EXPECT_LT((w[2].translation() - Vec3(1, 3, 4)).norm(), 1e-12);
  // Halfway between the frames: rotations halfway (45 degrees about Z at the root).
  const auto h = m.world(m.pose_at(0.25));
  const Vec3 child = Vec3(1, 2, 3) + Vec3(std::cos(M_PI / 4), std::sin(M_PI / 4), 0);
  EXPECT_LT((h[1].translation() - child).norm(), 1e-12);
  // Held outside the motion.
  EXPECT_LT((m.world(m.pose_at(9.0))[2].translation() - Vec3(2, 3, 3)).norm(), 1e-12);
  // Retimed: twice as fast, starting at 1 s.
  MotionClip clip{&m, 1.0, 2.0};
  EXPECT_LT((m.world(clip.pose_at(1.125))[1].translation() - child).norm(), 1e-12);
}

TEST(BvhMotion, WholeFramesBeyondTheHeaderCountAreIgnored) {
  Motion m = parse_bvh(std::string(kChain) + "5 5 5 0 0 0 0 0 0\n", "chain.bvh");
  EXPECT_EQ(m.frames.size(), 2u);
}

// A name is the rest of its line (Biped's "Bip01 L Thigh"), up to a brace on the same line.
TEST(BvhMotion, NamesRunToTheEndOfTheirLine) {
  std::string text = kChain;
  text.replace(text.find("ROOT Root\n{"), 11, "ROOT Bip01 {");
  text.replace(text.find("JOINT Child"), 11, "JOINT Bip01 L  Thigh");
  const Motion m = parse_bvh(text, "biped.bvh");
  ASSERT_EQ(m.skeleton.joints.size(), 3u);
  EXPECT_EQ(m.skeleton.joints[0].name, "Bip01");
  EXPECT_EQ(m.skeleton.joints[1].name, "Bip01 L Thigh");
  EXPECT_EQ(m.skeleton.joints[2].name, "Bip01 L Thigh_end");
  EXPECT_EQ(m.frames, parse_bvh(kChain, "chain.bvh").frames);
}

TEST(BvhMotion, WriterRoundTrips) {
  Motion m = parse_bvh(kChain, "chain.bvh");
  const std::string path = (std::filesystem::temp_directory_path() / ("vdcloth_chain_" + std::to_string(::getpid()) + ".bvh")).string();
  ASSERT_TRUE(write_bvh(m, path));
  Motion back = read_bvh(path);
  std::filesystem::remove(path);
  ASSERT_EQ(back.skeleton.joints.size(), m.skeleton.joints.size());
  for (std::size_t j = 0; j < m.skeleton.joints.size(); ++j) {
    EXPECT_EQ(back.skeleton.joints[j].name, m.skeleton.joints[j].name);
    EXPECT_EQ(back.skeleton.joints[j].parent, m.skeleton.joints[j].parent);
    EXPECT_EQ(back.skeleton.joints[j].offset, m.skeleton.joints[j].offset);
    EXPECT_EQ(back.skeleton.joints[j].channels, m.skeleton.joints[j].channels);
  }
  EXPECT_EQ(back.frames, m.frames);
  EXPECT_EQ(back.frame_time, m.frame_time);
}

TEST(BvhMotion, MalformedFilesNameTheLine) {
  struct Case {
    std::string text, expect;
  };
  std::string chain = kChain;
  std::vector<Case> cases = {
      {std::regex_replace(chain, std::regex("Xrotation Yrotation Zrotation"), "Xrotation Wrotation Zrotation"), "line 9"},
      {std::regex_replace(chain, std::regex("OFFSET 1 0 0"), "OFFSET 1 zero 0"), "line 8"},
      {std::regex_replace(chain, std::regex("Frames: 2"), "Frames: 3"), "file ends in frame 3"},
      {std::regex_replace(chain, std::regex("1 2 3 0 0 0 0 0 0"), "1 2 3 0 0 0 0 0 0 7"), "more values"},
      {std::regex_replace(chain, std::regex("Frame Time: 0.5"), "Frame Time: 0"), "line 18"},
      {chain + "1 2 x\n", "line 21"},
      {"HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n", "file ends"},
  };
  // A hierarchy nested 100,000 joints deep is refused at the 257th level, not read until the
  // stack runs out.
  std::string deep = "HIERARCHY\nROOT j\n{\nOFFSET 0 0 0\n";
  for (int k = 0; k < 100000; ++k) deep += "JOINT j\n{\nOFFSET 0 0 1\n";
  cases.push_back({deep, "nested more than 256 levels deep"});
  cases.push_back({deep, "line " + std::to_string(5 + 3 * 256 + 1)});  // the '{' of joint 257 (its JOINT on line 5 + 3 x 256)
  for (const auto& c : cases) {
    try {
      parse_bvh(c.text, "bad.bvh");
      ADD_FAILURE() << "accepted: " << c.expect;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.bvh"), std::string::npos) << e.what();
    }
  }
}

const char* kCmuDir = "/usr/share/assimp/models/BVH";

TEST(BvhMotion, CmuFilesMatchTheirHeaders) {
  int checked = 0;
  for (const char* name : {"01_01.bvh", "01_03.bvh", "Boxing_Toes.bvh"}) {
    const std::string path = std::string(kCmuDir) + "/" + name;
    ASSERT_TRUE(std::filesystem::exists(path)) << path << " (Debian package assimp-testmodels)";
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    // The header, read independently: joints (ROOT, JOINT, End Site), frames, frame time.
    auto count = [&](const std::regex& re) { return std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()); };
    const auto joints = count(std::regex(R"(\b(ROOT|JOINT)\s)")) + count(std::regex(R"(End Site)"));
    std::smatch frames, frame_time;
    ASSERT_TRUE(std::regex_search(text, frames, std::regex(R"(Frames:\s*(\d+))")));
    ASSERT_TRUE(std::regex_search(text, frame_time, std::regex(R"(Frame Time:\s*([0-9.eE+-]+))")));
    Motion m = read_bvh(path);
    EXPECT_EQ(static_cast<long>(m.skeleton.joints.size()), joints) << name;
    EXPECT_EQ(m.frames.size(), std::stoul(frames[1])) << name;
    EXPECT_DOUBLE_EQ(m.frame_time, std::stod(frame_time[1])) << name;
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}

TEST(BvhMotion, CmuJointPositionMatchesAHandComputation) {
  Motion m = read_bvh(std::string(kCmuDir) + "/01_01.bvh");
  // Frame 1: Hips at (9.3722, 17.8693, -17.3198), unrotated; LHipJoint offset 0, unrotated;
  // LeftUpLeg offset (1.36306, -1.79463, 0.83929) with Zrotation -17; LeftLeg offset
  // (2.44811, -6.72613, 0). LeftLeg = hips + upleg offset + Rz(-17) leg offset.
  const double a = -17 * M_PI / 180, x = 2.44811, y = -6.72613;
  const Vec3 expected = Vec3(9.3722, 17.8693, -17.3198) + Vec3(1.36306, -1.79463, 0.83929) +
                        Vec3(x * std::cos(a) - y * std::sin(a), x * std::sin(a) + y * std::cos(a), 0);
  int leg = -1;
  for (std::size_t j = 0; j < m.skeleton.joints.size(); ++j)
    if (m.skeleton.joints[j].name == "LeftLeg") leg = static_cast<int>(j);
  ASSERT_GE(leg, 0);
  ASSERT_EQ(m.frames[0][9], -17);  // the LeftUpLeg Zrotation channel, as read above
  const auto w = m.world(m.frame_pose(0));
  EXPECT_LT((w[static_cast<std::size_t>(leg)].translation() - expected).norm(), 1e-9);
}

}  // namespace
}  // namespace vdc
