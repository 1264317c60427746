// Joint names across the naming schemes of motion captures: the project's figures (Hips, Spine,
// Chest, Neck, Head, LeftShoulder, LeftArm, LeftForeArm, LeftHand, LeftUpLeg, LeftLeg, LeftFoot,
// LeftToe and their Right twins), CMU's (LowerBack, Spine1, Neck1, LeftToeBase, ...) and
// Mixamo's (mixamorig:Hips, Spine2, ...). A scene asks for a joint by any of them; a capture of
// another scheme is mapped by the scene (`joint_names`), which renames its joints.
#pragma once
#include <map>
#include <optional>
#include <string>

#include "scene/skeleton.hpp"

namespace vdc {

// A name as compared: lower case, without a namespace ("mixamorig:"), '_', '-', '.' or spaces.
std::string folded_joint_name(const std::string& name);

// The joint of `skeleton` a scene means by `wanted`: the joint of that name, else the one whose
// folded name is the same, else, for a joint of the project's figures, the first present of the
// names other schemes give it (Chest: Chest, UpperChest, Spine2, Spine1; Spine: Spine,
// LowerBack; Hips: Hips, Pelvis, Root; LeftToe: LeftToe, LeftToeBase; and so on, the sides
// written Left, L or L_). Empty when none is there.
std::optional<int> find_joint(const Skeleton& skeleton, const std::string& wanted);

// The names find_joint tries for `wanted` beyond its own, folded, in order (empty for a name
// that is not one of the project's figures' joints).
std::vector<std::string> joint_aliases(const std::string& wanted);

// Why find_joint found no `joint` in `skeleton`: the names tried and the first of its joints,
// and how a scene maps another scheme's names.
std::string missing_joint(const Skeleton& skeleton, const std::string& joint);

// Renames joints (capture name -> name the scene uses), e.g. {"pelvis_ctrl": "Hips"}; throws
// std::invalid_argument naming a capture name the skeleton does not have.
void rename_joints(Skeleton& skeleton, const std::map<std::string, std::string>& names);

}  // namespace vdc
