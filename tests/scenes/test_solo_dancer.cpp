// solo-dancer, its first 20 frames in each mode: at every frame end the dress crosses neither
// the dancing body nor itself (exact triangle-triangle tests).
#include <gtest/gtest.h>

#include "collision/intersection.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

std::vector<std::array<int32_t, 3>> face_nodes(const Mesh& m) {
  std::vector<std::array<int32_t, 3>> faces;
  for (FaceId f : m.faces()) faces.push_back({m.face_node(f, 0).idx, m.face_node(f, 1).idx, m.face_node(f, 2).idx});
  return faces;
}

std::vector<Vec3> positions(const Mesh& m) {
  std::vector<Vec3> x(static_cast<std::size_t>(m.node_capacity()));
  for (NodeId n : m.nodes()) x[static_cast<std::size_t>(n.idx)] = m.x(n);
  return x;
}

TEST(SoloDancer, DressNeverCrossesTheBodyOrItselfInAnyMode) {
  for (SimMode mode : {SimMode::Fixed, SimMode::Adaptive, SimMode::View}) {
    Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/solo-dancer.json");
    scene.fixed_size = 0.04;  // the test's fixed mesh (the scene's baseline is size_min: 10 mm)
    Simulation sim(std::move(scene), SimOptions{mode, 2});
    for (int f = 0; f < 20; ++f) {
      const FrameStats s = sim.step_frame();
      EXPECT_EQ(s.collision_fallbacks, 0) << sim_mode_name(mode) << " frame " << s.frame;
      const Mesh& dress = sim.scene().garments[0].mesh;
      const Mesh& body = sim.scene().obstacles[0].mesh;
      ASSERT_EQ(count_intersections_between(face_nodes(dress), positions(dress), face_nodes(body), positions(body)), 0) << sim_mode_name(mode) << " frame " << s.frame;
      ASSERT_EQ(count_self_intersections(face_nodes(dress), positions(dress)), 0) << sim_mode_name(mode) << " frame " << s.frame;
    }
  }
}

}  // namespace
}  // namespace vdc
