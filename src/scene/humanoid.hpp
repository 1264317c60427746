// A humanoid skeleton recognised by its shape, not its joints' names: from the tree and the rest
// pose, the hips (where two legs and the spine part), the chest (where two arms and the neck
// part), each limb's joints (the girdle before it, the joint it swings from, the one it bends at,
// its end), left and right by the way the feet point, and every joint's part of the body.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/skeleton.hpp"

namespace vdc {

enum class BodyPart : std::uint8_t { Other, Hips, Spine, Neck, Head, Clavicle, UpperArm, ForeArm, Hand, Finger, HipJoint, Thigh, Shin, Foot, Toe };

// A limb's joints (indices into the skeleton's joints; -1 where it has none).
struct Limb {
  int girdle = -1;  // the first of the joints before the root: a clavicle, CMU's hip joint
  int root = -1;    // where it swings from the trunk: the upper arm, the thigh
  int bend = -1;    // the elbow, the knee
  int end = -1;     // the hand, the foot
  int tip = -1;     // the toe (none on an arm)
};

struct Humanoid {
  int hips = -1, spine = -1, chest = -1, neck = -1, head = -1;
  std::array<Limb, 2> arms, legs;  // left, right
  std::vector<BodyPart> parts;     // per joint
};

// The humanoid in `skeleton`, else why it is not one (which part was not found). Joints a scene
// named after a landmark (Joint::named_by_scene, see landmark_joint) are that landmark whatever
// the shape says.
struct HumanoidRecognition {
  std::optional<Humanoid> humanoid;
  std::string why_not;
};
HumanoidRecognition recognise_humanoid(const Skeleton& skeleton);
// The humanoid in `skeleton`; throws std::invalid_argument saying why it is not one.
Humanoid humanoid_of(const Skeleton& skeleton);

// The joints in the figure's order rather than the file's: depth first from the root, at each
// joint its children of the trunk and head first, then the left limbs', then the right's (the
// farther reaching first among equals). The project's figures list their joints so.
std::vector<int> figure_order(const Skeleton& skeleton, const Humanoid& humanoid);

// Each joint's mirror image: the joint at the same place in the other side's limb (the two
// limbs' trees matched child by child, the farther reaching first), itself on the trunk, neck and
// head. Throws std::invalid_argument naming two matched joints whose trees differ.
std::vector<int> mirror_partners(const Skeleton& skeleton, const Humanoid& humanoid);

// The project's name of a landmark (Hips, Spine, Chest, Neck, Head; LeftShoulder, LeftArm,
// LeftForeArm, LeftHand, LeftUpLeg, LeftLeg, LeftFoot, LeftToe and the Right ones; compared
// folded, so "left_arm" is LeftArm) -> its joint in `humanoid`: -1 when the figure has none (no
// clavicle, neck or toe), nullopt when `name` is not a landmark's.
std::optional<int> landmark_joint(const Humanoid& humanoid, const std::string& name);

// The landmarks' names, in the order above.
const std::vector<std::string>& landmark_names();

}  // namespace vdc
