// Occlusion in a view run: a sheet under a larger one, the camera looking down on both. The
// lower sheet is hidden when the upper one is opaque, seen when it is sheer, and the run's
// stats count what the camera sees of each face at the frame's start.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene/scene.hpp"
#include "sim/ensemble.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

// Two grids facing up (+y): "top", 1 m square at y = 0, and "under", 0.5 m square 0.5 m below
// it, both centred on the y axis; the camera 3 m above looks straight down.
std::string two_sheets(const fs::path& dir, const std::string& view, bool sheer) {
  fs::create_directories(dir);
  const std::string material = std::string("\"") + VDCLOTH_SOURCE_DIR + "/materials/cotton.json\"";
  const fs::path path = dir / "sheets.json";
  std::ofstream(path) << R"({"frame_time": 0.04, "substeps": 2, "remeshing": {"size": [0.05, 0.2]},
    "camera": {"fov": 40, "width": 640, "height": 360, "up": [0, 0, -1], "keys": [{"time": 0, "position": [0, 3, 0], "target": [0, 0, 0]}]},
    "view": )" << view << R"(,
    "garments": [
      {"name": "top", "mesh": {"grid": {"size": [1, 1], "cells": [4, 4]}}, "transform": {"translate": [-0.5, 0, 0.5]},
       "material": )" << material << R"(, "sheer": )" << (sheer ? "true" : "false") << R"(},
      {"name": "under", "mesh": {"grid": {"size": [0.5, 0.5], "cells": [4, 4]}}, "transform": {"translate": [-0.25, -0.5, 0.25]},
       "material": )" << material << R"(}]})";
  return path.string();
}

struct Seen {
  FrameStats stats;
  double least = 1, most = 0;  // of the under sheet's view factors after the frame
};

Seen first_frame(const std::string& view, bool sheer) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-occlusion-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  Simulation sim(load_scene(two_sheets(dir, view, sheer)), SimOptions{SimMode::View, 1});
  Seen seen;
  seen.stats = sim.step_frame();
  const Mesh& under = sim.garment_mesh(1);
  const auto& factor = under.face_attrs().get<double>(kViewFactorAttr);
  for (FaceId f : under.faces()) seen.least = std::min(seen.least, factor[f]), seen.most = std::max(seen.most, factor[f]);
  fs::remove_all(dir);
  return seen;
}

TEST(OcclusionRun, AnOpaqueSheetHidesTheOneUnderItASheerOneDoesNot) {
  const Seen opaque = first_frame(R"({"occlusion": true, "v_occluded": 0.3})", false);
  EXPECT_EQ(opaque.stats.hidden_faces, 32);   // all of the lower sheet's 4 x 4 x 2
  EXPECT_EQ(opaque.stats.visible_faces, 32);  // all of the upper one's
  EXPECT_EQ(opaque.stats.back_facing_faces, 0);
  EXPECT_DOUBLE_EQ(opaque.least, 0.3);
  EXPECT_DOUBLE_EQ(opaque.most, 0.3);
  const Seen sheer = first_frame(R"({"occlusion": true, "v_occluded": 0.3})", true);
  EXPECT_EQ(sheer.stats.hidden_faces, 0);
  EXPECT_EQ(sheer.stats.visible_faces, 64);
  EXPECT_EQ(sheer.least, 1.0);
  const Seen off = first_frame("{}", false);
  EXPECT_EQ(off.stats.hidden_faces, 0);
  EXPECT_EQ(off.stats.visible_faces, 64);
  EXPECT_EQ(off.least, 1.0);
}

// A crowd: the lower sheet in group "a", a ball of group "b" between it and the camera (and
// b's own sheet far to the side). The ball collides with nothing of group a, but it hides a's
// sheet: in the whole scene stepped as an ensemble, and in group a run alone.
TEST(OcclusionRun, AnotherGroupsBodyHidesThisGroupsCloth) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-occlusion-groups-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(dir);
  const std::string material = std::string("\"") + VDCLOTH_SOURCE_DIR + "/materials/cotton.json\"";
  const fs::path path = dir / "crowd.json";
  std::ofstream(path) << R"({"frame_time": 0.04, "substeps": 2, "remeshing": {"size": [0.05, 0.2]},
    "camera": {"fov": 40, "width": 640, "height": 360, "up": [0, 0, -1], "keys": [{"time": 0, "position": [0, 3, 0], "target": [0, 0, 0]}]},
    "view": {"occlusion": true},
    "garments": [
      {"name": "under", "group": "a", "mesh": {"grid": {"size": [0.5, 0.5], "cells": [4, 4]}}, "transform": {"translate": [-0.25, -0.5, 0.25]},
       "material": )" << material << R"(},
      {"name": "aside", "group": "b", "mesh": {"grid": {"size": [0.5, 0.5], "cells": [4, 4]}}, "transform": {"translate": [5, -0.5, 0.25]},
       "material": )" << material << R"(}],
    "obstacles": [{"name": "ball", "group": "b", "mesh": {"sphere": {"radius": 0.6, "subdivisions": 3}}, "transform": {"translate": [0, 1.2, 0]}}]})";
  Ensemble whole(load_scene(path.string()), SimOptions{SimMode::View, 2});
  ASSERT_EQ(whole.parts().size(), 2u);
  EXPECT_EQ(whole.parts()[0]->scene().obstacles.size(), 0u);
  EXPECT_EQ(whole.parts()[0]->scene().hiding.size(), 1u);
  EXPECT_EQ(whole.step_frame().hidden_faces, 32);  // a's sheet; b's is out of frame
  Ensemble alone(keep_groups(load_scene(path.string()), {"a"}), SimOptions{SimMode::View, 1});
  EXPECT_EQ(alone.step_frame().hidden_faces, 32);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vdc
