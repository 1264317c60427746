// Adaptive mode on sheet-hang: remeshed every frame, the mesh stays valid, every edge within
// the sizing field, material area and mass conserved, handles kept, energy never gained.
#include <gtest/gtest.h>

#include "remesh/remesher.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

TEST(Adaptive, SheetHangRemeshesEveryFrameAndConserves) {
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-hang.json");
  const double density = scene.garments[0].material.density;
  Simulation sim(std::move(scene), SimOptions{SimMode::Adaptive, 1});
  const double e0 = sim.energy().total();
  int splits = 0, collapses = 0;
  for (int f = 0; f < 40; ++f) {
    FrameStats s = sim.step_frame();
    splits += s.splits;
    collapses += s.collapses;
    const Mesh& mesh = sim.scene().garments[0].mesh;
    ValidationReport v = mesh.validate();
    ASSERT_TRUE(v.ok()) << "frame " << s.frame << "\n" << v.summary();
    double area = 0;
    for (FaceId face : mesh.faces()) area += mesh.material_area(face);
    EXPECT_NEAR(area, 1.0, 1e-9) << "frame " << s.frame;
    EXPECT_NEAR(area * density, density, 1e-9 * density);
    int handles = 0;
    for (NodeId n : mesh.nodes()) handles += (mesh.flags(n) & kNodeHandle) != 0;
    EXPECT_EQ(handles, 2);
    // Remeshing happens at the start of a frame: the mesh the frame ends with is the one the
    // sizing field of that start asked for, so its edges satisfy it.
    for (EdgeId e : mesh.edges()) ASSERT_LE(edge_size2(mesh, e), 1.0 + 1e-9) << "frame " << s.frame;
    EXPECT_LE(s.energy.total(), e0 + 1e-6) << "frame " << s.frame;
  }
  EXPECT_GT(splits, 0);
  EXPECT_GT(collapses, 500);  // the 1,152-face start is far finer than a flat sheet needs
}

}  // namespace
}  // namespace vdc
