// Joint transforms of a skeleton's motion (BVH conventions: a joint's local transform is its
// offset plus position channels, then its rotation channels composed in the order listed).
#include "scene/skeleton.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/humanoid.hpp"

namespace vdc {

Pose Motion::frame_pose(std::size_t i) const {
  const auto& values = frames[i];
  Pose pose;
  pose.rotation.reserve(skeleton.joints.size());
  pose.translation.reserve(skeleton.joints.size());
  for (const Joint& j : skeleton.joints) {
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    Vec3 t = j.offset;
    for (std::size_t c = 0; c < j.channels.size(); ++c) {
      const double v = values[static_cast<std::size_t>(j.first_channel) + c];
      const double a = v * M_PI / 180.0;
      switch (j.channels[c]) {
        case Channel::XPosition: t.x() += v; break;
        case Channel::YPosition: t.y() += v; break;
        case Channel::ZPosition: t.z() += v; break;
        case Channel::XRotation: q = q * Eigen::AngleAxisd(a, Vec3::UnitX()); break;
        case Channel::YRotation: q = q * Eigen::AngleAxisd(a, Vec3::UnitY()); break;
        case Channel::ZRotation: q = q * Eigen::AngleAxisd(a, Vec3::UnitZ()); break;
      }
    }
    pose.rotation.push_back(q.normalized());
    pose.translation.push_back(t);
  }
  return pose;
}

Pose Motion::pose_at(double t) const {
  if (frames.size() <= 1 || t <= 0) return frame_pose(0);
  const double s = t / frame_time;
  const auto last = frames.size() - 1;
  if (s >= static_cast<double>(last)) return frame_pose(last);
  const auto i = static_cast<std::size_t>(std::floor(s));
  const double w = s - static_cast<double>(i);
  Pose a = frame_pose(i);
  const Pose b = frame_pose(i + 1);
  for (std::size_t j = 0; j < a.rotation.size(); ++j) {
    a.rotation[j] = a.rotation[j].slerp(w, b.rotation[j]);
    a.translation[j] = (1 - w) * a.translation[j] + w * b.translation[j];
  }
  return a;
}

std::vector<Eigen::Isometry3d> Motion::world(const Pose& pose) const {
  std::vector<Eigen::Isometry3d> out(skeleton.joints.size());
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.translate(pose.translation[j]);
    local.rotate(pose.rotation[j]);
    const int p = skeleton.joints[j].parent;
    out[j] = p < 0 ? local : out[static_cast<std::size_t>(p)] * local;
  }
  return out;
}

bool descends_from(const Skeleton& skeleton, int joint, int ancestor) {
  for (int j = joint; j >= 0; j = skeleton.joints[static_cast<std::size_t>(j)].parent)
    if (j == ancestor) return true;
  return false;
}

std::vector<char> joints_below(const Skeleton& skeleton, const std::vector<int>& roots) {
  std::vector<char> out(skeleton.joints.size(), 0);
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j)
    for (int r : roots) out[j] = out[j] || descends_from(skeleton, static_cast<int>(j), r);
  return out;
}

void scale_lengths(Motion& motion, double factor) {
  for (Joint& j : motion.skeleton.joints) {
    j.offset *= factor;
    for (std::size_t c = 0; c < j.channels.size(); ++c)
      if (j.channels[c] == Channel::XPosition || j.channels[c] == Channel::YPosition || j.channels[c] == Channel::ZPosition)
        for (auto& frame : motion.frames) frame[static_cast<std::size_t>(j.first_channel) + c] *= factor;
  }
}

namespace {

// The name with Left and Right swapped (the project's, CMU's and Mixamo's names mark the side
// so); the name itself for a joint on the middle line.
std::string partner_name(const std::string& name) {
  std::string out = name;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"Left", "Right"}, {"Right", "Left"}}) {
    const auto at = name.find(from);
    if (at != std::string::npos) return out.replace(at, from.size(), to);
  }
  return out;
}

// Each joint's partner by name: Left and Right swapped (for a skeleton that is not a humanoid's).
std::vector<std::size_t> partners_by_name(const std::vector<Joint>& joints) {
  std::vector<std::size_t> partner(joints.size());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const std::string wanted = partner_name(joints[j].name);
    const auto it = std::find_if(joints.begin(), joints.end(), [&](const Joint& x) { return x.name == wanted; });
    if (it == joints.end()) throw std::invalid_argument("joint '" + joints[j].name + "' has no partner '" + wanted + "'");
    partner[j] = static_cast<std::size_t>(it - joints.begin());
  }
  return partner;
}

}  // namespace

// The mirror image of a motion (a reflection of its figure, e.g. for a crowd's copies).
std::vector<std::size_t> mirror_image_joints(const Skeleton& skeleton) {
  const HumanoidRecognition figure = recognise_humanoid(skeleton);
  if (!figure.humanoid) return partners_by_name(skeleton.joints);
  std::vector<std::size_t> partner;
  for (int p : mirror_partners(skeleton, *figure.humanoid)) partner.push_back(static_cast<std::size_t>(p));
  return partner;
}

Motion mirrored(const Motion& motion) {
  const auto& joints = motion.skeleton.joints;
  const std::vector<std::size_t> partner = mirror_image_joints(motion.skeleton);
  for (std::size_t j = 0; j < joints.size(); ++j)
    if (joints[partner[j]].channels != joints[j].channels || (joints[partner[j]].parent < 0) != (joints[j].parent < 0))
      throw std::invalid_argument("joint '" + joints[j].name + "' and its mirror image '" + joints[partner[j]].name + "' differ in channels");
  Motion out = motion;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& from = joints[partner[j]];
    out.skeleton.joints[j].offset = Vec3(-from.offset.x(), from.offset.y(), from.offset.z());
  }
  for (std::size_t f = 0; f < motion.frames.size(); ++f)
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const Joint& to = joints[j];
      const Joint& from = joints[partner[j]];
      for (std::size_t c = 0; c < to.channels.size(); ++c) {
        const double v = motion.frames[f][static_cast<std::size_t>(from.first_channel) + c];
        const Channel channel = to.channels[c];
        const bool negated = channel == Channel::XPosition || channel == Channel::YRotation || channel == Channel::ZRotation;
        out.frames[f][static_cast<std::size_t>(to.first_channel) + c] = negated ? -v : v;
      }
    }
  return out;
}

}  // namespace vdc
