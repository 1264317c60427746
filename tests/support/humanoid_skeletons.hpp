// Skeletons of other rigs' shapes for the humanoid's tests: any motion renamed j0, j1, ... with
// its joints in another order, a 3ds Max Biped-style tree and the project's figure with twist
// joints, the last two with the project's figure's joint positions.
#pragma once
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "scene/figure.hpp"
#include "scene/skeleton.hpp"

namespace vdc::test {

// The motion with every joint named j<k> and each joint's children listed last first (depth
// first, as a BVH file lists them), its channel values moved with their joints; `moved_to`, when
// given, gets each joint's new index.
inline Motion renamed_and_reordered(const Motion& motion, std::vector<int>* moved_to = nullptr) {
  const Skeleton& s = motion.skeleton;
  std::vector<std::vector<int>> children(s.joints.size());
  for (std::size_t j = 1; j < s.joints.size(); ++j) children[static_cast<std::size_t>(s.joints[j].parent)].push_back(static_cast<int>(j));
  Motion out = motion;
  out.skeleton.joints.clear();
  out.skeleton.num_channels = 0;
  std::vector<int> to(s.joints.size(), -1), order;
  std::function<void(int)> visit = [&](int j) {
    Joint joint = s.joints[static_cast<std::size_t>(j)];
    to[static_cast<std::size_t>(j)] = static_cast<int>(out.skeleton.joints.size());
    order.push_back(j);
    joint.name = "j" + std::to_string(out.skeleton.joints.size());
    joint.parent = joint.parent < 0 ? -1 : to[static_cast<std::size_t>(joint.parent)];
    joint.first_channel = out.skeleton.num_channels;
    out.skeleton.num_channels += static_cast<int>(joint.channels.size());
    out.skeleton.joints.push_back(joint);
    for (auto c = children[static_cast<std::size_t>(j)].rbegin(); c != children[static_cast<std::size_t>(j)].rend(); ++c) visit(*c);
  };
  visit(0);
  for (std::size_t f = 0; f < motion.frames.size(); ++f)
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Joint &from = s.joints[static_cast<std::size_t>(order[k])], &into = out.skeleton.joints[k];
      for (std::size_t c = 0; c < from.channels.size(); ++c)
        out.frames[f][static_cast<std::size_t>(into.first_channel) + c] = motion.frames[f][static_cast<std::size_t>(from.first_channel) + c];
    }
  if (moved_to) *moved_to = to;
  return out;
}

inline Skeleton renamed_and_reordered(const Skeleton& skeleton, std::vector<int>* moved_to = nullptr) {
  Motion m;
  m.skeleton = skeleton;
  return renamed_and_reordered(m, moved_to).skeleton;
}

// Builds a skeleton joint by joint, each with the figure's three rotation channels (the root
// also its position).
class SkeletonBuilder {
 public:
  int add(const std::string& name, int parent, const Vec3& offset, bool end_site = false) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.offset = offset;
    j.end_site = end_site;
    if (parent < 0) j.channels = {Channel::XPosition, Channel::YPosition, Channel::ZPosition};
    if (!end_site) j.channels.insert(j.channels.end(), {Channel::ZRotation, Channel::XRotation, Channel::YRotation});
    j.first_channel = skeleton_.num_channels;
    skeleton_.num_channels += static_cast<int>(j.channels.size());
    skeleton_.joints.push_back(j);
    return static_cast<int>(skeleton_.joints.size()) - 1;
  }
  const Skeleton& skeleton() const { return skeleton_; }

 private:
  Skeleton skeleton_;
};

// The arms' offsets of the project's figure: 50 degrees below horizontal.
inline Vec3 figure_arm(int side, double length) {
  const double c = std::cos(50 * M_PI / 180), d = std::sin(50 * M_PI / 180);
  return Vec3(side * length * c, -length * d, 0);
}

