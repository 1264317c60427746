// sheet-sphere: a sheet held at two corners, pushed and swept by a moving sphere. At the end of
// every frame no cloth vertex may be inside the sphere by more than 10% of the thickness and no
// two cloth triangles that share no node may intersect.
#include <gtest/gtest.h>

#include "collision/intersection.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

// Depth of x inside a closed convex mesh (0 outside): the smallest distance to a face plane.
double depth_inside_convex(const Mesh& m, const Vec3& x) {
  double depth = std::numeric_limits<double>::infinity();
  for (FaceId f : m.faces()) {
    const double s = m.world_normal(f).dot(x - m.x(m.face_node(f, 0)));
    if (s >= 0) return 0;
    depth = std::min(depth, -s);
  }
  return depth;
}

TEST(SheetSphere, NothingInsideTheSphereAndNoSelfIntersectionAtAnyFrameEnd) {
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-sphere.json");
  const double thickness = scene.collision.thickness;
  Simulation sim(std::move(scene), SimOptions{SimMode::Fixed, 1});
  int contacts = 0;
  // The whole scene: the sheet falls, the sphere pushes into it and sweeps under it, and the
  // sheet, released at 7 s, falls onto the sphere.
  const int frames = sim.scene().frames;
  for (int f = 0; f < frames; ++f) {
    FrameStats s = sim.step_frame();
    contacts += s.impacts + s.proximities;
    EXPECT_EQ(s.collision_fallbacks, 0) << "frame " << s.frame;
    const Mesh& cloth = sim.scene().garments[0].mesh;
    const Mesh& sphere = sim.scene().obstacles[0].mesh;
    std::vector<Vec3> x(static_cast<std::size_t>(cloth.node_capacity()));
    std::vector<std::array<int32_t, 3>> faces;
    for (NodeId n : cloth.nodes()) {
      x[static_cast<std::size_t>(n.idx)] = cloth.x(n);
      ASSERT_LE(depth_inside_convex(sphere, cloth.x(n)), 0.1 * thickness) << "frame " << s.frame << " node " << n.idx;
    }
    for (FaceId face : cloth.faces()) faces.push_back({cloth.face_node(face, 0).idx, cloth.face_node(face, 1).idx, cloth.face_node(face, 2).idx});
    ASSERT_EQ(count_self_intersections(faces, x), 0) << "frame " << s.frame;
  }
  EXPECT_GT(contacts, 1000);  // the sphere did meet the sheet (proximity pairs and impacts, summed over frames)
}

}  // namespace
}  // namespace vdc
