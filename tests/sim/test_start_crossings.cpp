// A garment that crosses a body where the run starts, and stays crossed after untangling (here
// with untangling turned off), is reported once at the start, naming the garment, the obstacle
// and the count of crossing face pairs; a garment clear of the body is not.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

// The start-up log of a 1 m sheet at height `y` beside a ball of radius 0.3 at the sheet's
// centre, untangling only detecting.
std::vector<std::string> start_log(double y) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_start_crossings_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"collision": {"untangle_iterations": 0}, "garments": [{"name": "sheet",
    "mesh": {"grid": {"size": [1, 1], "cells": [8, 8]}}, "transform": {"translate": [-0.5, )" << y << R"(, 0.5]},
    "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6}}],
    "obstacles": [{"name": "ball", "mesh": {"sphere": {"radius": 0.3, "subdivisions": 2}}}]})";
  Scene scene = load_scene((dir / "scene.json").string());
  fs::remove_all(dir);
  std::vector<std::string> log;
  Simulation sim(std::move(scene), SimOptions{SimMode::Adaptive, 1}, [&](const std::string& line) { log.push_back(line); });
  return log;
}

TEST(StartCrossings, AGarmentThroughTheBodyIsNamedOnceWithItsCount) {
  int reports = 0;
  for (const std::string& line : start_log(0.0)) {
    if (line.find("garment 'sheet' crosses obstacle 'ball' in ") == std::string::npos) continue;
    ++reports;
    // The sheet's plane cuts the ball's equator: some of its 128 faces cross some of the ball's.
    const int pairs = std::stoi(line.substr(line.find(" in ") + 4));
    EXPECT_GT(pairs, 0) << line;
    EXPECT_LT(pairs, 128 * 320) << line;
  }
  EXPECT_EQ(reports, 1);
  for (const std::string& line : start_log(0.5)) EXPECT_EQ(line.find("crosses obstacle"), std::string::npos) << line;
}

}  // namespace
}  // namespace vdc
