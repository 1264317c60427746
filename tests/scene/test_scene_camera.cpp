// The `camera` block and the `cameras` list: the lens's defaults and values, the keys in order
// with their cuts, the focus following the target, a stereo camera's eyes, named cameras, and
// errors naming the key (a key's by its index).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "output/camera_export.hpp"
#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"
#include "support/text.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;
namespace fs = std::filesystem;

// The cameras of a scene whose top level is `top`.
std::vector<ShotCamera> cameras(const std::string& top) { return parse_cameras(json_block(top, ""), "", 0.04); }

// The one camera of a `camera` block.
CameraPath parse_camera(const JsonValue& block) {
  const std::vector<ShotCamera> got = cameras(R"({"camera": )" + block.raw().dump() + "}");
  EXPECT_EQ(got.size(), 1u);
  EXPECT_EQ(got.front().name, "");
  return got.front().path;
}

CameraPath camera(const std::string& lens_keys) {
  return parse_camera(json_block("{" + lens_keys + R"("keys": [{"time": 0, "position": [0, 1, 4], "target": [0, 1, 0]}]})", "camera"));
}

const std::string kKeys = R"("keys": [{"time": 0, "position": [0, 1, 4], "target": [0, 1, 0]}, {"time": 1, "position": [4, 1, 0], "target": [0, 1, 0]}])";

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

// A stereo camera is its two eyes, half the interaxial distance either side of the camera
// along its right vector at every time, looking the same way; named left and right, or after
// their camera.
TEST(SceneCamera, AStereoCameraIsItsTwoEyes) {
  const std::vector<ShotCamera> pair = cameras(R"({"camera": {"stereo": {"interaxial": 0.065}, )" + kKeys + "}}");
  ASSERT_EQ(pair.size(), 2u);
  EXPECT_EQ(pair[0].name, "left");
  EXPECT_EQ(pair[1].name, "right");
  const CameraPath centre = cameras(R"({"camera": {)" + kKeys + "}}").front().path;
  for (double t : {0.0, 0.37, 1.0}) {
    const Camera c = centre.at(t), left = pair[0].path.at(t), right = pair[1].path.at(t);
    const Vec3 side = c.basis()[0];
    EXPECT_NEAR((left.position - (c.position - 0.0325 * side)).norm(), 0.0, 1e-12) << t;
    EXPECT_NEAR((right.position - (c.position + 0.0325 * side)).norm(), 0.0, 1e-12) << t;
    EXPECT_NEAR((right.basis()[2] - c.basis()[2]).norm(), 0.0, 1e-12) << "parallel eyes, t " << t;
    EXPECT_NEAR((left.basis()[2] - c.basis()[2]).norm(), 0.0, 1e-12) << "parallel eyes, t " << t;
  }
  const std::vector<ShotCamera> named = cameras(R"({"cameras": [{"name": "a", )" + kKeys + R"(}, {"name": "b", "stereo": {"interaxial": 0.1}, )" +
                                                kKeys + "}]}");
  ASSERT_EQ(named.size(), 3u);
  EXPECT_EQ(named[0].name, "a");
  EXPECT_EQ(named[1].name, "b_left");
  EXPECT_EQ(named[2].name, "b_right");
  EXPECT_EQ(named[2].path.lens().eye_offset, 0.05);
}

TEST(SceneCamera, NamedCamerasEachWithTheirOwnLensAndKeys) {
  const std::vector<ShotCamera> two = cameras(R"({"cameras": [{"name": "wide", )" + kKeys + R"(},
      {"name": "close", "fov": 20, "width": 640, "height": 480, "keys": [{"time": 0, "position": [1, 1, 1], "target": [0, 1, 0]},
       {"time": 0.5, "position": [0, 1, 2], "target": [0, 1, 0], "cut": true}]}]})");
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].name, "wide");
  EXPECT_EQ(two[0].path.lens().fov_y_degrees, Camera{}.fov_y_degrees);
  EXPECT_TRUE(two[0].path.cuts_in(0, 2).empty());
  EXPECT_EQ(two[1].name, "close");
  EXPECT_EQ(two[1].path.lens().fov_y_degrees, 20.0);
  EXPECT_EQ(two[1].path.lens().width, 640);
  EXPECT_EQ(two[1].path.cuts_in(0, 2), std::vector<double>{0.5});
  EXPECT_TRUE(cameras("{}").empty());
}

