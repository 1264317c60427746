// The `camera` block: the lens's defaults and values, the keys in order with their cuts, the
// focus following the target, and errors naming the key (a key's by its index).
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

CameraPath camera(const std::string& lens_keys) {
  return parse_camera(json_block("{" + lens_keys + R"("keys": [{"time": 0, "position": [0, 1, 4], "target": [0, 1, 0]}]})", "camera"));
}

TEST(SceneCamera, TheLensDefaultsAndValues) {
  const Camera plain = camera("").lens();
  const Camera d;
  EXPECT_EQ(plain.fov_y_degrees, d.fov_y_degrees);
  EXPECT_EQ(plain.width, d.width);
  EXPECT_EQ(plain.height, d.height);
  EXPECT_EQ(plain.up, d.up);
  EXPECT_EQ(plain.focus_distance, 0.0);
  EXPECT_FALSE(plain.focus_on_target);
  const Camera given = camera(R"("fov": 30, "width": 640, "height": 480, "near": 0.5, "far": 20, "up": [1, 0, 0],
                                 "focus_distance": "target", "f_stop": 4, "sensor_height": 36, "shutter": 0.5, )")
                           .lens();
  EXPECT_EQ(given.fov_y_degrees, 30.0);
  EXPECT_EQ(given.width, 640);
  EXPECT_EQ(given.height, 480);
  EXPECT_EQ(given.near, 0.5);
  EXPECT_EQ(given.far, 20.0);
  EXPECT_EQ(given.up, Vec3(1, 0, 0));
  EXPECT_TRUE(given.focus_on_target);
  EXPECT_EQ(given.f_stop, 4.0);
  EXPECT_EQ(given.sensor_height_mm, 36.0);
  EXPECT_EQ(given.shutter, 0.5);
}

TEST(SceneCamera, KeysInOrderWithTheirCuts) {
  const CameraPath path = parse_camera(json_block(R"({"keys": [{"time": 0, "position": [0, 1, 4], "target": [0, 1, 0]},
      {"time": 2, "position": [4, 1, 0], "target": [0, 1, 0]}, {"time": 3, "position": [0, 3, 3], "target": [0, 1, 0], "cut": true}]})",
                                                  "camera"));
  ASSERT_EQ(path.keys().size(), 3u);
  EXPECT_EQ(path.keys()[1].position, Vec3(4, 1, 0));
  EXPECT_FALSE(path.keys()[1].cut);
  EXPECT_TRUE(path.keys()[2].cut);
  EXPECT_EQ(path.cuts_in(0, 4), std::vector<double>{3.0});
}

TEST(SceneCamera, ErrorsNameTheKey) {
  auto error = [](const std::string& text) { return input_error([&] { parse_camera(json_block(text, "camera")); }); };
  EXPECT_EQ(error(R"({"keys": []})"), "scene.json:camera.keys: a camera needs at least one key");
  EXPECT_EQ(error(R"({"fov": 180, "keys": []})"), "scene.json:camera.fov: must be below 180 degrees");
  EXPECT_EQ(error(R"({"near": 2, "far": 1, "keys": []})"), "scene.json:camera.far: must be beyond near");
  EXPECT_EQ(error(R"({"keys": [{"time": 1, "position": [0, 0, 1], "target": [0, 0, 0]}, {"time": 1, "position": [0, 0, 2], "target": [0, 0, 0]}]})"),
            "scene.json:camera.keys[1].time: keyframe times must increase");
  EXPECT_EQ(error(R"({"keys": [{"time": 0, "position": [0, 5, 0], "target": [0, 0, 0]}]})"),
            "scene.json:camera.keys[0].target: the view direction is parallel to the camera's up vector");
  // 40 degrees on a 24 mm sensor: a focal length of 12 / tan(20 degrees) = 32.97 mm, so a focus
  // at 3 cm is inside the lens.
  const std::string inside = error(R"({"focus_distance": 0.03, "keys": []})");
  EXPECT_EQ(inside.rfind("scene.json:camera.focus_distance: must be beyond the focal length (32.96", 0), 0u) << inside;
  EXPECT_NEAR(Camera{}.focal_length_mm(), 12 / std::tan(20 * M_PI / 180), 1e-9);
}

}  // namespace
}  // namespace vdc
