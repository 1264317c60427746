// The `collision` block: the impact separation and repulsion band follow the thickness unless
// given, and each bound names its key.
#include <gtest/gtest.h>

#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

TEST(SceneCollision, TheSeparationAndTheBandFollowTheThickness) {
  const CollisionParams plain = parse_collision(json_block("{}", "collision"));
  EXPECT_EQ(plain.thickness, 0.002);
  EXPECT_DOUBLE_EQ(plain.impact_separation, 0.0002);
  EXPECT_EQ(plain.repulsion_thickness, 0.004);
  const CollisionParams thick = parse_collision(json_block(R"({"thickness": 0.005})", "collision"));
  EXPECT_DOUBLE_EQ(thick.impact_separation, 0.0005);  // a tenth of it
  EXPECT_EQ(thick.repulsion_thickness, 0.01);         // twice it
  const CollisionParams given = parse_collision(json_block(
      R"({"thickness": 0.003, "impact_separation": 0.001, "repulsion_thickness": 0.003, "repulsion_stiffness": 5, "friction": 0,
          "max_iterations": 7, "untangle_iterations": 0})",
      "collision"));
  EXPECT_EQ(given.impact_separation, 0.001);
  EXPECT_EQ(given.repulsion_thickness, 0.003);
  EXPECT_EQ(given.repulsion_stiffness, 5.0);
  EXPECT_EQ(given.friction, 0.0);
  EXPECT_EQ(given.max_iterations, 7);
  EXPECT_EQ(given.untangle_iterations, 0);
}

TEST(SceneCollision, ErrorsNameTheKey) {
  EXPECT_EQ(input_error([] { parse_collision(json_block(R"({"thickness": 0.001, "impact_separation": 0.002})", "collision")); }),
            "scene.json:collision.impact_separation: must be at most the thickness");
  EXPECT_EQ(input_error([] { parse_collision(json_block(R"({"repulsion_thickness": 0.001})", "collision")); }),
            "scene.json:collision.repulsion_thickness: must be at least the thickness");
  EXPECT_EQ(input_error([] { parse_collision(json_block(R"({"max_iterations": 1001})", "collision")); }),
            "scene.json:collision.max_iterations: must be between 1 and 1000");
  EXPECT_EQ(input_error([] { parse_collision(json_block(R"({"untangle_iterations": -1})", "collision")); }),
            "scene.json:collision.untangle_iterations: must be between 0 and 10000");
}

}  // namespace
}  // namespace vdc
