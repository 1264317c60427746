// The camera export: Euler angles against hand-computed poses and rebuilt into the camera's
// basis, shots and cuts by frame, and the files' contents.
#include "output/camera_export.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace vdc {
namespace {

Camera looking(const Vec3& from, const Vec3& at, const Vec3& up = Vec3(0, 1, 0)) {
  Camera c;
  c.position = from;
  c.target = at;
  c.up = up;
  return c;
}

Mat3 rotation_x(double a) { return Eigen::AngleAxisd(a, Vec3::UnitX()).toRotationMatrix(); }
Mat3 rotation_y(double a) { return Eigen::AngleAxisd(a, Vec3::UnitY()).toRotationMatrix(); }
Mat3 rotation_z(double a) { return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix(); }

void expect_near(const Vec3& a, const Vec3& b, double tol) { EXPECT_LT((a - b).norm(), tol) << a.transpose() << " vs " << b.transpose(); }

TEST(CameraExport, EulerAnglesOfHandComputedPoses) {
  expect_near(zxy_euler_degrees(looking({0, 0, 5}, {0, 0, 0})), Vec3(0, 0, 0), 1e-12);    // down -z
  expect_near(zxy_euler_degrees(looking({5, 0, 0}, {0, 0, 0})), Vec3(0, 90, 0), 1e-12);   // down -x: turned left
  expect_near(zxy_euler_degrees(looking({0, 5, 5}, {0, 0, 0})), Vec3(-45, 0, 0), 1e-12);  // 45 degrees down
  expect_near(zxy_euler_degrees(looking({0, 0, 5}, {0, 0, 0}, {1, 0, 0})), Vec3(0, 0, -90), 1e-12);  // rolled: +x up
  expect_near(zxy_euler_degrees(looking({0, 5, 0}, {0, 0, 0}, {0, 0, -1})), Vec3(-90, 0, 0), 1e-9);  // straight down
}

// Any pose: Ry(y) Rx(x) Rz(z) of the angles is the camera's basis (right, up, backwards).
TEST(CameraExport, EulerAnglesRebuildTheBasis) {
  const std::vector<Camera> poses = {looking({1.6, 1.2, 2.8}, {0, 1, 0}), looking({-0.6, 0.5, -1.2}, {0, 0.55, 0}),
                                     looking({-3.2, 1.5, 1.0}, {0, 0.9, 0}, Vec3(0.3, 1, 0.1)),
                                     looking({0.2, -2, 0.1}, {0, 0, 0}, Vec3(1, 0.2, 0))};
  for (const Camera& c : poses) {
    const Vec3 a = zxy_euler_degrees(c) * M_PI / 180.0;
    const Mat3 r = rotation_y(a.y()) * rotation_x(a.x()) * rotation_z(a.z());
    const auto [right, up, forward] = c.basis();
    expect_near(r.col(0), right, 1e-12);
    expect_near(r.col(1), up, 1e-12);
    expect_near(r.col(2), -forward, 1e-12);
  }
}

CameraPath two_shots() {
  Camera lens;
  lens.fov_y_degrees = 30;
  lens.width = 1280;
  lens.height = 720;
  return CameraPath(lens, {CameraKey{0, {0, 1, 5}, {0, 1, 0}, false}, CameraKey{0.5, {1, 1, 5}, {0, 1, 0}, false},
                           CameraKey{1.0, {0, 2, -4}, {0, 1, 0}, true}, CameraKey{2.0, {1, 2, -4}, {0, 1, 0}, false}});
}

// Frame 4 (t = 1 s at 0.25 s a frame) is the first of the second shot: its cut flag, its shot
// number, and the pose of the cut's key.
TEST(CameraExport, FramesKnowTheirShotAndTheirCut) {
  const std::vector<CameraFrame> frames = camera_frames(two_shots(), 0.25, 8);
  ASSERT_EQ(frames.size(), 9u);
  for (const CameraFrame& f : frames) {
    EXPECT_EQ(f.frame * 0.25, f.time);
    EXPECT_EQ(f.shot, f.frame < 4 ? 0 : 1) << f.frame;
    EXPECT_EQ(f.cut, f.frame == 4) << f.frame;
  }
  expect_near(frames[4].camera.position, Vec3(0, 2, -4), 1e-12);
  expect_near(frames[0].camera.position, Vec3(0, 1, 5), 1e-12);
  expect_near(frames[8].camera.position, Vec3(1, 2, -4), 1e-12);
}

std::string temp_dir() {
  const std::string dir = testing::TempDir() + "vdcloth_camera_export_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(CameraExport, FilesHoldEveryFrame) {
  const std::string dir = temp_dir();
  write_camera_files(two_shots(), 0.25, 8, dir);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/camera.json"));
  EXPECT_EQ(j["width"], 1280);
  EXPECT_EQ(j["fov_y_degrees"], 30.0);
  // Horizontal field of view: 2 atan(tan(15 degrees) * 16 / 9).
  EXPECT_NEAR(j["fov_x_degrees"].get<double>(), 2 * std::atan(std::tan(M_PI / 12) * 16.0 / 9.0) * 180 / M_PI, 1e-12);
  ASSERT_EQ(j["frames"].size(), 9u);
  EXPECT_EQ(j["frames"][4]["cut"], true);
  EXPECT_EQ(j["frames"][4]["shot"], 1);
  expect_near(Vec3(j["frames"][4]["position"][0], j["frames"][4]["position"][1], j["frames"][4]["position"][2]), Vec3(0, 2, -4), 1e-12);
  EXPECT_EQ(j["frames"][3]["cut"], false);

  // camera.chan: frame, translation, rotation (degrees), vertical fov. Frame 4 looks from
  // (0, 2, -4) at (0, 1, 0): heading 180 degrees, pitch -atan(1 / 4).
  std::ifstream chan(dir + "/camera.chan");
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(chan, line);) {
    std::istringstream in(line);
    rows.emplace_back();
    for (double v; in >> v;) rows.back().push_back(v);
  }
  ASSERT_EQ(rows.size(), 9u);
  for (const auto& row : rows) ASSERT_EQ(row.size(), 8u);
  EXPECT_EQ(rows[4][0], 4);
  EXPECT_EQ(rows[4][1], 0);
  EXPECT_EQ(rows[4][2], 2);
  EXPECT_EQ(rows[4][3], -4);
  EXPECT_NEAR(rows[4][4], -std::atan(0.25) * 180 / M_PI, 1e-6);
  EXPECT_NEAR(std::abs(rows[4][5]), 180, 1e-6);
  EXPECT_NEAR(rows[4][6], 0, 1e-6);
  EXPECT_EQ(rows[4][7], 30);

