// Joints asked for by a scene: landmarks by the figure's shape, other joints by their names, and
// joints renamed by a scene.
#include <gtest/gtest.h>

#include <stdexcept>

#include "scene/figure.hpp"
#include "scene/joint_names.hpp"

namespace vdc {
namespace {

// The project's figure with each joint renamed by `rename` (its end sites kept).
template <class Rename>
Skeleton figure_renamed(Rename rename) {
  Skeleton s = figure_skeleton();
  for (Joint& j : s.joints)
    if (!j.end_site) j.name = rename(j.name);
  return s;
}

TEST(JointNames, FoldingDropsNamespaceCaseAndSeparators) {
  EXPECT_EQ(folded_joint_name("mixamorig:LeftUpLeg"), "leftupleg");
  EXPECT_EQ(folded_joint_name("L_Upper-Arm.001"), "lupperarm001");
  EXPECT_EQ(folded_joint_name("Hips"), "hips");
}

// A landmark's name means the joint the shape gives it, whatever the capture calls it; any other
// name is the capture's joint of that name, folded.
TEST(JointNames, LandmarksByShapeOtherJointsByName) {
  const Skeleton own = figure_skeleton();
  const Skeleton mixamo = figure_renamed([](const std::string& n) { return "mixamorig:" + n; });
  const Skeleton swapped = figure_renamed([](const std::string& n) { return n == "LeftArm" ? std::string("RightArm") : n == "RightArm" ? std::string("LeftArm") : n; });
  for (const char* landmark : {"Hips", "Chest", "Head", "LeftShoulder", "LeftArm", "RightForeArm", "RightToe"}) {
    EXPECT_EQ(find_joint(mixamo, landmark), find_joint(own, landmark)) << landmark;
    EXPECT_EQ(find_joint(swapped, landmark), find_joint(own, landmark)) << landmark;  // the name misleads, the shape does not
  }
  EXPECT_EQ(find_joint(own, "left_fore-arm"), 8);   // folded
  EXPECT_EQ(find_joint(mixamo, "mixamorig:Spine"), 1);
  EXPECT_EQ(find_joint(own, "Head_end"), 5);        // not a landmark: by its name
  EXPECT_EQ(find_joint(own, "LeftHand_end"), 10);
  EXPECT_EQ(find_joint(own, "Tail"), std::nullopt);
  // A landmark the figure lacks: with its arms moved onto the chest, the figure has no clavicles,
  // though joints named LeftShoulder and RightShoulder are left there.
  Skeleton no_clavicles = figure_skeleton();
  for (std::size_t arm : {7, 12}) {
    Joint& j = no_clavicles.joints[arm];
    j.offset += no_clavicles.joints[static_cast<std::size_t>(j.parent)].offset;
    j.parent = 2;
  }
  EXPECT_EQ(find_joint(no_clavicles, "LeftArm"), 7);
  EXPECT_EQ(find_joint(no_clavicles, "LeftShoulder"), std::nullopt);
  EXPECT_NE(missing_joint(no_clavicles, "LeftShoulder").find("the motion's figure has no joint where 'LeftShoulder' is on the project's figure"), std::string::npos);
}

TEST(JointNames, RenamesAreFoundFirstThenApplied) {
  Skeleton s = figure_renamed([](const std::string& n) { return n == "Hips" ? "a" : n == "Spine" ? "b" : n == "Chest" ? "c" : n; });
  rename_joints(s, {{"a", "b"}, {"b", "c"}});
  EXPECT_EQ(s.joints[0].name, "b");
  EXPECT_EQ(s.joints[1].name, "c");
  EXPECT_EQ(s.joints[2].name, "c");
  EXPECT_TRUE(s.joints[0].named_by_scene && s.joints[1].named_by_scene && !s.joints[2].named_by_scene);
  EXPECT_THROW(rename_joints(s, {{"z", "Hips"}}), std::invalid_argument);
}

}  // namespace
}  // namespace vdc
