// An animated character as an obstacle: a motion (BVH, lengths scaled to metres), the
// procedural body of its skeleton, placed in the scene by a transform and played from a start
// time at a speed. Its vertices move with the skin, so collisions see per-vertex velocities.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "scene/body.hpp"
#include "scene/transform.hpp"

namespace vdc {

class Character {
 public:
  // With `skin`, that mesh (in the skeleton's rest pose and units) is the body instead of the
  // procedural one.
  Character(Motion motion, const BodyParams& body, const Transform& placement, double start, double speed,
            std::optional<MeshSource> skin = std::nullopt);
  const MeshSource& rest_mesh() const { return body_->rest_mesh(); }  // unplaced, rest pose
  // Placed, skinned vertex positions at scene time t (by mesh node index).
  std::vector<Vec3> positions_at(double t) const;
  // The placed world transform of a joint (index into the motion's skeleton) at scene time t.
  Eigen::Affine3d joint_transform(int joint, double t) const;
  const Motion& motion() const { return *motion_; }
  double start() const { return clip_.start; }
  double speed() const { return clip_.speed; }

 private:
  std::unique_ptr<Motion> motion_;  // stable address: the body refers to it
  std::unique_ptr<Body> body_;
  Transform placement_;
  MotionClip clip_;
};

}  // namespace vdc
