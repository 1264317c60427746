// --mode view on sheet-camera: with the view factor forced to 1 and the screen-space floor off
// it reproduces the adaptive run bit for bit; with the scene's parameters it coarsens the sheet
// while the camera sees its back and where the close-up leaves it out of frame, and the faces it
// coarsened carry less stiffness against compression.
#include <gtest/gtest.h>

#include "physics/membrane.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

Scene sheet_camera() { return load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-camera.json"); }

TEST(ViewMode, WithFactorOneAndNoFloorItIsTheAdaptiveRunExactly) {
  Scene neutral = sheet_camera();
  neutral.view.v_back = 1;
  neutral.view.v_out = 1;
  neutral.view.l_min = 0;
  Simulation adaptive(sheet_camera(), SimOptions{SimMode::Adaptive, 1});
  Simulation view(std::move(neutral), SimOptions{SimMode::View, 1});
  for (int f = 0; f < 30; ++f) {
    adaptive.step_frame();
    FrameStats s = view.step_frame();
    const Mesh& a = adaptive.garment_mesh(0);
    const Mesh& b = view.garment_mesh(0);
    ASSERT_EQ(a.num_faces(), b.num_faces()) << "frame " << s.frame;
    ASSERT_EQ(a.num_nodes(), b.num_nodes()) << "frame " << s.frame;
    for (NodeId n : a.nodes()) ASSERT_EQ(a.x(n), b.x(n)) << "frame " << s.frame << " node " << n.idx;
    EXPECT_GT(s.visible_faces + s.back_facing_faces + s.out_of_frame_faces, 0);  // every face was classified
  }
}

TEST(ViewMode, FacesSeenFromBehindOrOutOfFrameAreCoarsened) {
  // 4.5 s to 5.2 s (frames 113 to 130) the camera sees the sheet's back; the close-up after the
  // cut at 5.2 s leaves part of the sheet out of frame.
  Simulation adaptive(sheet_camera(), SimOptions{SimMode::Adaptive, 1});
  Simulation view(sheet_camera(), SimOptions{SimMode::View, 1});
  int adaptive_faces = 0, view_faces = 0, adaptive_back = 0, view_back = 0, out_of_frame = 0;
  for (int f = 0; f < 140; ++f) {
    const FrameStats a = adaptive.step_frame();
    const FrameStats v = view.step_frame();
    adaptive_faces += a.faces;
    view_faces += v.faces;
    if (v.frame >= 115 && v.frame <= 129) {
      adaptive_back += a.faces;
      view_back += v.faces;
    }
    if (v.frame > 131) out_of_frame += v.out_of_frame_faces;
  }
  EXPECT_LT(view_back, adaptive_back / 3);  // v_back = 0.2: edges 5 times longer
  EXPECT_LT(view_faces, adaptive_faces);
  EXPECT_GT(out_of_frame, 0);
  const auto& factor = view.garment_mesh(0).face_attrs().get<double>(kViewFactorAttr);
  double lowest = 1;
  for (FaceId f : view.garment_mesh(0).faces()) lowest = std::min(lowest, factor[f]);
  EXPECT_LT(lowest, 0.5);
  // Faces the camera coarsened resist compression less, by how much coarser (in the metric)
  // than their physics they may be (membrane.hpp); the others are the plain material.
  const Mesh& sheet = view.garment_mesh(0);
  const auto& coarsening = sheet.face_attrs().get<double>(kCoarseningAttr);
  const auto& compression = sheet.face_attrs().get<double>(kCompressionAttr);
  int relaxed = 0;
  for (FaceId f : sheet.faces()) {
    EXPECT_EQ(compression[f], coarse_compression_factor(coarsening[f]));
    relaxed += compression[f] < 0.5;
  }
  EXPECT_GT(relaxed, 0);
}

}  // namespace
}  // namespace vdc