TEST(SceneCamera, CamerasErrorsNameTheKey) {
  auto error = [](const std::string& text) { return input_error([&] { parse_cameras(json_block(text, ""), "", 0.04); }); };
  const std::string one = R"({"name": "a", )" + kKeys + "}";
  EXPECT_EQ(error(R"({"cameras": [)" + one + ", " + one + "]}"), "scene.json:cameras[1].name: name 'a' is used twice");
  EXPECT_EQ(error(R"({"camera": {)" + kKeys + R"(}, "cameras": [)" + one + "]}"),
            "scene.json:cameras: a scene has either one \"camera\" or a list of \"cameras\", not both");
  EXPECT_EQ(error(R"({"cameras": []})"), "scene.json:cameras: lists no camera: give at least one, or leave \"cameras\" out");
  EXPECT_EQ(error(R"({"cameras": [{)" + kKeys + "}]}"), "scene.json:cameras[0].name: required key is missing");
  EXPECT_EQ(error(R"({"cameras": [{"name": "a b", )" + kKeys + "}]}"),
            "scene.json:cameras[0].name: names must be non-empty, without spaces, dots or slashes (they name output files)");
  EXPECT_EQ(error(R"({"cameras": [{"name": "b_left", )" + kKeys + R"(}, {"name": "b", "stereo": {"interaxial": 0.1}, )" + kKeys + "}]}"),
            "scene.json:cameras[1].name: name 'b_left' is used twice");
  EXPECT_EQ(error(R"({"camera": {"name": "a", )" + kKeys + "}}"),
            "scene.json:camera.name: the one camera has no name: name cameras in a \"cameras\" list");
  EXPECT_EQ(error(R"({"camera": {"stereo": {"interaxial": 0}, )" + kKeys + "}}"),
            "scene.json:camera.stereo.interaxial: must be greater than 0, found 0");
  EXPECT_EQ(error(R"({"camera": {"stereo": {}, )" + kKeys + "}}"), "scene.json:camera.stereo.interaxial: required key is missing");
}

}  // namespace
}  // namespace vdc

namespace vdc {
namespace {

// A camera that turns, rolls and zooms, written as a run writes camera.chan, then read back as a
// scene's camera: the same view (position and basis) and field of view at every frame within
// 1e-9, and lines without a field of view take the lens's.
TEST(SceneCamera, AChannelFileReadsBackAsTheSameViewEveryFrame) {
  Camera lens;
  lens.fov_y_degrees = 35;
  std::vector<CameraKey> keys(3);
  keys[0] = {0.0, Vec3(0, 1.5, 4), Vec3(0, 1, 0), false, Vec3(0, 1, 0), 35.0};
  keys[1] = {1.0, Vec3(3, 2, 2), Vec3(0, 0.8, 0), false, Vec3(0.3, 1, 0.1), 50.0};
  keys[2] = {2.0, Vec3(-1, 0.5, 3), Vec3(0.2, 1, 0), false, Vec3(-0.5, 1, 0), 20.0};
  const CameraPath written(lens, keys);
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_chan_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const double frame_time = 0.04;
  write_camera_files(written, frame_time, 50, dir.string());
  std::ofstream(dir / "scene.json") << "{}";
  const std::vector<ShotCamera> read =
      parse_cameras(json_block(R"({"camera": {"chan": "camera.chan", "fov": 35}})", ""), (dir / "scene.json").string(), frame_time);
  ASSERT_EQ(read.size(), 1u);
  double worst = 0;
  for (int f = 0; f <= 50; ++f) {
    const Camera a = written.at(f * frame_time), b = read[0].path.at(f * frame_time);
    const auto ba = a.basis(), bb = b.basis();
    for (int k = 0; k < 3; ++k) worst = std::max(worst, (ba[static_cast<std::size_t>(k)] - bb[static_cast<std::size_t>(k)]).norm());
    worst = std::max({worst, (a.position - b.position).norm(), std::abs(a.fov_y_degrees - b.fov_y_degrees)});
  }
  EXPECT_LT(worst, 1e-9);
  // Nuke's files start at frame 1001 and may leave the field of view out.
  std::ofstream(dir / "nuke.chan") << "# frame tx ty tz rx ry rz\n1001 0 1 5 0 90 0\n1002 0 1 5 0 90 30\n";
  const std::vector<ShotCamera> nuke =
      parse_cameras(json_block(R"({"camera": {"chan": "nuke.chan", "first_frame": 1001, "fov": 30}})", ""), (dir / "scene.json").string(), frame_time);
  const Camera start = nuke[0].path.at(0.0), rolled = nuke[0].path.at(frame_time);
  EXPECT_LT((start.basis()[2] - Vec3(-1, 0, 0)).norm(), 1e-12);  // heading 90: looking down -x
  EXPECT_LT((rolled.basis()[1] - Vec3(0, std::cos(M_PI / 6), std::sin(M_PI / 6))).norm(), 1e-12);  // rolled 30 degrees about its view
  EXPECT_EQ(rolled.fov_y_degrees, 30);
  auto error = [&](const std::string& text) {
    return input_error([&] { parse_cameras(json_block(text, ""), (dir / "scene.json").string(), frame_time); });
  };
  std::ofstream(dir / "short.chan") << "0 1 2 3\n";
  EXPECT_EQ(error(R"({"camera": {"chan": "short.chan"}})"),
            "scene.json:camera.chan: " + (dir / "short.chan").string() +
                ":line 1: expected 7 or 8 numbers (frame, translation, rotation and field of view), found 4");
  std::ofstream(dir / "back.chan") << "2 0 0 0 0 0 0\n1 0 0 0 0 0 0\n";
  EXPECT_TRUE(test::contains(error(R"({"camera": {"chan": "back.chan"}})"), "line 2: frame numbers must increase"));
  EXPECT_TRUE(test::contains(error(R"({"camera": {"chan": "camera.chan", "keys": []}})"), "leave out \"keys\" and \"up\""));
  EXPECT_TRUE(test::contains(error(R"({"camera": {"chan": "camera.chan", "focus_distance": "target"}})"), "no target to focus on"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vdc
