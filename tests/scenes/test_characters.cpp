// The character shots (karate, solo-dancer, dancers-10, rigged-wuson): garments start valid and clear of the
// bodies and of each other, and a short run in each mode ends every frame with no garment
// crossing a body, another garment (karate's layers stay ordered) or itself, by the exact
// triangle-triangle test.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "collision/distance.hpp"
#include "scene/scene.hpp"
#include "sim/ensemble.hpp"
#include "support/scene_crossings.hpp"

namespace vdc {
namespace {

using test::first_crossing;

// The garments' meshes of a run's one part, as a run resumed from them takes them.
ResumePoint meshes_now(const Ensemble& run) {
  const Simulation& part = *run.parts().front();
  ResumePoint point;
  point.frame = run.frame();
  for (std::size_t g = 0; g < part.scene().garments.size(); ++g) {
    point.names.push_back(part.scene().garments[g].name);
    point.garments.push_back(part.garment_mesh(g));
  }
  return point;
}

Scene character_scene(const std::string& name, double test_fixed_size) {
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/" + name + ".json");
  // The test's fixed mesh: the scenes' baseline is their 10 mm size_min, minutes a frame.
  scene.fixed_size = test_fixed_size;
  return scene;
}

// One scene in one mode, the first `frames` frames. ctest runs two tests at a time on CI's two
// cores, so each run takes one thread, except the crowd, whose parts share the two.
// `then_view`: an adaptive run then checks the view run too, from its own meshes where the view
// settles (until then a view run sizes as the adaptive run does) to the same frame.
struct CharacterRun {
  std::string scene;
  SimMode mode;
  int frames;
  double test_fixed_size;
  int threads;
  bool then_view = false;
};

void PrintTo(const CharacterRun& run, std::ostream* os) {
  *os << run.scene << " " << sim_mode_name(run.mode) << (run.then_view ? " then view" : "") << ", " << run.frames << " frames, " << run.threads
      << " threads";
}

std::string run_name(const testing::TestParamInfo<CharacterRun>& info) {
  std::string name = info.param.scene + "_" + sim_mode_name(info.param.mode);
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

class CharacterShot : public testing::TestWithParam<CharacterRun> {};

TEST_P(CharacterShot, NoGarmentCrossesABodyAnotherGarmentOrItselfAtAnyFrameEnd) {
  const CharacterRun& p = GetParam();
  Scene scene = character_scene(p.scene, p.test_fixed_size);
  // A view run shorter than the scene's settle would be the adaptive run throughout: coarsen
  // from the first frame, so that what is checked is the view's coarse cloth.
  if (p.frames * scene.frame_time <= scene.view.settle) scene.view.settle = 0;
  const int settle = static_cast<int>(scene.view.settle_frames(scene.frame_time));
  Ensemble run(std::move(scene), SimOptions{p.mode, p.threads});
  for (const auto& part : run.parts()) ASSERT_EQ(first_crossing(*part), "") << "at the start";
  std::optional<ResumePoint> settled;
  for (int f = 0; f < p.frames; ++f) {
    if (p.then_view && run.frame() == settle) settled = meshes_now(run);
    const FrameStats s = run.step_frame();
    for (const auto& part : run.parts()) ASSERT_EQ(first_crossing(*part), "") << "frame " << s.frame;
  }
  if (!p.then_view) return;
  ASSERT_TRUE(settled) << "the view settles after the run's last frame";
  Ensemble view(character_scene(p.scene, p.test_fixed_size), SimOptions{SimMode::View, p.threads}, Simulation::Log{}, {*settled},
                "the adaptive run where the view settles");
  while (view.frame() < p.frames) {
    const FrameStats s = view.step_frame();
    for (const auto& part : view.parts()) ASSERT_EQ(first_crossing(*part), "") << "view, frame " << s.frame;
  }
}

// karate's three layers stay ordered; the solo dress and the ten dresses never cross anything.
// karate's view run (settling at frame 12) goes on from its adaptive run's frame 12.
// solo-dancer's adaptive and view runs are ViewFidelity's (test_view_fidelity.cpp), which checks
// both for crossings at every frame end over 25 frames as it checks the straps, its view run
// switching to coarse at frame 5 (the view runs here at the scenes' settle, frame 12).
std::vector<CharacterRun> character_runs() {
  std::vector<CharacterRun> runs;
  for (SimMode mode : {SimMode::Fixed, SimMode::Adaptive, SimMode::View}) {
    if (mode != SimMode::View) runs.push_back({"karate", mode, 20, 0.05, 1, mode == SimMode::Adaptive});
    if (mode == SimMode::Fixed) runs.push_back({"solo-dancer", mode, 20, 0.05, 1});
    runs.push_back({"dancers-10", mode, 5, 0.06, 2});
  }
  // A rigged character from an artist's file (Debian's assimp-testmodels), skinned by its own
  // weights, its open skin of 54 pieces repaired for collisions: its 0.4 s of pre-roll and 17
  // frames of its walk, then view from where it settles (frame 12) to frame 17.
  runs.push_back({"rigged-wuson", SimMode::Adaptive, 27, 0.05, 1, true});
  return runs;
}

INSTANTIATE_TEST_SUITE_P(Characters, CharacterShot, testing::ValuesIn(character_runs()), run_name);

// As loaded: every garment a valid mesh, and nothing crossing or nearer than twice the collision
// thickness (garment nodes to body and to other garments' faces, by the BVH-free brute force).
TEST(Characters, GarmentsStartValidAndClear) {
  for (const std::string name : {"karate", "solo-dancer", "dancers-10"}) {
    Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/" + name + ".json");
    const double clearance = 2 * scene.collision.thickness;
    for (const Scene& part : split_groups(std::move(scene))) {
      EXPECT_EQ(first_crossing(part), "") << name;
      for (const GarmentSpec& g : part.garments) {
        EXPECT_TRUE(g.mesh.validate().ok()) << name << " " << g.name;
        auto nearest = [&](const Mesh& other) {
          double d = 1e9;
          for (NodeId n : g.mesh.nodes())
            for (FaceId f : other.faces()) {
              const Vec3 &a = other.x(other.face_node(f, 0)), &b = other.x(other.face_node(f, 1)), &c = other.x(other.face_node(f, 2));
              const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - d, hi = a.cwiseMax(b).cwiseMax(c).array() + d;
              const Vec3& p = g.mesh.x(n);
              if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
              d = std::min(d, point_triangle_distance(p, a, b, c));
            }
          return d;
        };
        for (const ObstacleSpec& o : part.obstacles) EXPECT_GT(nearest(o.mesh), clearance) << name << " " << g.name << " to " << o.name;
        for (const GarmentSpec& h : part.garments) {
          if (&h == &g) continue;
          EXPECT_GT(nearest(h.mesh), clearance) << name << " " << g.name << " to " << h.name;
        }
      }
    }
  }
}

// solo-dancer and karate with their motion swapped for a CMU capture (assimp-testmodels'
// 01_01.bvh: a T-pose reference frame, then forward jumps), at the capture's documented scale
// and nothing else changed: the garments are made for the capture's figure in its T-pose (karate's
// held hakama and belt inside the arms' reach), the pre-roll brings the figure into its first
// pose, and 40 frames in adaptive mode and the 28 of view mode from where the view settles end
// with nothing crossing and no frame far slower than the run's median (the test's mesh is coarser
// than the scenes': 2 cm at the finest).
class CaptureShot : public testing::TestWithParam<std::string> {};

// The frames from where `run` is to frame 40: none ends with a crossing or a collision
// fallback, and none takes 20 times the median frame. `before_frame` sees the run before each.
void clear_to_frame_forty(Ensemble& run, SimMode mode, const std::function<void(const Ensemble&)>& before_frame = {}) {
  const Simulation& part = *run.parts().front();
  std::vector<double> seconds;
  while (run.frame() < 40) {
    if (before_frame) before_frame(run);
    const FrameStats s = run.step_frame();
    seconds.push_back(s.seconds);
    ASSERT_EQ(first_crossing(part), "") << sim_mode_name(mode) << " frame " << s.frame;
    EXPECT_EQ(s.collision_fallbacks, 0) << sim_mode_name(mode) << " frame " << s.frame;
  }
  std::sort(seconds.begin(), seconds.end());
  EXPECT_LT(seconds.back(), 20 * seconds[seconds.size() / 2]) << sim_mode_name(mode);
}

TEST_P(CaptureShot, ACaptureDrivesTheGarmentsWithoutCrossings) {
  const std::string capture = "/usr/share/assimp/models/BVH/01_01.bvh";
  if (!std::ifstream(capture)) GTEST_SKIP() << capture << " is missing (scripts/install-deps.sh installs assimp-testmodels)";
  const std::string name = GetParam();
  const std::string dir = testing::TempDir() + "vdcloth_capture_" + name + "_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/" + name + ".json"));
  scene["obstacles"][0]["character"]["motion"] = capture;
  scene["obstacles"][0]["character"]["scale"] = 0.056;
  for (auto& g : scene["garments"]) g["material"] = std::string(VDCLOTH_SOURCE_DIR) + "/materials/" + (name == "karate" ? "denim" : "cotton") + ".json";
  scene["remeshing"]["size"] = {0.02, 0.2};
  const std::string path = dir + "/capture.json";
  std::ofstream(path) << scene.dump();

