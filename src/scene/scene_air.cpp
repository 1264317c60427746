// The `air` block (docs/scene-format.md, "air"): damping, drag and wind.
#include "scene/scene_blocks.hpp"

namespace vdc {

AirSpec parse_air(const JsonValue& j) {
  j.only_keys({"damping", "drag", "wind"});
  AirSpec air;
  air.damping = j.non_negative_or("damping", 0.0);
  air.drag = j.non_negative_or("drag", 0.0);
  air.wind = j.vec3_or("wind", Vec3::Zero());
  return air;
}

}  // namespace vdc
