// Reader of channel files (.chan), the camera format of Nuke, Maya and vdcloth's own
// camera.chan: a line per frame of whitespace-separated numbers, the frame, the translation, the
// rotation in degrees (ZXY order) and, optionally, the vertical field of view in degrees.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/math.hpp"

namespace vdc {

struct ChanFrame {
  double frame = 0;
  Vec3 translation = Vec3::Zero();
  Vec3 rotation_degrees = Vec3::Zero();
  std::optional<double> fov_y_degrees;
};

// The frames of a channel file, in increasing frame order; blank lines and lines starting '#'
// skipped. Throws InputError(path, "line L", problem) for a line of other than 7 or 8 numbers,
// a number that is not finite, frames that do not increase, or no frame at all.
std::vector<ChanFrame> read_chan(const std::string& path);
// The same from text already read; `name` is used in errors.
std::vector<ChanFrame> parse_chan(const std::string& text, const std::string& name);

}  // namespace vdc
