// The `air` block: nothing given is still air, values pass through, a negative drag is named.
#include <gtest/gtest.h>

#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

TEST(SceneAir, DefaultsAreStillAirAndValuesPassThrough) {
  const AirSpec still = parse_air(json_block("{}", "air"));
  EXPECT_EQ(still.damping, 0.0);
  EXPECT_EQ(still.drag, 0.0);
  EXPECT_EQ(still.wind, Vec3::Zero());
  const AirSpec windy = parse_air(json_block(R"({"damping": 0.5, "drag": 1.2, "wind": [3, 0, -1]})", "air"));
  EXPECT_EQ(windy.damping, 0.5);
  EXPECT_EQ(windy.drag, 1.2);
  EXPECT_EQ(windy.wind, Vec3(3, 0, -1));
}

TEST(SceneAir, ErrorsNameTheKey) {
  EXPECT_EQ(input_error([] { parse_air(json_block(R"({"drag": -1})", "air")); }), "scene.json:air.drag: must not be negative, found -1");
  EXPECT_NE(input_error([] { parse_air(json_block(R"({"gust": 1})", "air")); }).find("scene.json:air.gust: unknown key"), std::string::npos);
}

}  // namespace
}  // namespace vdc
