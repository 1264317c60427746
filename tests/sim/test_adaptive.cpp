// Adaptive mode on sheet-hang: remeshed every frame, the mesh stays valid, every edge within
// the sizing field, material area and mass conserved, handles kept, energy never gained. A
// part's garments are sized and remeshed side by side, with the results of one thread. A view
// run is the adaptive run until view.settle.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "physics/cloth_model.hpp"
#include "remesh/remesher.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

TEST(Adaptive, SheetHangRemeshesEveryFrameAndConserves) {
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-hang.json");
  const double density = scene.garments[0].material.density;
  Simulation sim(std::move(scene), SimOptions{SimMode::Adaptive, 1});
  const double e0 = sim.energy().total();
  int splits = 0, collapses = 0;
  for (int f = 0; f < 40; ++f) {
    FrameStats s = sim.step_frame();
    splits += s.splits;
    collapses += s.collapses;
    const Mesh& mesh = sim.garment_mesh(0);
    ValidationReport v = mesh.validate();
    ASSERT_TRUE(v.ok()) << "frame " << s.frame << "\n" << v.summary();
    double area = 0;
    for (FaceId face : mesh.faces()) area += mesh.material_area(face);
    EXPECT_NEAR(area, 1.0, 1e-9) << "frame " << s.frame;
    // The masses the simulation integrates with: lumped from the remeshed faces, the sheet's
    // whole mass, and none left on a node without faces.
    ClothModel model;
    append_garment(model, mesh, sim.scene().garments[0].material);
    double mass = 0;
    for (double m : model.node_mass) {
      ASSERT_GT(m, 0) << "frame " << s.frame;
      mass += m;
    }
    EXPECT_NEAR(mass, density * 1.0, 1e-9 * density) << "frame " << s.frame;
    int handles = 0;
    for (NodeId n : mesh.nodes()) handles += (mesh.flags(n) & kNodeHandle) != 0;
    EXPECT_EQ(handles, 2);
    // Remeshing happens at the start of a frame: the mesh the frame ends with is the one the
    // sizing field of that start asked for, so its edges satisfy it.
    for (EdgeId e : mesh.edges()) ASSERT_LE(edge_size2(mesh, e), 1.0 + 1e-9) << "frame " << s.frame;
    EXPECT_LE(s.energy.total(), e0 + 1e-6) << "frame " << s.frame;
  }
  EXPECT_GT(splits, 0);
  EXPECT_GT(collapses, 500);  // the 1,152-face start is far finer than a flat sheet needs
}

namespace fs = std::filesystem;

// Three hanging sheets of unequal size in one part, a metre apart in a row that a camera looks
// down, so that each is at its own distance from it.
std::string three_sheets_scene(const fs::path& dir, const std::string& view = R"({"v_back": 0.2, "v_out": 0.01})") {
  fs::create_directories(dir);
  std::string garments;
  const std::pair<const char*, double> sheets[] = {{"a", 0.3}, {"b", 0.5}, {"c", 0.8}};
  double z = 0;
  for (const auto& [name, width] : sheets) {
    if (!garments.empty()) garments += ", ";
    const std::string w = std::to_string(width);
    garments += std::string(R"({"name": ")") + name + R"(", "mesh": {"grid": {"size": [)" + w + ", " + w + R"(], "cells": [8, 8]}}, "material": ")" +
                VDCLOTH_SOURCE_DIR + R"(/materials/cotton.json", "transform": {"translate": [0, 1, )" + std::to_string(z) +
                R"(]}, "handles": [{"uv": [[0, 1], [1, 1]]}]})";
    z -= 1.0;
  }
  const fs::path path = dir / "three-sheets.json";
  std::ofstream(path) << R"({"frame_time": 0.04, "substeps": 4, "remeshing": {"size": [0.02, 0.2]},
    "camera": {"fov": 40, "width": 640, "height": 360, "keys": [{"time": 0, "position": [0.2, 0.8, 2], "target": [0.2, 0.8, -0.2]}]},
    "view": )" << view << R"(,
    "garments": [)" << garments << "]}";
  return path.string();
}

