// View mode under cameras that stress it: a cut every three frames, a camera that never looks at
// the cloth, a camera inside a skirt with a 1 cm near plane, a camera inside the crowd. Each run
// ends every frame with nothing crossing, no collision fallback and no undone remesh.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"
#include "sim/ensemble.hpp"
#include "support/scene_crossings.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

// scenes/NAME.json with its camera replaced (its relative paths made absolute, written aside).
Scene with_camera(const std::string& name, const nlohmann::json& camera) {
  const std::string source = VDCLOTH_SOURCE_DIR;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(source + "/scenes/" + name + ".json"));
  j["camera"] = camera;
  std::string text = j.dump();
  for (std::size_t at = 0; (at = text.find("\"../", at)) != std::string::npos;) text.replace(at, 4, "\"" + source + "/");
  const fs::path path = fs::temp_directory_path() / ("vdcloth-camera-" + name + "-" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << text;
  Scene scene = load_scene(path.string());
  fs::remove(path);
  return scene;
}

nlohmann::json key(double time, const Vec3& position, const Vec3& target, bool cut = false) {
  nlohmann::json k = {{"time", time}, {"position", {position.x(), position.y(), position.z()}}, {"target", {target.x(), target.y(), target.z()}}};
  if (cut) k["cut"] = true;
  return k;
}

nlohmann::json camera(nlohmann::json keys, double near = 0.05) {
  return {{"fov", 40}, {"width", 1280}, {"height", 720}, {"near", near}, {"far", 60}, {"up", {0, 1, 0}}, {"keys", std::move(keys)}};
}

// Runs `frames` view frames, checking every frame end; returns each frame's statistics (the
// view's face counts are of the mesh the frame started with, before its remesh).
std::vector<FrameStats> run_view(Scene scene, int frames, int threads) {
  Ensemble run(std::move(scene), SimOptions{SimMode::View, threads});
  std::vector<FrameStats> stats;
  for (int f = 0; f < frames; ++f) {
    const FrameStats s = run.step_frame();
    stats.push_back(s);
    for (const auto& part : run.parts()) EXPECT_EQ(test::first_crossing(*part), "") << "frame " << s.frame;
    EXPECT_EQ(s.collision_fallbacks, 0) << "frame " << s.frame;
    EXPECT_EQ(s.remesh_undone, 0) << "frame " << s.frame;
    if (::testing::Test::HasFailure()) break;
  }
  return stats;
}

TEST(CameraStress, ACutEveryThreeFrames) {
  // Front and back of sheet-camera's hanging sheet in turn, a cut every 0.12 s.
  nlohmann::json keys = nlohmann::json::array();
  for (int k = 0; k <= 12; ++k)
    keys.push_back(key(0.12 * k, k % 2 ? Vec3(-1.8, 0.6, -1.4) : Vec3(1.2, 0.6, 1.8), Vec3(0, 0.1, -0.3), k > 0));
  int seen_from_front = 0, seen_from_behind = 0;
  for (const FrameStats& s : run_view(with_camera("sheet-camera", camera(keys)), 36, 1)) {
    seen_from_front += s.visible_faces > s.back_facing_faces;
    seen_from_behind += s.back_facing_faces > s.visible_faces;
  }
  EXPECT_GE(seen_from_front, 12);
  EXPECT_GE(seen_from_behind, 12);
}

TEST(CameraStress, ACameraThatNeverLooksAtTheClothLetsItGoCoarse) {
  // Looking away from the sheet (behind the camera): every face is out of frame, and the sheet
  // goes down towards the count of its size maximum, 1 m^2 in equilateral triangles of 20 cm
  // edges (58), held finer only where it moves (the velocity criterion is kept under eq. 2).
  const std::vector<FrameStats> stats = run_view(with_camera("sheet-camera", camera({key(0, Vec3(0, 0.6, 2), Vec3(0, 0.6, 5))})), 40, 1);
  for (const FrameStats& s : stats) EXPECT_EQ(s.visible_faces + s.back_facing_faces, 0) << "frame " << s.frame;
  EXPECT_LT(stats.back().faces, 4 * 58) << "faces at frame 40";
}

TEST(CameraStress, ACameraInsideTheSkirtWithACentimetreNearPlane) {
  // Between the solo dancer's legs at knee height, looking forward, near plane 1 cm.
  const std::vector<FrameStats> stats = run_view(with_camera("solo-dancer", camera({key(0, Vec3(0, 0.45, 0.02), Vec3(0, 0.5, 1))}, 0.01)), 10, 1);
  EXPECT_EQ(stats.size(), 10u);
}

TEST(CameraStress, ACameraInsideTheCrowd) {
  // Between the crowd's two rows, at head height, looking along them.
  const std::vector<FrameStats> stats = run_view(with_camera("dancers-10", camera({key(0, Vec3(0, 1.5, -1.75), Vec3(4, 1.2, -1.75))}, 0.01)), 3, 2);
  EXPECT_GT(stats.back().visible_faces, 0);
}

}  // namespace
}  // namespace vdc
