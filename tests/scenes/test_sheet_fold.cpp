// sheet-fold: a sheet dropped on the ground that folds onto itself must end every frame with no
// cloth-cloth intersection and no vertex in the ground, also when impact zones are forced to
// fail and the fallbacks take over.
#include <gtest/gtest.h>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "support/triangle_soup.hpp"

namespace vdc {
namespace {

struct FoldRun {
  int contacts = 0, fallbacks = 0, halvings = 0;
  double lowest_top = 1e9;
};

// Runs sheet-fold for `frames` frames, checking at every frame end that no vertex is in the
// ground by more than 10% of the thickness and that no two cloth triangles intersect.
FoldRun run_sheet_fold(Scene scene, int frames) {
  const double thickness = scene.collision.thickness;
  Simulation sim(std::move(scene), SimOptions{SimMode::Fixed, 1});
  FoldRun run;
  for (int f = 0; f < frames; ++f) {
    FrameStats s = sim.step_frame();
    run.contacts += s.impacts + s.proximities;
    run.fallbacks += s.collision_fallbacks;
    run.halvings += s.halvings;
    const Mesh& m = sim.garment_mesh(0);
    double top = -1e9;
    for (NodeId n : m.nodes()) {
      EXPECT_GE(m.x(n).y(), -0.1 * thickness) << "frame " << s.frame << ": a vertex is in the ground";
      top = std::max(top, m.x(n).y());
    }
    EXPECT_EQ(test::self_crossings(m), 0) << "frame " << s.frame;
    run.lowest_top = std::min(run.lowest_top, top);
    if (::testing::Test::HasFailure()) break;
  }
  return run;
}

TEST(SheetFold, NoIntersectionsAndNothingInTheGroundAtAnyFrameEnd) {
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-fold.json");
  const int frames = scene.frames;  // the whole scene
  FoldRun run = run_sheet_fold(std::move(scene), frames);
  EXPECT_GT(run.contacts, 1000);   // it did land and fold (proximity pairs and impacts, summed over frames)
  EXPECT_LT(run.lowest_top, 0.2);  // the 1 m sheet ends up lying in folds, not standing
  EXPECT_EQ(run.fallbacks, 0);
}

TEST(SheetFold, ZonesThatCannotSeparateHalveTheStepThenFreezeAndTheRunGoesOn) {
  // One detection round a step: every impact zone fails to confirm its separation, so the step
  // is retried in halves and, at the last level, the zone keeps its start positions. A softer
  // repulsion than the default lets the folds reach the impact zones.
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-fold.json");
  scene.collision.max_iterations = 1;
  scene.collision.repulsion_stiffness = 1;
  FoldRun run = run_sheet_fold(std::move(scene), 20);
  EXPECT_GT(run.halvings, 0);
  EXPECT_GT(run.fallbacks, 0);
}

}  // namespace
}  // namespace vdc
