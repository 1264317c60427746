// What carries a garment must carry it in view mode too: on solo-dancer the dress hangs from its
// straps, whose tops face away from the camera (it looks up at them) and are coarsened. With
// eq. 2 applied to the whole sizing field and the coarse straps resisting compression with the
// full stretch stiffness, the right strap slid off the shoulder within 20 frames (11 cm from it
// at frame 20, 17 cm at frame 30) while the adaptive run kept both on. Now both runs keep them
// resting on the shoulders. The two runs (the scene as shipped, one thread; the view run coarse
// from frame 5) are solo-dancer's adaptive and view character shots too: their frames end with
// nothing crossing (test_characters.cpp checks the other shots).
#include <gtest/gtest.h>

#include <string>

#include "collision/distance.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "support/scene_crossings.hpp"

namespace vdc {
namespace {

// The top of the shoulder under a strap: the highest body vertex in a 3 by 4 cm column at the
// dress pattern's strap line (13 cm either side of the midline), in the chest joint's frame.
Vec3 shoulder_top(const Character& body, int chest, double t, int side) {
  const Eigen::Affine3d to_chest = body.joint_transform(chest, t).inverse();
  double highest = -1;
  Vec3 top = Vec3::Constant(1e9);
  for (const Vec3& b : body.positions_at(t)) {
    const Vec3 local = to_chest * b;
    if (std::abs(local.x() - side * 0.13) < 0.015 && std::abs(local.z()) < 0.02 && local.y() > highest) {
      highest = local.y();
      top = b;
    }
  }
  return top;
}

// Distance from that point to the dress's surface.
double strap_gap(const Mesh& dress, const Vec3& shoulder) {
  double gap = 1e9;
  for (FaceId f : dress.faces())
    gap = std::min(gap, point_triangle_distance(shoulder, dress.x(dress.face_node(f, 0)), dress.x(dress.face_node(f, 1)),
                                                dress.x(dress.face_node(f, 2))));
  return gap;
}

using test::first_crossing;

TEST(ViewFidelity, TheStrapsStayOnTheShouldersAsInTheAdaptiveRunAndNothingCrosses) {
  const std::string path = std::string(VDCLOTH_SOURCE_DIR) + "/scenes/solo-dancer.json";
  // Coarse from frame 5 rather than the scene's frame 12: 20 coarse frames, and the switch to
  // them before the straps are checked.
  Scene coarse_early = load_scene(path);
  coarse_early.view.settle = 0.2;
  Simulation adaptive(load_scene(path), SimOptions{SimMode::Adaptive, 1});
  Simulation view(std::move(coarse_early), SimOptions{SimMode::View, 1});
  const Character& body = *view.scene().obstacles.at(0).character;
  int chest = -1;
  for (std::size_t j = 0; j < body.motion().skeleton.joints.size(); ++j)
    if (body.motion().skeleton.joints[j].name == "Chest") chest = static_cast<int>(j);
  ASSERT_GE(chest, 0);
  // The dress rests 2 x 3 mm (the repulsion band) from the body, a coarse face's chord a few
  // millimetres more: 15 mm is on the shoulder; a strap that slid off is 5 to 17 cm away.
  const double on_shoulder = 0.015;
  ASSERT_EQ(first_crossing(adaptive), "") << "at the start";
  for (int frame = 1; frame <= 25; ++frame) {
    adaptive.step_frame();
    const FrameStats s = view.step_frame();
    ASSERT_EQ(first_crossing(adaptive), "") << "adaptive, frame " << frame;
    ASSERT_EQ(first_crossing(view), "") << "view, frame " << frame;
    if (frame < 10) continue;  // the dress is still dropping onto the shoulders
    for (int side : {1, -1}) {
      const Vec3 top = shoulder_top(body, chest, view.time(), side);
      const double a = strap_gap(adaptive.garment_mesh(0), top), v = strap_gap(view.garment_mesh(0), top);
      EXPECT_LT(a, on_shoulder) << "adaptive, frame " << frame << ", side " << side;
      EXPECT_LT(v, on_shoulder) << "view, frame " << frame << ", side " << side << " (adaptive: " << a << " m)";
      EXPECT_GT(s.back_facing_faces, 0);
    }
  }
}

}  // namespace
}  // namespace vdc
