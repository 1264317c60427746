// A `garments[i]` entry: placed by its transform, its handles holding the nodes chosen by index,
// point, pattern coordinate and box, and errors naming the handle.
#include <gtest/gtest.h>

#include <limits>

#include "physics/cloth_model.hpp"
#include "scene/scene_blocks.hpp"
#include "support/json_block.hpp"

namespace vdc {
namespace {

using test::input_error;
using test::json_block;

// A 1 m sheet of 2 x 2 cells: node j * 3 + i at (i / 2, 0, -j / 2) before its transform.
std::string sheet(const std::string& more) {
  return R"({"name": "sheet", "mesh": {"grid": {"size": [1, 1], "cells": [2, 2]}},
             "material": {"density": 0.1, "stretch": {"warp": 10, "weft": 10, "shear": 1}, "bending": 1e-5})" +
         more + "}";
}

GarmentSpec garment(const std::string& more) {
  GarmentMaking making;
  return parse_garment(json_block(sheet(more), "garments[0]"), "scene.json", making);
}

TEST(SceneGarments, PlacedByItsTransformWithItsMaterial) {
  GarmentMaking making;
  const GarmentSpec g = parse_garment(json_block(sheet(R"(, "transform": {"translate": [0, 2, 0]}, "group": "a")"), "garments[0]"), "scene.json", making);
  EXPECT_EQ(g.name, "sheet");
  EXPECT_EQ(g.group, "a");
  EXPECT_FALSE(g.sheer);
  EXPECT_EQ(g.material.density, 0.1);
  EXPECT_EQ(g.mesh.x(NodeId(8)), Vec3(1, 2, -1));
  ASSERT_TRUE(making.transform.has_value());
  EXPECT_FALSE(making.rest_initial);
  EXPECT_FALSE(making.pattern.has_value());
  EXPECT_TRUE(g.handles.empty());
}

TEST(SceneGarments, HandlesHoldTheNodesTheyChoose) {
  // Node 0 by index, node 2 nearest (1.01, 0, 0), node 7 at pattern coordinate (0.5, 1), nodes
  // 3 and 6 in the box along the sheet's edge x = 0 past z = -0.4.
  const GarmentSpec g = garment(R"(, "handles": [{"nodes": [0]}, {"points": [[1.01, 0, 0]], "release": 2}, {"uv": [[0.5, 1]]},
                                   {"box": [[-0.1, -0.1, -1.1], [0.1, 0.1, -0.4]]}])");
  ASSERT_EQ(g.handles.size(), 4u);
  const auto& which = g.mesh.node_attrs().get<int32_t>(kHandleAttr);
  const auto& anchor = g.mesh.node_attrs().get<Vec3>(kAnchorAttr);
  const int32_t expected[9] = {0, -1, 1, 3, -1, -1, 3, 2, -1};
  for (int32_t n = 0; n < 9; ++n) {
    EXPECT_EQ(which[NodeId(n)], expected[n]) << "node " << n;
    EXPECT_EQ(static_cast<bool>(g.mesh.flags(NodeId(n)) & kNodeHandle), expected[n] >= 0) << "node " << n;
  }
  EXPECT_EQ(anchor[NodeId(2)], Vec3(1, 0, 0));
  EXPECT_EQ(g.handles[1].release, 2.0);
  EXPECT_EQ(g.handles[0].release, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(g.handles[0].path.empty());
}

TEST(SceneGarments, ErrorsNameTheHandle) {
  auto error = [](const std::string& more) { return input_error([&] { garment(more); }); };
  EXPECT_EQ(error(R"(, "handles": [{"nodes": [9]}])"), "scene.json:garments[0].handles[0].nodes[0]: node index out of range (the mesh has 9 nodes)");
  EXPECT_EQ(error(R"(, "handles": [{"release": 1}])"), "scene.json:garments[0].handles[0]: a handle needs at least one of nodes, points, uv or box");
  EXPECT_EQ(error(R"(, "handles": [{"nodes": [4]}, {"points": [[0.5, 0, -0.5]]}])"),
            "scene.json:garments[0].handles[1]: node 4 already belongs to another handle");
  EXPECT_EQ(error(R"(, "handles": [{"box": [[2, 2, 2], [3, 3, 3]]}])"), "scene.json:garments[0].handles[0].box: no node of the garment is in the box");
  EXPECT_EQ(error(R"(, "rest_shape": "curved")"), "scene.json:garments[0].rest_shape: expected \"flat\" or \"initial\"");
}

}  // namespace
}  // namespace vdc
