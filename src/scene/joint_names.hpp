// A scene's names for a character's joints. The project's landmark names (Hips, Spine, Chest,
// Neck, Head, LeftShoulder, LeftArm, LeftForeArm, LeftHand, LeftUpLeg, LeftLeg, LeftFoot, LeftToe
// and their Right twins) mean the joints the humanoid's shape gives them (scene/humanoid.hpp),
// whatever the capture calls them; any other name is a capture's own joint. A scene's
// `joint_names` renames a capture's joints, and a joint it names after a landmark is that landmark.
#pragma once
#include <map>
#include <optional>
#include <string>

#include "scene/skeleton.hpp"

namespace vdc {

// A name as compared: lower case, without a namespace ("mixamorig:"), '_', '-', '.' or spaces.
std::string folded_joint_name(const std::string& name);

// The joint of `skeleton` a scene means by `wanted`: the joint the scene's joint_names gave that
// name, else for a landmark's name that landmark of the humanoid (none when the figure has no
// such joint), else the joint of that name, else the one whose folded name is the same. Empty
// when none is there.
std::optional<int> find_joint(const Skeleton& skeleton, const std::string& wanted);

// Why find_joint found no `joint` in `skeleton`: for a landmark, why the skeleton is not a
// humanoid or which part the figure lacks; else the first of its joints; and how a scene maps
// another scheme's names.
std::string missing_joint(const Skeleton& skeleton, const std::string& joint);

// Renames joints (capture name -> name the scene uses), e.g. {"pelvis_ctrl": "Hips"}, marking
// them named by the scene; throws std::invalid_argument naming a capture name the skeleton does
// not have.
void rename_joints(Skeleton& skeleton, const std::map<std::string, std::string>& names);

}  // namespace vdc
