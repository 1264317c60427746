// Animated character obstacles: skinned procedural bodies placed in the scene.
#include "scene/character.hpp"

namespace vdc {

Character::Character(Motion motion, const BodyParams& body, const Transform& placement, double start, double speed,
                     std::optional<MeshSource> skin)
    : motion_(std::make_unique<Motion>(std::move(motion))), placement_(placement) {
  body_ = skin ? std::make_unique<Body>(*motion_, body, std::move(*skin)) : std::make_unique<Body>(*motion_, body);
  clip_ = MotionClip{motion_.get(), start, speed};
}

std::vector<Vec3> Character::positions_at(double t) const {
  std::vector<Vec3> x = body_->skin(clip_.pose_at(t));
  const Mat3 r = placement_.rotation();
  for (Vec3& p : x) p = r * (placement_.scale * p) + placement_.translate;
  return x;
}

Eigen::Affine3d Character::joint_transform(int joint, double t) const {
  const Eigen::Isometry3d w = motion_->world(clip_.pose_at(t))[static_cast<std::size_t>(joint)];
  Eigen::Affine3d placed = Eigen::Affine3d::Identity();
  placed.linear() = placement_.rotation() * placement_.scale;
  placed.translation() = placement_.translate;
  return placed * w;
}

}  // namespace vdc
