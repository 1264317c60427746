// A remesh whose crossings untangling cannot remove is not kept: on sheet-sphere in adaptive mode
// with untangling allowed no pass, every remesh that puts cloth inside the sphere (a split's new
// node on a chord through it) falls back to the frame's start mesh, and no frame ends crossed.
#include <gtest/gtest.h>

#include "collision/intersection.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

struct Soup {
  std::vector<std::array<int32_t, 3>> faces;
  std::vector<Vec3> x;
};

Soup soup(const Mesh& m) {
  Soup s;
  s.x.resize(static_cast<std::size_t>(m.node_capacity()), Vec3::Zero());
  for (NodeId n : m.nodes()) s.x[static_cast<std::size_t>(n.idx)] = m.x(n);
  for (FaceId f : m.faces()) s.faces.push_back({m.face_node(f, 0).idx, m.face_node(f, 1).idx, m.face_node(f, 2).idx});
  return s;
}

TEST(RemeshFallback, CrossingsUntanglingCannotRemoveMakeTheFrameKeepItsStartMesh) {
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-sphere.json");
  scene.collision.untangle_iterations = 0;  // detection only: any crossing left by a remesh stays
  // Edges of 15 to 30 cm over a sphere of 10 cm radius: a split's new node on a chord over the
  // sphere lies inside it.
  scene.remeshing.size_min = 0.15;
  scene.remeshing.size_max = 0.3;
  Simulation sim(std::move(scene), SimOptions{SimMode::Adaptive, 1});
  int undone = 0, faces_before = sim.num_faces();
  // 250 frames: the sheet falls onto the sphere, which then moves under it from 1.5 s (frame 38).
  for (int f = 0; f < 250; ++f) {
    const FrameStats s = sim.step_frame();
    if (s.remesh_undone) {
      ++undone;
      EXPECT_EQ(s.faces, faces_before) << "frame " << s.frame << " kept its start mesh, so its face count";
      EXPECT_EQ(s.splits + s.flips + s.collapses > 0, true) << "frame " << s.frame;
    }
    faces_before = s.faces;
    const Soup cloth = soup(sim.scene().garments[0].mesh), sphere = soup(sim.scene().obstacles[0].mesh);
    ASSERT_EQ(count_self_intersections(cloth.faces, cloth.x), 0) << "frame " << s.frame;
    ASSERT_EQ(count_intersections_between(cloth.faces, cloth.x, sphere.faces, sphere.x), 0) << "frame " << s.frame;
  }
  EXPECT_GT(undone, 0) << "no remesh left a crossing: the test no longer reaches the fallback";
}

}  // namespace
}  // namespace vdc