  remove_camera_files(dir);
  EXPECT_FALSE(std::filesystem::exists(dir + "/camera.json"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/camera.chan"));
  std::filesystem::remove_all(dir);
}

// A focus that follows the target: each frame's focus distance is the target's distance, 5 m
// at frame 0 and sqrt(1 + 16) at the cut (frame 4); a fixed focus is the same every frame.
TEST(CameraExport, EachFrameHoldsItsFocus) {
  const std::string dir = temp_dir();
  Camera lens;
  lens.focus_on_target = true;
  lens.f_stop = 2;
  const CameraPath follow(lens, two_shots().keys());
  write_camera_files(follow, 0.25, 8, dir);
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/camera.json"));
  EXPECT_EQ(j["depth_of_field"]["follows_target"], true);
  EXPECT_EQ(j["depth_of_field"]["f_stop"], 2.0);
  EXPECT_DOUBLE_EQ(j["depth_of_field"]["focus_distance"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(j["frames"][0]["focus_distance"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(j["frames"][4]["focus_distance"].get<double>(), std::sqrt(17.0));
  lens.focus_on_target = false;
  lens.focus_distance = 3;
  write_camera_files(CameraPath(lens, two_shots().keys()), 0.25, 8, dir);
  j = nlohmann::json::parse(std::ifstream(dir + "/camera.json"));
  EXPECT_EQ(j["depth_of_field"]["follows_target"], false);
  for (const auto& frame : j["frames"]) EXPECT_EQ(frame["focus_distance"], 3.0);
  write_camera_files(two_shots(), 0.25, 8, dir);  // a pinhole: no focus anywhere
  j = nlohmann::json::parse(std::ifstream(dir + "/camera.json"));
  EXPECT_FALSE(j.contains("depth_of_field"));
  EXPECT_FALSE(j["frames"][0].contains("focus_distance"));
  std::filesystem::remove_all(dir);
}

TEST(CameraExport, AnUnwritableDirectoryIsAnOutputError) {
  EXPECT_THROW(write_camera_files(two_shots(), 0.25, 8, temp_dir() + "/missing/sub"), OutputError);
}

}  // namespace
}  // namespace vdc