  Ensemble adaptive(load_scene(path), SimOptions{SimMode::Adaptive, 1});
  const Simulation& part = *adaptive.parts().front();
  EXPECT_EQ(part.scene().preroll_frames, 25);
  for (const GarmentSpec& g : part.scene().garments) EXPECT_EQ(g.fitted_to, scene["obstacles"][0]["name"]) << g.name;
  ASSERT_EQ(first_crossing(part), "") << "at the start of the pre-roll";
  while (adaptive.frame() < 0) adaptive.step_frame();
  ASSERT_EQ(first_crossing(part), "") << "after the pre-roll";
  // Until the view settles (the scene's `settle`, frame 12) a view run sizes as the adaptive run
  // does, and its pre-roll is the adaptive method's: the view run starts from the adaptive run's
  // meshes at that frame rather than making them again, and coarsens from there to frame 40.
  const int settle = static_cast<int>(part.scene().view.settle_frames(part.scene().frame_time));
  EXPECT_EQ(settle, 12);
  std::optional<ResumePoint> settled;
  clear_to_frame_forty(adaptive, SimMode::Adaptive, [&](const Ensemble& run) {
    if (run.frame() == settle) settled = meshes_now(run);
  });
  ASSERT_TRUE(settled);
  Ensemble view(load_scene(path), SimOptions{SimMode::View, 1}, Simulation::Log{}, {*settled}, "the adaptive run where the view settles");
  ASSERT_EQ(view.frame(), settle);
  clear_to_frame_forty(view, SimMode::View);
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Captures, CaptureShot, testing::Values("solo-dancer", "karate"),
                         [](const testing::TestParamInfo<std::string>& shot) { return shot.param == "karate" ? "karate" : "solo_dancer"; });

}  // namespace
}  // namespace vdc
