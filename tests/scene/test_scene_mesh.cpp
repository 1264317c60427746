// A `mesh`: a grid's and a sphere's sizes by hand count, a dress kept as the garment's pattern,
// and what a garment or an obstacle cannot be.
#include <gtest/gtest.h>

#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

TEST(SceneMesh, AGridAndASphereHaveTheirCountedElements) {
  // 3 by 2 cells: 4 x 3 nodes, two triangles a cell, the far corner at (size x, 0, -size y).
  const Mesh grid = parse_mesh(json_block(R"({"grid": {"size": [1.5, 1], "cells": [3, 2]}})", "garments[0].mesh"), "scene.json", true);
  EXPECT_EQ(grid.num_nodes(), 12);
  EXPECT_EQ(grid.num_faces(), 12);
  EXPECT_EQ(grid.x(NodeId(11)), Vec3(1.5, 0, -1));
  // An icosahedron split twice: 20 x 4^2 faces, 10 x 4^2 + 2 vertices on the radius.
  const Mesh ball = parse_mesh(json_block(R"({"sphere": {"radius": 0.5, "subdivisions": 2}})", "obstacles[0].mesh"), "scene.json", false);
  EXPECT_EQ(ball.num_faces(), 320);
  EXPECT_EQ(ball.num_nodes(), 162);
  for (NodeId n : ball.nodes()) EXPECT_NEAR(ball.x(n).norm(), 0.5, 1e-12);
}

TEST(SceneMesh, ADressIsKeptAsThePattern) {
  std::optional<GarmentPattern> pattern;
  const Mesh dress = parse_mesh(json_block(R"({"dress": {"around": 32, "cell": 0.05}})", "garments[0].mesh"), "scene.json", true, &pattern);
  ASSERT_TRUE(pattern.has_value());
  ASSERT_TRUE(std::holds_alternative<DressParams>(*pattern));
  EXPECT_EQ(std::get<DressParams>(*pattern).around, 32);
  EXPECT_EQ(std::get<DressParams>(*pattern).cell, 0.05);
  EXPECT_TRUE(dress.validate().ok());
}

TEST(SceneMesh, ErrorsNameTheKey) {
  auto error = [](const std::string& text, bool garment) {
    return input_error([&] { parse_mesh(json_block(text, "m"), "scene.json", garment); });
  };
  EXPECT_EQ(error(R"({"sphere": {"radius": 1}})", true), "scene.json:m.sphere: a garment cannot be a sphere (it needs a pattern)");
  EXPECT_EQ(error(R"({"dress": {}})", false), "scene.json:m.dress: an obstacle cannot be a dress");
  EXPECT_EQ(error(R"({"sphere": {"radius": 1, "subdivisions": 7}})", false), "scene.json:m.sphere.subdivisions: must be between 0 and 6");
  EXPECT_EQ(error(R"({"grid": {"size": [1, 1], "cells": [1001, 1000]}})", true),
            "scene.json:m.grid.cells: cell counts must be between 1 and 1,000,000 in all (2,000,000 triangles)");
  EXPECT_EQ(error(R"({"dress": {"around": 20}})", true), "scene.json:m.dress.around: must be a multiple of 8 between 16 and 1000");
  EXPECT_EQ(error(R"({"tube": {"top": [1, 0.2], "bottom": [1.2, 0.2]}})", true), "scene.json:m.tube.bottom: the bottom ring must be below the top ring");
}

}  // namespace
}  // namespace vdc
