// solo-dancer, its first 20 frames in each mode: at every frame end the dress crosses neither
// the dancing body nor itself (exact triangle-triangle tests).
#include <gtest/gtest.h>

#include "collision/intersection.hpp"
#include "core/bvh.hpp"
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

// Pairs of a cloth face and an obstacle face that intersect.
int crossings(const Mesh& cloth, const Mesh& obstacle) {
  const auto of = face_nodes(obstacle);
  const auto ox = positions(obstacle);
  std::vector<Aabb> boxes(of.size());
  for (std::size_t f = 0; f < of.size(); ++f)
    for (int32_t n : of[f]) boxes[f].grow(ox[static_cast<std::size_t>(n)]);
  const Bvh tree(boxes);
  int count = 0;
  for (FaceId f : cloth.faces()) {
    const std::array<Vec3, 3> t{cloth.x(cloth.face_node(f, 0)), cloth.x(cloth.face_node(f, 1)), cloth.x(cloth.face_node(f, 2))};
    Aabb box;
    for (const Vec3& p : t) box.grow(p);
    tree.query(box, [&](int32_t g) {
      const auto& s = of[static_cast<std::size_t>(g)];
      count += triangles_intersect(t, {ox[static_cast<std::size_t>(s[0])], ox[static_cast<std::size_t>(s[1])], ox[static_cast<std::size_t>(s[2])]});
    });
  }
  return count;
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
      ASSERT_EQ(crossings(dress, body), 0) << sim_mode_name(mode) << " frame " << s.frame;
      ASSERT_EQ(count_self_intersections(face_nodes(dress), positions(dress)), 0) << sim_mode_name(mode) << " frame " << s.frame;
    }
  }
}

}  // namespace
}  // namespace vdc
