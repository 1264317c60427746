// An animated character as an obstacle: a motion (BVH, lengths scaled to metres), the
// procedural body of its skeleton, placed in the scene by a transform and played from a start
// time at a speed. Its vertices move with the skin, so collisions see per-vertex velocities.
// Before the shot (scene time < 0) it stands in the pose its garments were made in and, over
// its pre-roll, moves into the pose it has at time 0.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "scene/body.hpp"
#include "scene/transform.hpp"

namespace vdc {

// The pose a character's garments are made in and how long it takes, before the shot, to move
// from it into the shot's first pose (s; 0: it is in that pose from the start).
struct Dressing {
  std::optional<Pose> pose;  // none: the rest pose
  double preroll = 0;
};

class Character {
 public:
  // With `skin`, that mesh (in the skeleton's rest pose and units) is the body instead of the
  // procedural one, with its own weights or automatic ones.
  // `bodies`: procedural bodies polygonized before (see BodyMeshCache).
  Character(Motion motion, const BodyParams& body, const Transform& placement, double start, double speed,
            std::optional<Skin> skin = std::nullopt, Dressing dressing = {}, BodyMeshCache* bodies = nullptr);
  const MeshSource& rest_mesh() const { return body_->rest_mesh(); }  // unplaced, rest pose
  // Placed, skinned vertex positions at scene time t (by mesh node index).
  std::vector<Vec3> positions_at(double t) const;
  // The placed world transform of a joint (index into the motion's skeleton) at scene time t.
  Eigen::Affine3d joint_transform(int joint, double t) const;
  // A ball that holds the placed body at scene time t, found without skinning it: around the
  // root joint, as wide as the rest body's box is long diagonally (no limb reaches farther from
  // the root than the whole figure is long).
  std::pair<Vec3, double> reach_at(double t) const;
  const Motion& motion() const { return *motion_; }
  const BodyParams& body_params() const { return body_params_; }
  // The skeleton's pose at scene time t: the clip's from time 0 on, the dressing pose before the
  // pre-roll, eased from the one into the other over it (Dressing).
  Pose pose_at(double t) const;
  const Pose& dressing_pose() const { return dressing_; }
  double preroll() const { return preroll_; }
  // The body's vertices in a pose, unplaced (the skeleton's space), and for each the joint that
  // moves it most (index into the motion's skeleton).
  std::vector<Vec3> skinned(const Pose& pose) const { return body_->skin(pose); }
  const std::vector<int>& main_joints() const { return body_->main_joints(); }
  double start() const { return clip_.start; }
  double speed() const { return clip_.speed; }

 private:
  std::unique_ptr<Motion> motion_;  // stable address: the body refers to it
  std::unique_ptr<Body> body_;
  Transform placement_;
  BodyParams body_params_;
  MotionClip clip_;
  Pose dressing_;
  double preroll_ = 0;
  double rest_diagonal_ = 0;  // of the rest body's bounding box, unplaced
};

}  // namespace vdc
