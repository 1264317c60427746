// Humanoids recognised by shape: the project's figure, CMU's captures and a capture of the
// Collar-Shoulder-Elbow-Wrist scheme (assimp-testmodels) give each landmark the joint a person
// would; the same skeletons with meaningless names and their joints in another order give the
// same joints and mirror alike; Biped's tree and twist joints are recognised; a skeleton with
// one leg is not a humanoid, and says so.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "scene/bvh_motion.hpp"
#include "scene/figure.hpp"
#include "scene/humanoid.hpp"
#include "scene/joint_names.hpp"
#include "support/humanoid_skeletons.hpp"

namespace vdc {
namespace {

using test::biped_skeleton;
using test::renamed_and_reordered;
using test::twist_skeleton;

const char* kCaptures = "/usr/share/assimp/models/BVH/";

// The name of the joint of `skeleton` each landmark is on ("-" for none), in landmark_names' order.
std::vector<std::string> landmarks_named(const Skeleton& skeleton) {
  const HumanoidRecognition r = recognise_humanoid(skeleton);
  EXPECT_TRUE(r.humanoid) << r.why_not;
  std::vector<std::string> out;
  if (!r.humanoid) return out;
  for (const std::string& name : landmark_names()) {
    const int j = *landmark_joint(*r.humanoid, name);
    out.push_back(j < 0 ? "-" : skeleton.joints[static_cast<std::size_t>(j)].name);
  }
  return out;
}

std::vector<std::string> expected(std::vector<std::string> trunk, const std::array<std::vector<std::string>, 2>& sides) {
  for (const auto& side : sides) trunk.insert(trunk.end(), side.begin(), side.end());
  return trunk;
}

TEST(Humanoid, TheProjectsFigureIsNamedAsItsLandmarks) {
  const Skeleton figure = figure_skeleton();
  std::vector<std::string> own = landmark_names();
  EXPECT_EQ(landmarks_named(figure), own);
  const Humanoid h = *recognise_humanoid(figure).humanoid;
  auto part = [&](const char* name) { return h.parts[static_cast<std::size_t>(*find_joint(figure, name))]; };
  EXPECT_EQ(part("Hips"), BodyPart::Hips);
  EXPECT_EQ(part("Chest"), BodyPart::Spine);
  EXPECT_EQ(part("RightShoulder"), BodyPart::Clavicle);
  EXPECT_EQ(part("RightHand"), BodyPart::Hand);
  EXPECT_EQ(part("LeftLeg"), BodyPart::Shin);
  EXPECT_EQ(part("LeftToe"), BodyPart::Toe);
}

TEST(Humanoid, CapturesOfOtherSchemesGiveEachLandmarkItsJoint) {
  for (const char* file : {"01_01.bvh", "01_03.bvh", "Boxing_Toes.bvh"})
    ASSERT_TRUE(std::filesystem::exists(std::string(kCaptures) + file)) << file << " (Debian package assimp-testmodels)";
  const std::vector<std::string> cmu = expected(
      {"Hips", "LowerBack", "Spine1", "Neck", "Head"},
      {{{"LeftShoulder", "LeftArm", "LeftForeArm", "LeftHand", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"},
        {"RightShoulder", "RightArm", "RightForeArm", "RightHand", "RightUpLeg", "RightLeg", "RightFoot", "RightToeBase"}}});
  EXPECT_EQ(landmarks_named(read_bvh(std::string(kCaptures) + "01_01.bvh").skeleton), cmu);
  EXPECT_EQ(landmarks_named(read_bvh(std::string(kCaptures) + "01_03.bvh").skeleton), cmu);
  // Here LeftShoulder is the upper arm: the project's LeftShoulder (a clavicle) is LeftCollar.
  const std::vector<std::string> boxing =
      expected({"Hips", "Ab", "Chest", "Neck", "Head"}, {{{"LeftCollar", "LeftShoulder", "LeftElbow", "LeftWrist", "LeftHip", "LeftKnee", "LeftAnkle", "LeftToes"},
                                                           {"RightCollar", "RightShoulder", "RightElbow", "RightWrist", "RightHip", "RightKnee", "RightAnkle", "RightToes"}}});
  EXPECT_EQ(landmarks_named(read_bvh(std::string(kCaptures) + "Boxing_Toes.bvh").skeleton), boxing);
  // CMU's hip joints lead to the thighs; its hands end in fingers.
  const Skeleton s = read_bvh(std::string(kCaptures) + "01_01.bvh").skeleton;
  const Humanoid h = *recognise_humanoid(s).humanoid;
  auto part = [&](const char* name) { return h.parts[static_cast<std::size_t>(*find_joint(s, name))]; };
  EXPECT_EQ(part("LHipJoint"), BodyPart::HipJoint);
  EXPECT_EQ(part("LeftFingerBase"), BodyPart::Finger);
  EXPECT_EQ(part("RThumb"), BodyPart::Finger);
  EXPECT_EQ(part("Neck1"), BodyPart::Neck);
}

// Every motion the project ships or tests with, renamed j0, j1, ... and its children listed last
// first, gives each landmark the joint it gave, and each joint its part.
TEST(Humanoid, NamesAndTheOrderOfJointsDecideNothing) {
  std::vector<std::pair<std::string, Skeleton>> skeletons{{"figure", figure_skeleton()}, {"figure 1.6 m", figure_skeleton(1.6)}};
  for (const char* name : {"dance", "karate"}) skeletons.emplace_back(name, read_bvh(std::string(VDCLOTH_SOURCE_DIR) + "/motions/" + name + ".bvh").skeleton);
  for (const char* file : {"01_01.bvh", "01_03.bvh", "Boxing_Toes.bvh"}) skeletons.emplace_back(file, read_bvh(std::string(kCaptures) + file).skeleton);
  for (const auto& [name, skeleton] : skeletons) {
    std::vector<int> moved_to;
    const Skeleton other = renamed_and_reordered(skeleton, &moved_to);
    const Humanoid a = *recognise_humanoid(skeleton).humanoid, b = *recognise_humanoid(other).humanoid;
    for (const std::string& landmark : landmark_names()) {
      const int j = *landmark_joint(a, landmark);
      EXPECT_EQ(j < 0 ? -1 : moved_to[static_cast<std::size_t>(j)], *landmark_joint(b, landmark)) << name << " " << landmark;
    }
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j)
      EXPECT_EQ(a.parts[j], b.parts[static_cast<std::size_t>(moved_to[j])]) << name << " " << skeleton.joints[j].name;
  }
}

TEST(Humanoid, BipedsTreeAndTwistJointsAreRecognised) {
  const std::vector<std::string> biped = expected(
      {"Bip01 Spine", "Bip01 Spine1", "Bip01 Neck", "-", "Bip01 Head"},
      {{{"Bip01 L Clavicle", "Bip01 L UpperArm", "Bip01 L Forearm", "Bip01 L Hand", "Bip01 L Thigh", "Bip01 L Calf", "Bip01 L Foot", "Bip01 L Toe0"},
        {"Bip01 R Clavicle", "Bip01 R UpperArm", "Bip01 R Forearm", "Bip01 R Hand", "Bip01 R Thigh", "Bip01 R Calf", "Bip01 R Foot", "Bip01 R Toe0"}}});
  EXPECT_EQ(landmarks_named(biped_skeleton()), biped);
  const std::vector<std::string> twists = expected(
      {"Hips", "Spine", "Chest", "Neck", "Head"},
      {{{"LeftShoulder", "LeftArm", "LeftForeArm", "LeftHand", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToe"},
        {"RightShoulder", "RightArm", "RightForeArm", "RightHand", "RightUpLeg", "RightLeg", "RightFoot", "RightToe"}}});
  const Skeleton twisted = twist_skeleton();
  EXPECT_EQ(landmarks_named(twisted), twists);
  const Humanoid h = *recognise_humanoid(twisted).humanoid;
  EXPECT_EQ(h.parts[static_cast<std::size_t>(*find_joint(twisted, "LeftArmTwist"))], BodyPart::UpperArm);
  EXPECT_EQ(h.parts[static_cast<std::size_t>(*find_joint(twisted, "RightForeArmTwist"))], BodyPart::ForeArm);
  EXPECT_EQ(h.parts[static_cast<std::size_t>(*find_joint(twisted, "LeftUpLegTwist"))], BodyPart::Thigh);
}

TEST(Humanoid, ASkeletonThatIsNotAHumanoidsSaysWhatIsMissing) {
  Skeleton one_leg = figure_skeleton();
  // Without its right leg: the hips keep two limbs, the spine and one leg.
  const int right_leg = *find_joint(one_leg, "RightUpLeg");
  std::vector<Joint> kept;
  for (std::size_t j = 0; j < one_leg.joints.size(); ++j)
    if (!descends_from(one_leg, static_cast<int>(j), right_leg)) kept.push_back(one_leg.joints[j]);
  one_leg.joints = kept;
  const HumanoidRecognition r = recognise_humanoid(one_leg);
  EXPECT_FALSE(r.humanoid);
  EXPECT_EQ(r.why_not, "no joint where two legs and a spine part (the hips) below one where two arms and a neck part (the chest)");
  EXPECT_EQ(missing_joint(one_leg, "LeftArm"),
            "the motion's skeleton is not a humanoid's, so it has no 'LeftArm': " + r.why_not + " (a character's joint_names renames a capture's joints)");
  EXPECT_THROW(humanoid_of(one_leg), std::invalid_argument);
  // A joint of its own name is still found; a landmark is not, though a joint bears its name.
  EXPECT_EQ(find_joint(one_leg, "Chest"), 2);
}

// A capture of meaningless names in another order mirrors as the original does: each joint
// where its partner by shape was, reflected in x = 0.
TEST(Humanoid, AFigureOfAnyNamesHasItsMirrorImage) {
  const Motion dance = read_bvh(std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh");
  std::vector<int> moved_to;
  const Motion renamed = renamed_and_reordered(dance, &moved_to);
  const Motion mirror = mirrored(dance), renamed_mirror = mirrored(renamed);
  for (std::size_t f : {std::size_t{0}, dance.frames.size() / 2}) {
    const auto a = mirror.world(mirror.frame_pose(f)), b = renamed_mirror.world(renamed_mirror.frame_pose(f));
    for (std::size_t j = 0; j < a.size(); ++j)
      EXPECT_LT((a[j].translation() - b[static_cast<std::size_t>(moved_to[j])].translation()).norm(), 1e-9) << dance.skeleton.joints[j].name;
  }
  const Humanoid h = *recognise_humanoid(dance.skeleton).humanoid;
  const std::vector<int> partner = mirror_partners(dance.skeleton, h);
  EXPECT_EQ(partner[static_cast<std::size_t>(*find_joint(dance.skeleton, "LeftForeArm"))], *find_joint(dance.skeleton, "RightForeArm"));
  EXPECT_EQ(partner[static_cast<std::size_t>(*find_joint(dance.skeleton, "RightToe"))], *find_joint(dance.skeleton, "LeftToe"));
  EXPECT_EQ(partner[static_cast<std::size_t>(*find_joint(dance.skeleton, "Head"))], *find_joint(dance.skeleton, "Head"));
}

// A scene's joint_names decide over the shape: the clavicle renamed LeftArm is the left arm.
TEST(Humanoid, AJointTheSceneNamesAfterALandmarkIsThatLandmark) {
  Skeleton s = figure_skeleton();
  const int clavicle = *find_joint(s, "LeftShoulder");
  rename_joints(s, {{"LeftShoulder", "LeftArm"}, {"LeftArm", "LeftUpperArm"}});
  EXPECT_EQ(find_joint(s, "LeftArm"), clavicle);
  EXPECT_EQ(recognise_humanoid(s).humanoid->arms[0].root, clavicle);
  EXPECT_EQ(find_joint(s, "LeftUpperArm"), clavicle + 1);  // a capture's own name
}

}  // namespace
}  // namespace vdc
