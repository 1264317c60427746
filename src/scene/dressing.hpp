// How a character comes to its capture: the pose its garments are made in (the dressing pose),
// a capture's leading reference frames (a T-pose held for calibration, then a jump into the
// motion), and the pre-roll that moves the figure from the dressing pose into the shot's first
// pose before the shot begins, as cloth artists settle garments in production.
#pragma once
#include <vector>

#include "scene/skeleton.hpp"

namespace vdc {

// A joint moving faster than this between two frames is a jump no body makes (m/s; a pitcher's
// hand peaks near 35 m/s, and only the leading frames are judged): the frame before it is a
// reference pose, not motion. CMU captures jump from their T-pose at about 70 m/s.
inline constexpr double kReferenceJumpSpeed = 50.0;

// The largest distance any joint lies apart in two poses of the motion's skeleton (m).
double largest_joint_distance(const Motion& motion, const Pose& a, const Pose& b);

// How many leading frames are reference poses: frames from which some joint jumps to the next
// faster than kReferenceJumpSpeed. The last frame is never one.
int leading_reference_frames(const Motion& motion);

// The pose garments are put on in: the last of `reference` leading reference frames if there
// are any (a capture's T-pose), else the rest pose (every rotation zero) stood where frame
// `first` stands: the root across the floor where it is there, its lowest joint as high as that
// frame's lowest. For the project's motions, which start at rest, the rest pose.
Pose dressing_pose(const Motion& motion, int reference, int first);

// Times from `from` to `to`, both included, `every` seconds apart or closer, and at most
// kMostSamples of them (a long shot is sampled more sparsely).
inline constexpr int kMostSamples = 10000;
std::vector<double> sample_times(double from, double to, double every);

// A clip's poses at sample_times(from, to, every), `to` cut to where the clip's motion ends
// (it holds its last pose after).
std::vector<Pose> clip_poses(const MotionClip& clip, double from, double to, double every);

// Per joint, rotations by spherical interpolation and translations linearly: a at s = 0, b at 1.
Pose blend_poses(const Pose& a, const Pose& b, double s);

// The pre-roll's ease in and out over u in [0, 1]: 3u^2 - 2u^3, clamped.
double preroll_ease(double u);

}  // namespace vdc
