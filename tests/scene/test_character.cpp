// Character obstacles in scenes: the skinned body placed by its transform, moving with the
// motion from its start time, and refused when an obstacle names both a mesh and a character.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "scene/scene.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

std::string write_scene(const std::string& obstacle) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_character_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"garments": [{"name": "s", "mesh": {"grid": {"size": [1, 1], "cells": [1, 1]}},
    "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6}}],
    "obstacles": [)" + obstacle + "]}";
  return (dir / "scene.json").string();
}

TEST(Character, PlacedSkinnedBodyFollowsItsMotion) {
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  Scene s = load_scene(write_scene(R"({"name": "d", "character": {"motion": ")" + motion +
                                   R"(", "start": 0.5, "resolution": 0.04}, "transform": {"translate": [2, 0, 0], "rotate": [0, 90, 0]}})"));
  fs::remove_all(fs::path(s.path).parent_path());
  ASSERT_EQ(s.obstacles.size(), 1u);
  const ObstacleSpec& o = s.obstacles[0];
  ASSERT_TRUE(o.character);
  EXPECT_TRUE(o.moves());
  // Before the clip starts the body holds its rest pose: the rest mesh, turned and moved.
  const std::vector<Vec3> x0 = o.positions_at(0.0);
  const MeshSource& rest = o.character->rest_mesh();
  ASSERT_EQ(x0.size(), rest.positions.size());
  for (std::size_t i = 0; i < x0.size(); i += 97) {
    const Vec3& p = rest.positions[i];
    EXPECT_LT((x0[i] - Vec3(2 + p.z(), p.y(), -p.x())).norm(), 1e-12) << i;
  }
  for (NodeId n : o.mesh.nodes()) ASSERT_EQ(o.mesh.x(n), x0[static_cast<std::size_t>(n.idx)]);
  // Three seconds into the dance the body has moved.
  const std::vector<Vec3> x3 = o.positions_at(3.5);
  double moved = 0;
  for (std::size_t i = 0; i < x0.size(); ++i) moved = std::max(moved, (x3[i] - x0[i]).norm());
  EXPECT_GT(moved, 0.2);
}

TEST(Character, AnObstacleIsAMeshOrACharacter) {
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  const std::string both = write_scene(R"({"name": "d", "mesh": {"sphere": {"radius": 1}}, "character": {"motion": ")" + motion + R"("}})");
  EXPECT_THROW(load_scene(both), InputError);
  const std::string missing = write_scene(R"({"name": "d", "character": {"motion": "nowhere.bvh"}})");
  try {
    load_scene(missing);
    ADD_FAILURE() << "accepted a missing motion";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("obstacles[0].character.motion"), std::string::npos) << e.what();
  }
  fs::remove_all(fs::path(missing).parent_path());
}

}  // namespace
}  // namespace vdc