// Biped's tree: a root and pelvis above the spine joint the thighs hang from, the clavicles and
// head on the neck, fingers on the hands, names "Bip01 L UpperArm".
inline Skeleton biped_skeleton() {
  SkeletonBuilder b;
  const int root = b.add("Bip01", -1, Vec3(0, 0.95, 0));
  const int pelvis = b.add("Bip01 Pelvis", root, Vec3::Zero());
  const int spine = b.add("Bip01 Spine", pelvis, Vec3(0, 0.02, 0));
  const int spine1 = b.add("Bip01 Spine1", spine, Vec3(0, 0.13, 0));
  const int spine2 = b.add("Bip01 Spine2", spine1, Vec3(0, 0.15, 0));
  const int neck = b.add("Bip01 Neck", spine2, Vec3(0, 0.17, 0));
  const int head = b.add("Bip01 Head", neck, Vec3(0, 0.14, 0.01));
  b.add("Bip01 HeadNub", head, Vec3(0, 0.13, 0), true);
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "Bip01 L " : "Bip01 R ";
    const int clavicle = b.add(p + "Clavicle", neck, Vec3(side * 0.03, 0, 0));
    const int upper = b.add(p + "UpperArm", clavicle, Vec3(side * 0.15, 0, 0));
    const int fore = b.add(p + "Forearm", upper, figure_arm(side, 0.28));
    const int hand = b.add(p + "Hand", fore, figure_arm(side, 0.25));
    const int thumb = b.add(p + "Finger0", hand, Vec3(side * 0.01, -0.01, 0.02));
    b.add(p + "Finger0Nub", thumb, figure_arm(side, 0.05), true);
    const int finger = b.add(p + "Finger1", hand, figure_arm(side, 0.03));
    b.add(p + "Finger1Nub", finger, figure_arm(side, 0.06), true);
  }
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "Bip01 L " : "Bip01 R ";
    const int thigh = b.add(p + "Thigh", spine, Vec3(side * 0.09, -0.07, 0));
    const int calf = b.add(p + "Calf", thigh, Vec3(0, -0.42, 0));
    const int foot = b.add(p + "Foot", calf, Vec3(0, -0.42, 0));
    const int toe = b.add(p + "Toe0", foot, Vec3(0, -0.05, 0.12));
    b.add(p + "Toe0Nub", toe, Vec3(0, 0, 0.05), true);
  }
  return b.skeleton();
}

// The project's figure with a twist joint halfway along each upper arm, forearm and thigh.
inline Skeleton twist_skeleton() {
  SkeletonBuilder b;
  const int hips = b.add("Hips", -1, Vec3(0, 0.95, 0));
  const int spine = b.add("Spine", hips, Vec3(0, 0.10, 0));
  const int chest = b.add("Chest", spine, Vec3(0, 0.20, 0));
  const int neck = b.add("Neck", chest, Vec3(0, 0.22, 0));
  const int head = b.add("Head", neck, Vec3(0, 0.09, 0.01));
  b.add("Head_end", head, Vec3(0, 0.13, 0), true);
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "Left" : "Right";
    const int shoulder = b.add(p + "Shoulder", chest, Vec3(side * 0.03, 0.17, 0));
    const int arm = b.add(p + "Arm", shoulder, Vec3(side * 0.15, 0, 0));
    const int arm_twist = b.add(p + "ArmTwist", arm, figure_arm(side, 0.14));
    const int fore = b.add(p + "ForeArm", arm_twist, figure_arm(side, 0.14));
    const int fore_twist = b.add(p + "ForeArmTwist", fore, figure_arm(side, 0.125));
    const int hand = b.add(p + "Hand", fore_twist, figure_arm(side, 0.125));
    b.add(p + "Hand_end", hand, figure_arm(side, 0.09), true);
  }
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "Left" : "Right";
    const int up = b.add(p + "UpLeg", hips, Vec3(side * 0.09, -0.05, 0));
    const int twist = b.add(p + "UpLegTwist", up, Vec3(0, -0.21, 0));
    const int leg = b.add(p + "Leg", twist, Vec3(0, -0.21, 0));
    const int foot = b.add(p + "Foot", leg, Vec3(0, -0.42, 0));
    const int toe = b.add(p + "Toe", foot, Vec3(0, -0.05, 0.12));
    b.add(p + "Toe_end", toe, Vec3(0, 0, 0.05), true);
  }
  return b.skeleton();
}

// A motion of `skeleton` standing still in its rest pose for `frames` frames at 30 a second.
inline Motion standing(const Skeleton& skeleton, std::size_t frames = 2) {
  Motion m;
  m.skeleton = skeleton;
  m.frames.assign(frames, std::vector<double>(static_cast<std::size_t>(skeleton.num_channels), 0.0));
  return m;
}

}  // namespace vdc::test
