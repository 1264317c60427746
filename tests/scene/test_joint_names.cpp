// Joints asked for by the project's names, found under CMU's, Mixamo's and other schemes' names,
// and renamed by a scene.
#include <gtest/gtest.h>

#include <stdexcept>

#include "scene/joint_names.hpp"

namespace vdc {
namespace {

Skeleton skeleton_of(const std::vector<std::string>& names) {
  Skeleton s;
  for (const std::string& name : names) {
    Joint j;
    j.name = name;
    j.parent = s.joints.empty() ? -1 : 0;
    s.joints.push_back(j);
  }
  return s;
}

TEST(JointNames, FoldingDropsNamespaceCaseAndSeparators) {
  EXPECT_EQ(folded_joint_name("mixamorig:LeftUpLeg"), "leftupleg");
  EXPECT_EQ(folded_joint_name("L_Upper-Arm.001"), "lupperarm001");
  EXPECT_EQ(folded_joint_name("Hips"), "hips");
}

TEST(JointNames, MixamoNamesAreTheProjectsWithANamespace) {
  const Skeleton s = skeleton_of({"mixamorig:Hips", "mixamorig:Spine", "mixamorig:Spine1", "mixamorig:Spine2", "mixamorig:Neck",
                                  "mixamorig:Head", "mixamorig:LeftUpLeg", "mixamorig:RightForeArm"});
  EXPECT_EQ(find_joint(s, "Hips"), 0);
  EXPECT_EQ(find_joint(s, "Spine"), 1);
  EXPECT_EQ(find_joint(s, "Chest"), 3);  // Mixamo's chest is the third spine joint
  EXPECT_EQ(find_joint(s, "LeftUpLeg"), 6);
  EXPECT_EQ(find_joint(s, "RightForeArm"), 7);
  EXPECT_EQ(find_joint(s, "LeftForeArm"), std::nullopt);
}

TEST(JointNames, CmuNamesAreFoundForTheProjectsJoints) {
  const Skeleton s = skeleton_of({"Hips", "LHipJoint", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "LowerBack", "Spine",
                                  "Spine1", "Neck", "Neck1", "Head", "LeftShoulder", "LeftArm"});
  EXPECT_EQ(find_joint(s, "Chest"), 8);     // Spine1: CMU has no Spine2
  EXPECT_EQ(find_joint(s, "Spine"), 7);     // its own name first, not LowerBack
  EXPECT_EQ(find_joint(s, "LeftToe"), 5);   // LeftToeBase
  EXPECT_EQ(find_joint(s, "Neck"), 9);
  EXPECT_EQ(find_joint(s, "LeftShoulder"), 12);
}

TEST(JointNames, OtherSchemesSideAndPartNames) {
  const Skeleton s = skeleton_of({"pelvis", "spine_01", "L_Thigh", "l_calf", "L_UpperArm", "r_wrist", "lowerback"});
  EXPECT_EQ(find_joint(s, "Hips"), 0);
  EXPECT_EQ(find_joint(s, "Spine"), 6);  // lowerback; spine_01 folds to spine01, not a name of the spine
  EXPECT_EQ(find_joint(s, "LeftUpLeg"), 2);
  EXPECT_EQ(find_joint(s, "LeftLeg"), 3);
  EXPECT_EQ(find_joint(s, "LeftArm"), 4);
  EXPECT_EQ(find_joint(s, "RightHand"), 5);
  EXPECT_EQ(find_joint(s, "RightArm"), std::nullopt);
  EXPECT_EQ(find_joint(s, "spine_01"), 1);  // any joint by its own name
  EXPECT_TRUE(joint_aliases("Tail").empty());
  EXPECT_EQ(joint_aliases("LeftToe"), (std::vector<std::string>{"ltoe", "lefttoebase", "ltoebase", "lefttoes", "ltoes", "leftball", "lball"}));
}

TEST(JointNames, RenamesAreFoundFirstThenApplied) {
  Skeleton s = skeleton_of({"a", "b", "c"});
  rename_joints(s, {{"a", "b"}, {"b", "c"}});
  EXPECT_EQ(s.joints[0].name, "b");
  EXPECT_EQ(s.joints[1].name, "c");
  EXPECT_EQ(s.joints[2].name, "c");
  EXPECT_THROW(rename_joints(s, {{"z", "Hips"}}), std::invalid_argument);
}

}  // namespace
}  // namespace vdc
