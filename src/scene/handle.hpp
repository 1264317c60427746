// Handles: garment nodes held in place or moved along a keyframed path, released at a time.
#pragma once
#include <limits>

#include "scene/track.hpp"

namespace vdc {

struct ClothHandle {
  Vec3Track path;  // offsets from the nodes' initial positions; empty: pinned where they start
  double release = std::numeric_limits<double>::infinity();  // s; free from then on

  bool active(double t) const { return t < release; }
  Vec3 offset(double t) const { return path.at(t); }
};

// Names of the node attributes that carry handles through topology changes.
inline constexpr const char* kHandleAttr = "handle";  // int32: index into the garment's handles, -1 if none
inline constexpr const char* kAnchorAttr = "anchor";  // Vec3: world position the path offsets apply to

}  // namespace vdc
