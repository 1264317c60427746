// The `remeshing` block: the sizing criteria and bounds, --mode fixed's size (0 when not given).
#include <gtest/gtest.h>

#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

TEST(SceneRemeshing, DefaultsAreTheSizingsAndValuesPassThrough) {
  const RemeshingBlock plain = parse_remeshing(json_block("{}", "remeshing"));
  const SizingParams d;
  EXPECT_EQ(plain.sizing.refine_angle, d.refine_angle);
  EXPECT_EQ(plain.sizing.size_min, d.size_min);
  EXPECT_EQ(plain.sizing.size_max, d.size_max);
  EXPECT_EQ(plain.sizing.aspect_min, d.aspect_min);
  EXPECT_EQ(plain.fixed_size, 0.0);
  const RemeshingBlock given = parse_remeshing(json_block(
      R"({"refine_angle": 0.2, "refine_velocity": 1, "refine_compression": 0.005, "size": [0.02, 0.1], "aspect_min": 0.5, "fixed_size": 0.03})",
      "remeshing"));
  EXPECT_EQ(given.sizing.refine_angle, 0.2);
  EXPECT_EQ(given.sizing.refine_velocity, 1.0);
  EXPECT_EQ(given.sizing.refine_compression, 0.005);
  EXPECT_EQ(given.sizing.size_min, 0.02);
  EXPECT_EQ(given.sizing.size_max, 0.1);
  EXPECT_EQ(given.sizing.aspect_min, 0.5);
  EXPECT_EQ(given.fixed_size, 0.03);
  // One size for both bounds is a uniform target, and allowed.
  EXPECT_EQ(parse_remeshing(json_block(R"({"size": [0.05, 0.05]})", "remeshing")).sizing.size_max, 0.05);
}

TEST(SceneRemeshing, ErrorsNameTheKey) {
  EXPECT_EQ(input_error([] { parse_remeshing(json_block(R"({"size": [0.1, 0.05]})", "remeshing")); }),
            "scene.json:remeshing.size: expected [min, max] with 0 < min <= max (metres)");
  EXPECT_EQ(input_error([] { parse_remeshing(json_block(R"({"aspect_min": 1.5})", "remeshing")); }),
            "scene.json:remeshing.aspect_min: must be at most 1");
  EXPECT_EQ(input_error([] { parse_remeshing(json_block(R"({"fixed_size": 0})", "remeshing")); }),
            "scene.json:remeshing.fixed_size: must be greater than 0, found 0");
}

}  // namespace
}  // namespace vdc
