// OBJ-sequence obstacles: file names from the pattern, positions interpolated between frames,
// held after the last, placed by the obstacle's transform.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "scene/obj_sequence.hpp"
#include "scene/scene.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

TEST(ObjSequence, PatternGivesNumberedNames) {
  EXPECT_EQ(sequence_files("a/body.%04d.obj", 9, 2), (std::vector<std::string>{"a/body.0009.obj", "a/body.0010.obj"}));
  EXPECT_EQ(sequence_files("f%d.obj", 1, 1), (std::vector<std::string>{"f1.obj"}));
  EXPECT_THROW(sequence_files("body.obj", 1, 2), InputError);
  EXPECT_THROW(sequence_files("body.%s.obj", 1, 2), InputError);
  EXPECT_THROW(sequence_files("%d.%d.obj", 1, 2), InputError);
}

TEST(ObjSequence, ObstacleMovesThroughTheFramesOfItsFiles) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_seq_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // A triangle (plus an unused vertex, which the mesh drops) rising 0.1 m a frame.
  for (int f = 0; f < 3; ++f) {
    std::ofstream out(dir / ("tri." + std::to_string(f) + ".obj"));
    const double y = 0.1 * f;
    out << "v 9 9 9\nv 0 " << y << " 0\nv 1 " << y << " 0\nv 0 " << y << " 1\nf 2 4 3\n";
  }
  std::ofstream(dir / "scene.json") << R"({"frame_time": 0.04, "garments": [{"name": "s", "mesh": {"grid": {"size": [1, 1], "cells": [1, 1]}},
    "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6}}],
    "obstacles": [{"name": "tri", "mesh": {"sequence": {"files": "tri.%d.obj", "first": 0, "count": 3}},
                   "transform": {"translate": [0, -1, 0]}}]})";
  Scene s = load_scene((dir / "scene.json").string());
  fs::remove_all(dir);
  ASSERT_EQ(s.obstacles.size(), 1u);
  const ObstacleSpec& o = s.obstacles[0];
  EXPECT_TRUE(o.moves());
  ASSERT_EQ(o.mesh.num_nodes(), 3);
  EXPECT_NEAR(o.positions_at(0.0)[0].y(), -1.0, 1e-15);
  EXPECT_NEAR(o.positions_at(0.02)[1].y(), -0.95, 1e-12);  // halfway between frames 0 and 1
  EXPECT_NEAR(o.positions_at(0.06)[2].y(), -0.85, 1e-12);
  EXPECT_NEAR(o.positions_at(5.0)[0].y(), -0.8, 1e-12);    // held at the last frame
  EXPECT_NEAR(o.positions_at(0.06)[1].x(), 1.0, 1e-15);
}

}  // namespace
}  // namespace vdc
