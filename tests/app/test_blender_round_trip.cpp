// The Blender round trip, in Debian's Blender run headless (tools/blender/check_round_trip.py):
// a shot built in Blender (a skinned, animated leg, a cloth square, a camera that moves, rolls
// and zooms) exported by the add-on as a vdcloth scene, simulated by the program, loaded back
// onto the same frames: the run's leg is Blender's own deformed leg within 0.1 mm at every
// frame, its camera the scene camera (0.1 mm, 1e-5 in direction, 1e-4 degrees of field of view).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "support/process_output.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

TEST(BlenderRoundTrip, AShotExportedFromBlenderRunsAndComesBackOnItsFrames) {
  ASSERT_EQ(test::capture("command -v blender >/dev/null 2>&1").status, 0) << "no blender: scripts/install-deps.sh installs it";
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_blender_trip_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string script = std::string(VDCLOTH_SOURCE_DIR) + "/tools/blender/check_round_trip.py";
  const test::Output made = test::capture("blender -b --factory-startup --python '" + script + "' -- make '" + dir.string() + "' 2>&1");
  ASSERT_EQ(made.status, 0) << made.text;
  ASSERT_NE(made.text.find("check_round_trip: made and exported"), std::string::npos) << made.text;
  for (const char* file : {"shot.json", "leg.gltf", "cloth.obj", "camera.chan"}) EXPECT_TRUE(fs::exists(dir / file)) << file;
  const test::Output run = test::capture(std::string(VDCLOTH_BINARY) + " run '" + (dir / "shot.json").string() + "' --mode adaptive --threads 1 --out '" +
                                         (dir / "run").string() + "' 2>&1");
  ASSERT_EQ(run.status, 0) << run.text;
  const test::Output check = test::capture("blender -b '" + (dir / "shot.blend").string() + "' --python '" + script + "' -- check '" +
                                           (dir / "run").string() + "' 2>&1");
  EXPECT_EQ(check.status, 0) << check.text;
  EXPECT_NE(check.text.find("check_round_trip: 13 frames checked, 0 failure(s)"), std::string::npos) << check.text;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vdc
