// A remesh whose crossings untangling cannot remove is not kept: a cap of cloth on a sphere, in
// adaptive mode with untangling allowed no pass, asked for edges far too long for the sphere,
// falls back to the frame's start mesh, and no frame ends crossed.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "support/triangle_soup.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

// A 20 cm square of cloth wrapped onto a sphere of 10 cm radius (distances from the square's
// centre kept along each meridian, 6 mm off the surface), in 10 x 10 cells of 2 cm: chords that
// short dip 0.5 mm, so the wrapped cap crosses nothing. OBJ text, world positions and material
// coordinates.
std::string wrapped_cap_obj() {
  const int cells = 10;
  const double side = 0.2, radius = 0.106;
  std::ostringstream obj;
  obj << std::setprecision(17);
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const double du = side * i / cells - side / 2, dv = side * j / cells - side / 2;
      const double theta = std::hypot(du, dv) / radius, phi = std::atan2(dv, du);
      obj << "v " << radius * std::sin(theta) * std::cos(phi) << " " << radius * std::cos(theta) << " "
          << -radius * std::sin(theta) * std::sin(phi) << "\nvt " << du + side / 2 << " " << dv + side / 2 << "\n";
    }
  auto id = [&](int i, int j) { return j * (cells + 1) + i + 1; };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      obj << "f " << a << "/" << a << " " << b << "/" << b << " " << c << "/" << c << "\n";
      obj << "f " << a << "/" << a << " " << c << "/" << c << " " << d << "/" << d << "\n";
    }
  return obj.str();
}

// The cap asked to coarsen to 14-15 cm edges, with untangling allowed no pass: the first remesh
// lays chords that dip 2.5 cm, through the sphere, which detection alone cannot undo; the frame
// falls back to its start mesh, keeping its faces, and no frame ends crossed.
TEST(RemeshFallback, CrossingsUntanglingCannotRemoveMakeTheFrameKeepItsStartMesh) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-fallback-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "cap.obj") << wrapped_cap_obj();
  std::ofstream(dir / "scene.json") << R"({"frame_time": 0.04, "substeps": 8, "remeshing": {"size": [0.14, 0.15]},
    "collision": {"thickness": 0.003},
    "garments": [{"name": "cap", "mesh": "cap.obj", "material": ")" << VDCLOTH_SOURCE_DIR << R"(/materials/cotton.json"}],
    "obstacles": [{"name": "sphere", "mesh": {"sphere": {"radius": 0.1, "subdivisions": 3}}}]})";
  Scene scene = load_scene((dir / "scene.json").string());
  fs::remove_all(dir);
  scene.collision.untangle_iterations = 0;  // detection only: any crossing left by a remesh stays
  Simulation sim(std::move(scene), SimOptions{SimMode::Adaptive, 1});
  auto crossings = [&] {
    const Mesh& cloth = sim.garment_mesh(0);
    return test::self_crossings(cloth) + test::crossings_between(cloth, sim.obstacle_mesh(0));
  };
  ASSERT_EQ(crossings(), 0) << "the wrapped cap starts clear of the sphere";
  const int faces_before = sim.num_faces();
  const FrameStats first = sim.step_frame();
  EXPECT_EQ(first.remesh_undone, 1);
  EXPECT_GT(first.collapses, 0) << "the remesh that was undone coarsened";
  EXPECT_EQ(first.faces, faces_before) << "the frame kept its start mesh";
  EXPECT_EQ(crossings(), 0);
  for (int f = 0; f < 2; ++f) {
    sim.step_frame();
    EXPECT_EQ(crossings(), 0) << "frame " << sim.frame();
  }
}

}  // namespace
}  // namespace vdc
