// Remeshing never adds a crossing: a cap of cloth on a sphere, in adaptive mode with untangling
// allowed no pass, asked for edges far too long for the sphere, coarsens only where its chords
// stay out of the sphere. A remesh that leaves more crossings than the frame started with (a
// sheet through the sphere from the start, refined: each crossing face split into several) is
// not kept: the frame falls back to its start mesh.
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

// A square of cloth `side` wide in cells x cells cells of two triangles, as OBJ text: material
// coordinates (du, dv) + side / 2, world position place(du, dv) for du, dv from the centre.
template <class Place>
std::string square_obj(int cells, double side, Place&& place) {
  std::ostringstream obj;
  obj << std::setprecision(17);
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const double du = side * i / cells - side / 2, dv = side * j / cells - side / 2;
      const Vec3 x = place(du, dv);
      obj << "v " << x.x() << " " << x.y() << " " << x.z() << "\nvt " << du + side / 2 << " " << dv + side / 2 << "\n";
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

// A 20 cm square of cloth wrapped onto a sphere of 10 cm radius (distances from the square's
// centre kept along each meridian, 6 mm off the surface), in 10 x 10 cells of 2 cm: chords that
// short dip 0.5 mm, so the wrapped cap crosses nothing.
std::string wrapped_cap_obj() {
  const double radius = 0.106;
  return square_obj(10, 0.2, [&](double du, double dv) {
    const double theta = std::hypot(du, dv) / radius, phi = std::atan2(dv, du);
    return Vec3(radius * std::sin(theta) * std::cos(phi), radius * std::cos(theta), -radius * std::sin(theta) * std::sin(phi));
  });
}

fs::path scene_dir(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-" + tag + "-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

Scene cloth_on_sphere(const fs::path& dir, const std::string& obj, const std::string& size) {
  std::ofstream(dir / "cloth.obj") << obj;
  std::ofstream(dir / "scene.json") << R"({"frame_time": 0.04, "substeps": 8, "remeshing": {"size": )" << size << R"(},
    "collision": {"thickness": 0.003},
    "garments": [{"name": "cloth", "mesh": "cloth.obj", "material": ")" << VDCLOTH_SOURCE_DIR << R"(/materials/cotton.json"}],
    "obstacles": [{"name": "sphere", "mesh": {"sphere": {"radius": 0.1, "subdivisions": 3}}}]})";
  Scene scene = load_scene((dir / "scene.json").string());
  fs::remove_all(dir);
  scene.collision.untangle_iterations = 0;  // detection only: any crossing left by a remesh stays
  return scene;
}

int crossings(const Simulation& sim) {
  const Mesh& cloth = sim.garment_mesh(0);
  return test::self_crossings(cloth) + test::crossings_between(cloth, sim.obstacle_mesh(0));
}

// The cap asked to coarsen to 14-15 cm edges: collapsing it to chords that long would dip them
// 2.5 cm, through the sphere; the remesher refuses each collapse that would cut the sphere, so
// the cap coarsens where it can, keeps what it coarsened, and no frame ends crossed.
TEST(RemeshGuard, ACapCoarsensOnlyWhereItsChordsStayOutOfTheSphere) {
  Simulation sim(cloth_on_sphere(scene_dir("guard"), wrapped_cap_obj(), "[0.14, 0.15]"), SimOptions{SimMode::Adaptive, 1});
  ASSERT_EQ(crossings(sim), 0) << "the wrapped cap starts clear of the sphere";
  const int faces_before = sim.num_faces();
  const FrameStats first = sim.step_frame();
  EXPECT_EQ(first.remesh_undone, 0);
  EXPECT_GT(first.remesh_refused, 0) << "collapses through the sphere were asked for";
  EXPECT_GT(first.collapses, 0);
  EXPECT_LT(first.faces, faces_before) << "the remesh coarsened where it could, and was kept";
  EXPECT_EQ(crossings(sim), 0);
  for (int f = 0; f < 2; ++f) {
    const FrameStats next = sim.step_frame();
    EXPECT_EQ(next.remesh_undone, 0);
    EXPECT_EQ(crossings(sim), 0) << "frame " << sim.frame();
  }
}

// A flat 20 cm sheet of 4 x 4 cells at 9.5 cm above the centre of the 10 cm sphere: it cuts the
// sphere's top in a circle of 3 cm radius from the start, and untangling is allowed no pass.
std::string sheet_through_sphere_obj() {
  return square_obj(4, 0.2, [](double du, double dv) { return Vec3(du, 0.095, -dv); });
}

// Asked for 1 cm edges, the remesh splits the faces that cross the sphere into many: more
// crossing pairs than the frame started with, so the frame keeps its start mesh and its count.
TEST(RemeshFallback, ARemeshThatLeavesMoreCrossingsIsUndone) {
  Simulation sim(cloth_on_sphere(scene_dir("fallback"), sheet_through_sphere_obj(), "[0.005, 0.01]"), SimOptions{SimMode::Adaptive, 1});
  const int at_start = crossings(sim);
  ASSERT_GT(at_start, 0) << "the sheet starts through the sphere";
  const int faces_before = sim.num_faces();
  const FrameStats first = sim.step_frame();
  EXPECT_EQ(first.remesh_undone, 1);
  EXPECT_GT(first.splits, 0) << "the remesh that was undone refined";
  EXPECT_EQ(first.faces, faces_before) << "the frame kept its start mesh";
  EXPECT_LE(crossings(sim), at_start);
}

}  // namespace
}  // namespace vdc
