// Handles: garment nodes held in place or moved along a keyframed path, released at a time.
#pragma once
#include <limits>
#include <vector>

#include "core/math.hpp"

namespace vdc {

struct Keyframe {
  double time = 0;
  Vec3 offset = Vec3::Zero();  // displacement from the node's initial position, m
};

struct ClothHandle {
  std::vector<Keyframe> path;  // empty: pinned where it starts; otherwise sorted by time
  double release = std::numeric_limits<double>::infinity();  // s; free from then on

  bool active(double t) const { return t < release; }
  // Offset at time t: cubic Hermite through the keyframes (tangents from neighbouring keys,
  // zero at both ends), held constant before the first and after the last.
  Vec3 offset(double t) const;
};

// Names of the node attributes that carry handles through topology changes.
inline constexpr const char* kHandleAttr = "handle";  // int32: index into the garment's handles, -1 if none
inline constexpr const char* kAnchorAttr = "anchor";  // Vec3: world position the path offsets apply to

}  // namespace vdc
