// The `collision` block (docs/scene-format.md, "collision"): thickness, repulsion, friction and
// the collision passes' bounds.
#include "scene/scene_blocks.hpp"

namespace vdc {

CollisionParams parse_collision(const JsonValue& j) {
  j.only_keys({"thickness", "impact_separation", "max_iterations", "untangle_iterations", "repulsion_thickness", "repulsion_stiffness",
               "friction"});
  CollisionParams c;
  c.thickness = j.positive_or("thickness", c.thickness);
  c.impact_separation = j.positive_or("impact_separation", 0.1 * c.thickness);
  if (c.impact_separation > c.thickness) j.at("impact_separation").fail("must be at most the thickness");
  c.repulsion_thickness = j.positive_or("repulsion_thickness", 2 * c.thickness);
  if (c.repulsion_thickness < c.thickness) j.at("repulsion_thickness").fail("must be at least the thickness");
  c.repulsion_stiffness = j.positive_or("repulsion_stiffness", c.repulsion_stiffness);
  c.friction = j.non_negative_or("friction", c.friction);
  long long it = j.integer_or("max_iterations", c.max_iterations);
  if (it < 1 || it > 1000) j.at("max_iterations").fail("must be between 1 and 1000");
  c.max_iterations = static_cast<int>(it);
  long long untangle = j.integer_or("untangle_iterations", c.untangle_iterations);
  if (untangle < 0 || untangle > 10000) j.at("untangle_iterations").fail("must be between 0 and 10000");
  c.untangle_iterations = static_cast<int>(untangle);
  return c;
}

}  // namespace vdc
