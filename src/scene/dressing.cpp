// The dressing pose, reference frames and pre-roll blending of a character's motion.
#include "scene/dressing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/body.hpp"

namespace vdc {

double largest_joint_distance(const Motion& motion, const Pose& a, const Pose& b) {
  const auto wa = motion.world(a), wb = motion.world(b);
  double d = 0;
  for (std::size_t j = 0; j < wa.size(); ++j) d = std::max(d, (wa[j].translation() - wb[j].translation()).norm());
  return d;
}

int leading_reference_frames(const Motion& motion) {
  int k = 0;
  const double jump = kReferenceJumpSpeed * motion.frame_time;
  while (static_cast<std::size_t>(k) + 1 < motion.frames.size() &&
         largest_joint_distance(motion, motion.frame_pose(static_cast<std::size_t>(k)), motion.frame_pose(static_cast<std::size_t>(k) + 1)) > jump)
    ++k;
  return k;
}

Pose dressing_pose(const Motion& motion, int reference, int first) {
  if (reference > 0) return motion.frame_pose(static_cast<std::size_t>(reference) - 1);
  Pose rest = Body::rest_pose(motion.skeleton);
  if (motion.frames.empty()) return rest;
  const Pose stand = motion.frame_pose(static_cast<std::size_t>(first));
  auto lowest = [&](const Pose& p) {
    double y = std::numeric_limits<double>::infinity();
    for (const auto& w : motion.world(p)) y = std::min(y, w.translation().y());
    return y;
  };
  // The root's own rotation is zero in both, so moving its translation moves the whole figure.
  const Vec3 root = motion.world(stand).front().translation();
  const Vec3 at = motion.world(rest).front().translation();
  rest.translation.front() += Vec3(root.x() - at.x(), lowest(stand) - lowest(rest), root.z() - at.z());
  return rest;
}

std::vector<double> sample_times(double from, double to, double every) {
  const double span = std::max(0.0, to - from);
  const int steps = std::clamp(static_cast<int>(std::ceil(span / every - 1e-9)), 1, kMostSamples - 1);
  std::vector<double> times;
  for (int k = 0; k <= steps; ++k) times.push_back(from + span * k / steps);
  return times;
}

std::vector<Pose> clip_poses(const MotionClip& clip, double from, double to, double every) {
  to = std::min(to, clip.start + clip.motion->duration() / clip.speed);
  std::vector<Pose> poses;
  for (double t : sample_times(from, std::max(from, to), every)) poses.push_back(clip.pose_at(t));
  return poses;
}

Pose blend_poses(const Pose& a, const Pose& b, double s) {
  Pose out = a;
  for (std::size_t j = 0; j < out.rotation.size(); ++j) {
    out.rotation[j] = a.rotation[j].slerp(s, b.rotation[j]);
    out.translation[j] = (1 - s) * a.translation[j] + s * b.translation[j];
  }
  return out;
}

double preroll_ease(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3 - 2 * u);
}

}  // namespace vdc
