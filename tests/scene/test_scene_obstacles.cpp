// An `obstacles[i]` entry: a mesh placed by its transform, turning about its placed centroid,
// its motion's tracks, and errors naming the obstacle.
#include <gtest/gtest.h>

#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

ObstacleSpec obstacle(const std::string& text) {
  BodyMeshCache bodies;
  return parse_obstacle(json_block(text, "obstacles[0]"), "scene.json", 0.04, 1.0, bodies);
}

TEST(SceneObstacles, PlacedByItsTransformAndMovedByItsTracks) {
  const ObstacleSpec o = obstacle(R"({"name": "ball", "group": "g", "mesh": {"sphere": {"radius": 0.5, "subdivisions": 1}},
      "transform": {"scale": 2, "translate": [0, 1, 0]},
      "motion": {"translate": [{"time": 0, "offset": [0, 0, 0]}, {"time": 1, "offset": [1, 0, 0]}], "rotate": [{"time": 0, "degrees": [0, 90, 0]}]}})");
  EXPECT_EQ(o.name, "ball");
  EXPECT_EQ(o.group, "g");
  EXPECT_FALSE(o.character);
  // Radius 0.5 scaled to 1 about the origin, then lifted 1 m: every node 1 m from (0, 1, 0),
  // the placed centroid (the icosphere's is the origin by symmetry).
  for (NodeId n : o.mesh.nodes()) {
    EXPECT_NEAR((o.mesh.x(n) - Vec3(0, 1, 0)).norm(), 1.0, 1e-12);
    EXPECT_EQ(o.rest[static_cast<std::size_t>(n.idx)], o.mesh.x(n));
  }
  EXPECT_LT((o.pivot - Vec3(0, 1, 0)).norm(), 1e-12);
  ASSERT_EQ(o.translate.keys.size(), 2u);
  EXPECT_EQ(o.translate.keys[1].value, Vec3(1, 0, 0));
  ASSERT_EQ(o.rotate.keys.size(), 1u);
  EXPECT_TRUE(o.moves());
  EXPECT_FALSE(obstacle(R"({"name": "floor", "mesh": {"grid": {"size": [1, 1], "cells": [1, 1]}}})").moves());
}

TEST(SceneObstacles, ErrorsNameTheObstacle) {
  auto error = [](const std::string& text) { return input_error([&] { obstacle(text); }); };
  EXPECT_EQ(error(R"({"name": "x"})"), "scene.json:obstacles[0]: an obstacle needs exactly one of \"mesh\" and \"character\"");
  EXPECT_EQ(error(R"({"name": "x", "mesh": {"sphere": {"radius": 1}}, "character": {}})"),
            "scene.json:obstacles[0]: an obstacle needs exactly one of \"mesh\" and \"character\"");
  EXPECT_EQ(error(R"({"name": "x", "mesh": {"sphere": {"radius": 1}}, "motion": {"translate": [{"time": 1, "offset": [0, 0, 0]},
                                                                                                {"time": 0.5, "offset": [0, 0, 0]}]}})"),
            "scene.json:obstacles[0].motion.translate[1].time: keyframe times must increase");
  EXPECT_EQ(error(R"({"name": "x", "mesh": {"sequence": {"files": "f%04d.obj", "count": 0}}})"),
            "scene.json:obstacles[0].mesh.sequence.count: must be between 1 and 1,000,000");
}

}  // namespace
}  // namespace vdc
