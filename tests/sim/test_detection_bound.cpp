// The state that ran away: cloth driven metres in one step, whose swept boxes all meet one
// another. Continuous detection stops at its work bound, the step falls back (logged), and the
// frame ends with the cloth where it started. The bound is lowered from its 400 candidates a
// cloth node or edge to 40 so that the sanitized test reaches it ten times sooner: the path
// taken is the same.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

TEST(DetectionBound, ClothScatteredInOneStepFallsBackAndTheFrameEnds) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_detection_bound_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // A soft 1 m sheet of 20 x 20 cells (kept as it is by --mode fixed: its diagonals are within the
  // fixed size), no gravity, and a velocity limit that lets any step through.
  std::ofstream(dir / "scene.json") << R"({"gravity": [0, 0, 0], "substeps": 8, "solver": {"max_velocity_change": 1e9}, "remeshing": {"fixed_size": 0.0708},
    "garments": [{"name": "sheet", "mesh": {"grid": {"size": [1, 1], "cells": [20, 20]}},
    "material": {"density": 0.1, "stretch": {"warp": 0.01, "weft": 0.01, "shear": 0.001}, "bending": 1e-9}}]})";
  Scene scene = load_scene((dir / "scene.json").string());
  fs::remove_all(dir);
  scene.collision.max_candidates_per_primitive = 40;
  // Every node sent off at up to 40 km/s: metres apart even in a sixteenth of a 5 ms step (the
  // smallest impact zones halve it to).
  Mesh& sheet = scene.garments[0].mesh;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-40000, 40000);
  for (NodeId n : sheet.nodes()) sheet.v(n) = Vec3(U(rng), U(rng), U(rng));
  std::vector<Vec3> start;
  for (NodeId n : sheet.nodes()) start.push_back(sheet.x(n));
  std::vector<std::string> log;
  Simulation sim(std::move(scene), SimOptions{SimMode::Fixed, 2}, [&](const std::string& line) { log.push_back(line); });
  const FrameStats stats = sim.step_frame();
  // 441 nodes and 1,240 edges: a bound of 67,240 pairs a round.
  EXPECT_GT(stats.collision_candidates, 40LL * (441 + 1240));
  EXPECT_GE(stats.collision_fallbacks, 1);
  EXPECT_GE(stats.halvings, 4);  // the step was first halved four times
  int over = 0;
  for (const std::string& line : log)
    if (line.find("over its bound (40 a cloth node or edge): the cloth keeps its start-of-step positions") != std::string::npos) ++over;
  EXPECT_GE(over, 1);
  // It fell back at the first step; the velocities it left are zero, so the sheet stayed.
  const Mesh& after = sim.garment_mesh(0);
  ASSERT_EQ(after.num_nodes(), static_cast<int>(start.size()));
  double moved = 0;
  for (NodeId n : after.nodes()) moved = std::max(moved, (after.x(n) - start[static_cast<std::size_t>(n.idx)]).norm());
  EXPECT_LT(moved, 1e-3);
}

}  // namespace
}  // namespace vdc
