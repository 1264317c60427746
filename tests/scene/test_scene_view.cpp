// The `view` block: defaults are ViewParams', v_occluded follows v_back unless given, and the
// orderings between factors name the key that breaks them.
#include <gtest/gtest.h>

#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

TEST(SceneView, DefaultsValuesAndTheOccludedFactorFollowingVBack) {
  const ViewParams plain = parse_view(json_block("{}", "view"));
  const ViewParams d;
  EXPECT_EQ(plain.v_back, d.v_back);
  EXPECT_EQ(plain.v_out, d.v_out);
  EXPECT_EQ(plain.settle, d.settle);
  EXPECT_EQ(plain.v_occluded, d.v_back);
  const ViewParams given = parse_view(json_block(
      R"({"v_back": 0.4, "v_out": 0.1, "l_min": 2, "l_max": 30, "settle": 0, "occlusion": false, "occlusion_erosion": 3,
          "gathering": 0.5, "coarse_damping": 2, "far_remesh_every": 4, "far_after": 0.5})",
      "view"));
  EXPECT_EQ(given.v_back, 0.4);
  EXPECT_EQ(given.v_out, 0.1);
  EXPECT_EQ(given.v_occluded, 0.4);
  EXPECT_EQ(given.l_min, 2.0);
  EXPECT_EQ(given.l_max, 30.0);
  EXPECT_EQ(given.settle, 0.0);
  EXPECT_FALSE(given.occlusion);
  EXPECT_EQ(given.occlusion_erosion, 3);
  EXPECT_EQ(given.gathering, 0.5);
  EXPECT_EQ(given.coarse_damping, 2.0);
  EXPECT_EQ(given.far_remesh_every, 4);
  EXPECT_EQ(given.far_after, 0.5);
  EXPECT_EQ(plain.far_remesh_every, 1);  // no level of detail unless asked
  EXPECT_EQ(parse_view(json_block(R"({"v_back": 0.4, "v_out": 0.1, "v_occluded": 0.2})", "view")).v_occluded, 0.2);
}

TEST(SceneView, ErrorsNameTheKey) {
  auto error = [](const std::string& text) { return input_error([&] { parse_view(json_block(text, "view")); }); };
  EXPECT_EQ(error(R"({"v_back": 1.5})"), "scene.json:view.v_back: must be at most 1");
  EXPECT_EQ(error(R"({"v_back": 0.2, "v_out": 0.3})"), "scene.json:view.v_out: must be at most v_back");
  EXPECT_EQ(error(R"({"l_min": 5, "l_max": 2})"), "scene.json:view.l_max: must be 0 (no ceiling) or at least l_min");
  EXPECT_EQ(error(R"({"l_min": 5, "l_max": 0})"), "");
  EXPECT_EQ(error(R"({"occlusion_erosion": 17})"), "scene.json:view.occlusion_erosion: must be an integer from 0 to 16 (pixels)");
  EXPECT_EQ(error(R"({"far_remesh_every": 0})"), "scene.json:view.far_remesh_every: must be an integer from 1 (every frame) to 100 (frames)");
  EXPECT_EQ(error(R"({"far_remesh_every": 2.5})").rfind("scene.json:view.far_remesh_every: ", 0), 0u);
  EXPECT_EQ(error(R"({"far_after": -1})").rfind("scene.json:view.far_after: ", 0), 0u);
  EXPECT_EQ(error(R"({"v_back": 0.4, "v_out": 0.2, "v_occluded": 0.1})"), "scene.json:view.v_occluded: must be at least v_out");
}

}  // namespace
}  // namespace vdc
