// Handles: garment nodes held in place, moved along a keyframed path, or carried by a joint of
// an animated character (a waistband tied to the pelvis), released at a time.
#pragma once
#include <limits>
#include <memory>

#include "scene/character.hpp"
#include "core/track.hpp"

namespace vdc {

struct ClothHandle {
  Vec3Track path;  // offsets from the nodes' initial positions; empty: pinned where they start
  double release = std::numeric_limits<double>::infinity();  // s; free from then on
  // Attached: the nodes move rigidly with this joint of the character from where they are at
  // the run's start (Scene::start_time; the path's offsets apply before).
  std::shared_ptr<const Character> character;
  int joint = -1;
  Eigen::Affine3d from_start = Eigen::Affine3d::Identity();  // inverse of the joint's transform at the start

  bool active(double t) const { return t < release; }
  // The rigid motion carrying the handle's nodes at time t (identity unless attached).
  Eigen::Affine3d carry(double t) const {
    return character ? Eigen::Affine3d(character->joint_transform(joint, t) * from_start) : Eigen::Affine3d::Identity();
  }
  // Where a node anchored at `anchor` (its position at the start) is held at time t; `carried` is
  // carry(t).
  Vec3 target(const Vec3& anchor, double t, const Eigen::Affine3d& carried) const { return carried * Vec3(anchor + path.at(t)); }
};

// Names of the node attributes that carry handles through topology changes.
inline constexpr const char* kHandleAttr = "handle";  // int32: index into the garment's handles, -1 if none
inline constexpr const char* kAnchorAttr = "anchor";  // Vec3: world position the path offsets apply to

}  // namespace vdc
