// The shipped scenes with several cameras: solo-dancer filmed at once by its shot camera and
// from the side, and through its shot camera as a stereo pair, whose eyes are that camera moved
// 3.25 cm to either side, looking the same way.
#include <gtest/gtest.h>

#include <string>

#include "scene/scene.hpp"

namespace vdc {
namespace {

Scene shipped(const std::string& name) { return load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/" + name + ".json"); }

TEST(ShippedCameras, SoloDancerFromTwoSidesAndInStereo) {
  const Scene single = shipped("solo-dancer"), two = shipped("solo-dancer-two-cameras"), stereo = shipped("solo-dancer-stereo");
  ASSERT_EQ(single.cameras.size(), 1u);
  ASSERT_EQ(two.cameras.size(), 2u);
  EXPECT_EQ(two.cameras[0].name, "shot");
  EXPECT_EQ(two.cameras[1].name, "side");
  ASSERT_EQ(stereo.cameras.size(), 2u);
  EXPECT_EQ(stereo.cameras[0].name, "left");
  EXPECT_EQ(stereo.cameras[1].name, "right");
  const CameraPath& shot = single.cameras[0].path;
  for (double t : {0.0, 3.0, 6.5, 9.0}) {
    const Camera c = shot.at(t), left = stereo.cameras[0].path.at(t), right = stereo.cameras[1].path.at(t);
    EXPECT_EQ(two.cameras[0].path.at(t).position, c.position) << t;
    EXPECT_NEAR((right.position - left.position - 0.065 * c.basis()[0]).norm(), 0.0, 1e-12) << t;
    EXPECT_NEAR((0.5 * (left.position + right.position) - c.position).norm(), 0.0, 1e-12) << t;
    EXPECT_NEAR((left.basis()[2] - c.basis()[2]).norm(), 0.0, 1e-12) << t;
  }
  EXPECT_EQ(two.cameras[1].path.cuts_in(0, 10).size(), 0u);
  EXPECT_EQ(two.cameras[0].path.cuts_in(0, 10).size(), 2u);
  EXPECT_EQ(stereo.cameras[1].path.cuts_in(0, 10).size(), 2u);
}

}  // namespace
}  // namespace vdc