TEST(Adaptive, GarmentsRemeshedSideBySideAsOnOneThread) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-three-sheets-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  const std::string path = three_sheets_scene(dir);
  for (SimMode mode : {SimMode::Adaptive, SimMode::View}) {
    Simulation one(load_scene(path), SimOptions{mode, 1});
    Simulation two(load_scene(path), SimOptions{mode, 2});
    int changes = 0;
    for (int f = 0; f < 4; ++f) {
      const FrameStats a = one.step_frame(), b = two.step_frame();
      changes += a.splits + a.collapses;
      EXPECT_EQ(a.splits, b.splits);
      EXPECT_EQ(a.collapses, b.collapses);
      EXPECT_EQ(a.flips, b.flips);
      for (std::size_t g = 0; g < 3; ++g) {
        const Mesh& ma = one.garment_mesh(g);
        const Mesh& mb = two.garment_mesh(g);
        ASSERT_EQ(ma.num_faces(), mb.num_faces()) << sim_mode_name(mode) << ", garment " << g << ", frame " << f + 1;
        ASSERT_EQ(ma.num_nodes(), mb.num_nodes());
        for (NodeId n : ma.nodes()) ASSERT_EQ(ma.x(n), mb.x(n)) << sim_mode_name(mode) << ", garment " << g << ", frame " << f + 1;
      }
    }
    EXPECT_GT(changes, 0) << sim_mode_name(mode);  // the meshes were remeshed, not merely moved
  }
  fs::remove_all(dir);
}

// Before view.settle a view run is the adaptive run bit for bit (no factor, no screen-space
// bound: the drape forms on the adaptive mesh); from the first frame that starts at settle on,
// the view coarsens. The camera sees the sheets' backs, all in frame; v_back is 1, so only the
// screen-space floor coarsens: 40 px, with floor_in_frame on the faces turned away too, on
// sheets 2 to 4 m away whose 2 cm edges span 6 to 13 px.
TEST(Adaptive, AViewRunIsTheAdaptiveRunUntilSettle) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-settle-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  const std::string path = three_sheets_scene(dir, R"({"v_back": 1, "v_out": 0.01, "l_min": 40, "floor_in_frame": true, "settle": 0.08})");
  Simulation adaptive(load_scene(path), SimOptions{SimMode::Adaptive, 1});
  Simulation view(load_scene(path), SimOptions{SimMode::View, 1});
  for (int frame = 1; frame <= 3; ++frame) {
    const double start = view.time();
    int at_start = 0;
    for (std::size_t g = 0; g < 3; ++g) at_start += view.garment_mesh(g).num_faces();
    adaptive.step_frame();
    const FrameStats s = view.step_frame();
    EXPECT_EQ(s.back_facing_faces + s.visible_faces, at_start) << "frame " << frame;
    EXPECT_EQ(s.out_of_frame_faces, 0) << "frame " << frame;
    std::size_t faces = 0, adaptive_faces = 0;
    bool same = true;
    for (std::size_t g = 0; g < 3; ++g) {
      const Mesh& a = adaptive.garment_mesh(g);
      const Mesh& v = view.garment_mesh(g);
      faces += v.num_faces(), adaptive_faces += a.num_faces();
      same = same && a.num_faces() == v.num_faces() && a.num_nodes() == v.num_nodes();
      if (same)
        for (NodeId n : a.nodes()) same = same && a.x(n) == v.x(n);
    }
    if (start + 1e-9 < 0.08) {
      EXPECT_TRUE(same) << "frame " << frame << ", starting at " << start << " s, before settle";
    } else {
      EXPECT_FALSE(same) << "frame " << frame;
      EXPECT_LT(faces, adaptive_faces) << "frame " << frame;
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vdc
