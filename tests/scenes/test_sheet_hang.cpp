// The default scene, sheet-hang, over its full 250 frames at 8 substeps: no NaN, no energy gain,
// and the sheet comes to rest under its two held corners.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

TEST(SheetHang, RunsSettlesAndNeverGainsEnergy) {
  Scene scene = load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/sheet-hang.json");
  ASSERT_EQ(scene.frames, 250);
  ASSERT_EQ(scene.substeps, 8);
  double mass = 0;
  for (const auto& g : scene.garments) mass += g.material.density * 1.0;  // a 1 m^2 sheet
  Simulation sim(std::move(scene), SimOptions{SimMode::Fixed, 1});
  const double e0 = sim.energy().total();
  double peak_kinetic = 0, last_kinetic = 0;
  int halvings = 0;
  for (int f = 0; f < 250; ++f) {
    FrameStats s = sim.step_frame();
    ASSERT_TRUE(std::isfinite(s.energy.total())) << "frame " << s.frame;
    // Held corners do no work and the integrator only dissipates: the total never rises above
    // the start (1e-6 J allows for the solver tolerance).
    ASSERT_LE(s.energy.total(), e0 + 1e-6) << "frame " << s.frame;
    peak_kinetic = std::max(peak_kinetic, s.energy.kinetic);
    last_kinetic = s.energy.kinetic;
    halvings += s.halvings;
  }
  EXPECT_EQ(halvings, 0);
  // The swing peaks at about the potential energy the sheet loses falling half its length,
  // m g L / 2 ~ 0.6 J. At rest means kinetic energy below 1e-4 J: an rms speed
  // sqrt(2 KE / m) under 4 cm/s, and well under 1% of the peak.
  EXPECT_GT(peak_kinetic, 0.1);
  EXPECT_LT(last_kinetic, 1e-4) << "rms speed " << std::sqrt(2 * last_kinetic / mass) << " m/s";
  EXPECT_LT(last_kinetic, 0.01 * peak_kinetic);
}

}  // namespace
}  // namespace vdc
