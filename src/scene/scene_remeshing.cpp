// The `remeshing` block (docs/scene-format.md, "remeshing"): the adaptive sizing's criteria and
// bounds, and --mode fixed's edge size.
#include "scene/scene_blocks.hpp"

namespace vdc {

RemeshingBlock parse_remeshing(const JsonValue& j) {
  j.only_keys({"refine_angle", "refine_velocity", "refine_compression", "size", "aspect_min", "fixed_size"});
  RemeshingBlock block;
  SizingParams& p = block.sizing;
  p.refine_angle = j.positive_or("refine_angle", p.refine_angle);
  p.refine_velocity = j.positive_or("refine_velocity", p.refine_velocity);
  p.refine_compression = j.positive_or("refine_compression", p.refine_compression);
  if (auto size = j.find("size")) {
    Vec2 range = size->vec2();
    if (!(range.x() > 0 && range.y() >= range.x())) size->fail("expected [min, max] with 0 < min <= max (metres)");
    p.size_min = range.x();
    p.size_max = range.y();
  }
  p.aspect_min = j.positive_or("aspect_min", p.aspect_min);
  if (p.aspect_min > 1) j.at("aspect_min").fail("must be at most 1");
  block.fixed_size = j.positive_or("fixed_size", 0.0);
  return block;
}

}  // namespace vdc
