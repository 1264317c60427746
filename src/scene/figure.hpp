// The project's own figure and its authored motions. The skeleton is a 1.75 m figure in an A
// pose (arms 50 degrees below horizontal, so garments can be put on in the rest pose); motions
// are authored as keyframed joint rotations, interpolated smoothly and sampled into BVH frames.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "scene/skeleton.hpp"

namespace vdc {

// Joints: Hips (root, position and rotation channels), Spine, Chest, Neck, Head, and per side
// Shoulder, Arm, ForeArm, Hand, UpLeg, Leg, Foot, Toe (Left..., Right...). Metres; the figure
// faces +z with its left side towards +x; y up.
Skeleton figure_skeleton(double height = 1.75);

// One keyframe: rotations in degrees about x, y and z (applied in the joint's channel order,
// Z then X then Y), and the root's displacement from its rest place in metres.
struct PoseKey {
  double time = 0;
  std::map<std::string, Vec3> rotation;  // joints not listed are at rest
  Vec3 root = Vec3::Zero();
  Vec3 root_rotation = Vec3::Zero();     // degrees, like a joint's
};

// Samples keys at `fps`: every channel is interpolated through the keys by cubic Hermite
// (tangents from the neighbouring keys, zero at both ends). Throws InputError naming `name` for
// an unknown joint or times that do not increase.
Motion author_motion(const Skeleton& skeleton, const std::vector<PoseKey>& keys, double fps, const std::string& name);

// Reads keyframes from JSON: {"fps": 30, "keys": [{"time": t, "root": [x, y, z],
// "root_rotation": [rx, ry, rz], "rotation": {"LeftArm": [rx, ry, rz], ...}}, ...]}.
Motion author_motion_file(const std::string& path);

}  // namespace vdc
