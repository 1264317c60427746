// Skeletons and their motion: a joint hierarchy with offsets and channels (the BVH model), the
// channel values of a sequence of frames, and joint transforms at any time (translations
// interpolated linearly, rotations by spherical interpolation between frames), with retiming.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/math.hpp"

namespace vdc {

enum class Channel { XPosition, YPosition, ZPosition, XRotation, YRotation, ZRotation };

struct Joint {
  std::string name;               // "End Site" children are named after their parent + "_end"
  int parent = -1;                // index of the parent joint, -1 for the root
  Vec3 offset = Vec3::Zero();     // from the parent joint, in the parent's frame
  std::vector<Channel> channels;  // in the order the file lists them
  int first_channel = 0;          // index of its first channel in a frame's values
  bool end_site = false;          // a BVH "End Site": a leaf point with no channels
  bool named_by_scene = false;    // renamed by a scene's joint_names: the landmark it is named after
};

struct Skeleton {
  std::vector<Joint> joints;  // parents before children
  int num_channels = 0;
};

// Per joint: rotation and translation relative to its parent (offset and position channels).
struct Pose {
  std::vector<Eigen::Quaterniond> rotation;
  std::vector<Vec3> translation;
};

struct Motion {
  Skeleton skeleton;
  double frame_time = 1.0 / 30;  // s
  std::vector<std::vector<double>> frames;  // channel values (degrees for rotations)

  double duration() const { return frames.empty() ? 0 : frame_time * static_cast<double>(frames.size() - 1); }
  // The pose of frame i: rotations composed in the order the channels are listed.
  Pose frame_pose(std::size_t i) const;
  // The pose at time t (s from the first frame): between frames, translations linear and
  // rotations spherical; held before the first frame and after the last.
  Pose pose_at(double t) const;
  // World transforms of every joint for a pose.
  std::vector<Eigen::Isometry3d> world(const Pose& pose) const;
};

// Whether `joint` is `ancestor` or below it in the hierarchy.
bool descends_from(const Skeleton& skeleton, int joint, int ancestor);
// Per joint: whether it is one of `roots` or below one.
std::vector<char> joints_below(const Skeleton& skeleton, const std::vector<int>& roots);

// Scales every length of a motion (joint offsets and position channels), e.g. from a capture's
// units to metres.
void scale_lengths(Motion& motion, double factor);

// The motion's mirror image across the skeleton's x = 0 plane (its left-right plane for a
// figure facing +z): each joint moves as its partner did, reflected: x offsets and x translations
// negated, rotations about y and z negated (M R M with M = diag(-1, 1, 1) keeps the channels'
// order). A humanoid's partners are by shape (mirror_partners, scene/humanoid.hpp), another
// skeleton's by name (Left... and Right... swapped). Throws std::invalid_argument naming a joint
// without a partner of the same channels.
Motion mirrored(const Motion& motion);
// Per joint, the joint whose motion it takes in `mirrored` (itself on the middle line).
std::vector<std::size_t> mirror_image_joints(const Skeleton& skeleton);

// A motion played in a scene: scene time t shows motion time (t - start) * speed.
struct MotionClip {
  const Motion* motion = nullptr;
  double start = 0;  // s
  double speed = 1;
  Pose pose_at(double t) const { return motion->pose_at((t - start) * speed); }
};

}  // namespace vdc
