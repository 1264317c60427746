// The far level of detail in a view run (view.far_remesh_every): a hanging sheet that a camera
// 40 m away cannot resolve is remeshed on every third frame only (from view.far_after on), and
// keeps its mesh between;
// one 2 m away is remeshed every frame; a camera dollying in switches the level mid-run, and a
// run resumed across the switch, or made on two threads, is the same run bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

// A 0.5 m sheet of 8 x 8 cells held by two corners at y = 1; the camera on the z axis at `from`
// m, then from 0.24 s (frame 6) to 0.6 s (frame 15) dollying to `to` m, looking at the sheet.
// l_min 4 and 2 cm folds (the defaults) make it unresolved beyond about 6 m for this 640 x 360,
// 40-degree lens (level_of_detail.hpp).
Scene hanging_sheet(double from, double to, int every, double far_after = 0) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-far-level-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(dir);
  const fs::path path = dir / "sheet.json";
  std::ofstream(path) << R"({"frame_time": 0.04, "substeps": 2, "remeshing": {"size": [0.02, 0.2]},
    "camera": {"fov": 40, "width": 640, "height": 360, "keys": [
      {"time": 0, "position": [0.25, 0.75, )" << from << R"(], "target": [0.25, 0.75, 0]},
      {"time": 0.24, "position": [0.25, 0.75, )" << from << R"(], "target": [0.25, 0.75, 0]},
      {"time": 0.6, "position": [0.25, 0.75, )" << to << R"(], "target": [0.25, 0.75, 0]}]},
    "view": {"l_min": 4, "far_after": )" << far_after << R"(, "far_remesh_every": )" << every << R"(},
    "garments": [{"name": "sheet", "mesh": {"grid": {"size": [0.5, 0.5], "cells": [8, 8]}}, "material": ")"
                      << VDCLOTH_SOURCE_DIR << R"(/materials/cotton.json", "transform": {"translate": [0, 1, 0]},
      "handles": [{"uv": [[0, 1], [1, 1]]}]}]})";
  Scene scene = load_scene(path.string());
  fs::remove_all(dir);
  return scene;
}

std::vector<FrameStats> run(Simulation& sim, int frames) {
  std::vector<FrameStats> out;
  for (int f = 0; f < frames; ++f) out.push_back(sim.step_frame());
  return out;
}

std::vector<double> positions(const Simulation& sim) {
  std::vector<double> x;
  const Mesh& mesh = sim.garment_mesh(0);
  for (NodeId n : mesh.nodes())
    for (int k = 0; k < 3; ++k) x.push_back(mesh.x(n)[k]);
  return x;
}

TEST(FarLevel, AnUnresolvedGroupIsRemeshedOnEveryThirdFrameAndKeepsItsMeshBetween) {
  Simulation far(hanging_sheet(40, 40, 3), SimOptions{SimMode::View, 1});
  int faces = far.garment_mesh(0).num_faces();
  for (const FrameStats& s : run(far, 7)) {
    const bool remeshed = (s.frame - 1) % 3 == 0;  // the frame started at frame s.frame - 1
    EXPECT_EQ(s.far_groups, 1) << "frame " << s.frame;
    EXPECT_EQ(s.remesh_seconds > 0, remeshed) << "frame " << s.frame;
    EXPECT_EQ(s.visible_faces + s.back_facing_faces + s.out_of_frame_faces > 0, remeshed) << "frame " << s.frame;  // the view's counts
    if (!remeshed) EXPECT_EQ(s.faces, faces) << "frame " << s.frame;
    EXPECT_EQ(s.splits + s.flips + s.collapses > 0 || remeshed, remeshed) << "frame " << s.frame;
    faces = s.faces;
  }
  // The same sheet 2 m from the camera, or with the level off: remeshed every frame.
  for (Scene scene : {hanging_sheet(2, 2, 3), hanging_sheet(40, 40, 1)}) {
    Simulation sim(std::move(scene), SimOptions{SimMode::View, 1});
    for (const FrameStats& s : run(sim, 4)) {
      EXPECT_EQ(s.far_groups, 0) << "frame " << s.frame;
      EXPECT_GT(s.remesh_seconds, 0) << "frame " << s.frame;
    }
  }
  // Not before far_after: frames starting at 0, 0.04 and 0.08 s are remeshed, 0.12 s is far.
  Simulation later(hanging_sheet(40, 40, 3, 0.1), SimOptions{SimMode::View, 1});
  const std::vector<FrameStats> after = run(later, 4);
  for (int f = 0; f < 4; ++f) EXPECT_EQ(after[static_cast<std::size_t>(f)].far_groups, f == 3 ? 1 : 0) << "frame " << f + 1;
  // Adaptive mode has no level of detail.
  Simulation adaptive(hanging_sheet(40, 40, 3), SimOptions{SimMode::Adaptive, 1});
  for (const FrameStats& s : run(adaptive, 2)) EXPECT_EQ(s.far_groups, 0);
}

// The camera dollies from 40 m to 2 m over frames 6 to 15: the sheet is far, then resolved (eq.
// 4's window anticipates the camera: it switches before the camera is near). Resumed at frame 5,
// whose remesh the far level skips.
TEST(FarLevel, ARunResumedAcrossTheSwitchOrMadeOnTwoThreadsIsTheSameRun) {
  Simulation whole(hanging_sheet(40, 2, 3), SimOptions{SimMode::View, 1});
  const std::vector<FrameStats> stats = run(whole, 12);
  std::vector<int> levels;
  for (const FrameStats& s : stats) levels.push_back(s.far_groups);
  EXPECT_EQ(levels.front(), 1);
  EXPECT_EQ(levels.back(), 0);
  EXPECT_TRUE(std::is_sorted(levels.rbegin(), levels.rend())) << "far, then resolved, once";
  EXPECT_EQ(stats[5].far_groups, 1);  // the frame the resumed run starts with

  Simulation first(hanging_sheet(40, 2, 3), SimOptions{SimMode::View, 1});
  run(first, 5);
  ResumePoint point;
  point.frame = 5;
  point.names = {"sheet"};
  point.garments = {first.garment_mesh(0)};
  Simulation resumed(hanging_sheet(40, 2, 3), SimOptions{SimMode::View, 1}, {}, point, "the test's frame 5");
  const std::vector<FrameStats> rest = run(resumed, 7);
  for (std::size_t f = 0; f < rest.size(); ++f) EXPECT_EQ(rest[f].far_groups, stats[5 + f].far_groups) << "frame " << rest[f].frame;
  EXPECT_EQ(positions(resumed), positions(whole));

  Simulation two(hanging_sheet(40, 2, 3), SimOptions{SimMode::View, 2});
  run(two, 12);
  EXPECT_EQ(positions(two), positions(whole));
}

}  // namespace
}  // namespace vdc
