// sheet-sphere in adaptive mode: the mesh refines where the sheet wraps the sphere and stays
// coarse where it is flat, and collisions hold at every frame end (nothing inside the sphere,
// no two cloth triangles intersecting).
#include <gtest/gtest.h>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "support/triangle_soup.hpp"

namespace vdc {
namespace {

Vec3 centroid(const Mesh& m) {
  Vec3 c = Vec3::Zero();
  for (NodeId n : m.nodes()) c += m.x(n);
  return c / m.num_nodes();
}

TEST(AdaptiveSphere, RefinesOverTheSphereCoarseWhereFlatAndNeverIntersects) {
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-sphere.json");
  const double thickness = scene.collision.thickness;
  Simulation sim(std::move(scene), SimOptions{SimMode::Adaptive, 1});
  // 130 frames: the sheet falls, the sphere rises into it (1.5 s to 3 s) and sweeps under it.
  for (int f = 0; f < 130; ++f) {
    FrameStats s = sim.step_frame();
    EXPECT_EQ(s.collision_fallbacks, 0) << "frame " << s.frame;
    const Mesh& cloth = sim.garment_mesh(0);
    const Mesh& sphere = sim.obstacle_mesh(0);
    const Vec3 centre = centroid(sphere);
    const double radius = (sphere.x(*sphere.nodes().begin()) - centre).norm();
    // The icosphere's faces lie at least radius cos(0.2) (its largest face angle) from the
    // centre: closer than that, less 10% of the thickness, is inside.
    const double inner = radius * std::cos(0.2) - 0.1 * thickness;
    for (NodeId n : cloth.nodes()) ASSERT_GT((cloth.x(n) - centre).norm(), inner) << "frame " << s.frame << " node " << n.idx;
    ASSERT_EQ(test::self_crossings(cloth), 0) << "frame " << s.frame;
    if (s.frame == 100 || s.frame == 125) {
      // Mean material area of faces within 5 cm of the sphere against faces farther than 25 cm.
      double near = 0, far = 0;
      int n_near = 0, n_far = 0;
      for (FaceId face : cloth.faces()) {
        const Vec3 c = (cloth.x(cloth.face_node(face, 0)) + cloth.x(cloth.face_node(face, 1)) + cloth.x(cloth.face_node(face, 2))) / 3;
        const double d = (c - centre).norm() - radius;
        if (d < 0.05) near += cloth.material_area(face), ++n_near;
        if (d > 0.25) far += cloth.material_area(face), ++n_far;
      }
      ASSERT_GT(n_near, 20) << "frame " << s.frame;
      ASSERT_GT(n_far, 20) << "frame " << s.frame;
      EXPECT_LT(near / n_near, far / n_far / 2) << "frame " << s.frame << ": faces over the sphere should be at least 2x finer";
    }
  }
}

}  // namespace
}  // namespace vdc
