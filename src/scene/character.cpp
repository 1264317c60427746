// Animated character obstacles: skinned procedural bodies placed in the scene.
#include "scene/character.hpp"

#include "core/bvh.hpp"
#include "scene/dressing.hpp"

namespace vdc {

Character::Character(Motion motion, const BodyParams& body, const Transform& placement, double start, double speed,
                     std::optional<Skin> skin, Dressing dressing, BodyMeshCache* bodies)
    : motion_(std::make_unique<Motion>(std::move(motion))), placement_(placement), body_params_(body), preroll_(dressing.preroll) {
  if (!skin)
    body_ = std::make_unique<Body>(*motion_, body, bodies);
  else if (skin->weights.empty())
    body_ = std::make_unique<Body>(*motion_, body, std::move(skin->mesh));
  else
    body_ = std::make_unique<Body>(*motion_, std::move(*skin));
  clip_ = MotionClip{motion_.get(), start, speed};
  dressing_ = dressing.pose ? *dressing.pose : Body::rest_pose(motion_->skeleton);
  Aabb box;
  for (const Vec3& x : body_->rest_mesh().positions) box.grow(x);
  if (!body_->rest_mesh().positions.empty()) rest_diagonal_ = (box.hi - box.lo).norm();
}

std::pair<Vec3, double> Character::reach_at(double t) const {
  return {joint_transform(0, t).translation(), placement_.scale * rest_diagonal_};
}

Pose Character::pose_at(double t) const {
  if (t >= 0 || preroll_ <= 0) return clip_.pose_at(t);
  if (t <= -preroll_) return dressing_;
  return blend_poses(dressing_, clip_.pose_at(0.0), preroll_ease(1 + t / preroll_));
}

std::vector<Vec3> Character::positions_at(double t) const {
  std::vector<Vec3> x = body_->skin(pose_at(t));
  const Mat3 r = placement_.rotation();
  for (Vec3& p : x) p = r * (placement_.scale * p) + placement_.translate;
  return x;
}

Eigen::Affine3d Character::joint_transform(int joint, double t) const {
  const Eigen::Isometry3d w = motion_->world(pose_at(t))[static_cast<std::size_t>(joint)];
  Eigen::Affine3d placed = Eigen::Affine3d::Identity();
  placed.linear() = placement_.rotation() * placement_.scale;
  placed.translation() = placement_.translate;
  return placed * w;
}

}  // namespace vdc
