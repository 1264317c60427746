// The project's figure and its authored motions: the shipped BVH files are what their keyframe
// files author, last at least 8 s, start from the rest pose; the procedural body of the figure
// is closed and outward at the rest pose and at poses through each motion.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "scene/bvh_motion.hpp"
#include "scene/body.hpp"
#include "scene/figure.hpp"

namespace vdc {
namespace {

std::string motion_path(const std::string& name, const char* ext) { return std::string(VDCLOTH_SOURCE_DIR) + "/motions/" + name + ext; }

TEST(Figure, ShippedMotionsAreTheirKeyframesAndStartAtRest) {
  for (const std::string name : {"dance", "karate"}) {
    const Motion shipped = read_bvh(motion_path(name, ".bvh"));
    const Motion authored = author_motion_file(motion_path(name, ".json"));
    ASSERT_EQ(shipped.frames.size(), authored.frames.size()) << name;
    EXPECT_GE(shipped.duration(), 8.0) << name;
    for (std::size_t f = 0; f < shipped.frames.size(); ++f)
      for (std::size_t c = 0; c < shipped.frames[f].size(); ++c)
        ASSERT_NEAR(shipped.frames[f][c], authored.frames[f][c], 1e-6) << name << " frame " << f << " channel " << c;
    for (double v : shipped.frames.front()) EXPECT_EQ(v, 0.0) << name << ": the first frame is the rest pose";
  }
}

TEST(Figure, AuthoringRefusesUnknownJointsAndUnorderedKeys) {
  PoseKey a, b;
  b.time = 1;
  b.rotation["LeftElbowPad"] = Vec3(10, 0, 0);
  EXPECT_THROW(author_motion(figure_skeleton(), {a, b}, 30, "test"), InputError);
  b.rotation.clear();
  b.time = 0;
  EXPECT_THROW(author_motion(figure_skeleton(), {a, b}, 30, "test"), InputError);
}

TEST(Figure, BodyIsClosedAndOutwardThroughEachMotion) {
  for (const std::string name : {"dance", "karate"}) {
    const Motion motion = read_bvh(motion_path(name, ".bvh"));
    const Body body(motion, BodyParams{});
    const MeshSource& mesh = body.rest_mesh();
    Mesh m = build_mesh(mesh);  // manifold and consistently oriented, or it throws
    for (EdgeId e : m.edges()) ASSERT_FALSE(m.is_boundary(e)) << name;
    const double v0 = enclosed_volume(mesh, mesh.positions);
    EXPECT_GT(v0, 0.04) << name;
    EXPECT_LT(v0, 0.12) << name;
    EXPECT_EQ(body.skin(Body::rest_pose(motion.skeleton)), mesh.positions) << name;
    EXPECT_EQ(body.skin(motion.frame_pose(0)), mesh.positions) << name;
    for (double t = 1.0; t < motion.duration(); t += 1.1) {
      const double v = enclosed_volume(mesh, body.skin(motion.pose_at(t)));
      EXPECT_GT(v, 0.8 * v0) << name << " at " << t << " s";
      EXPECT_LT(v, 1.2 * v0) << name << " at " << t << " s";
    }
  }
}

}  // namespace
}  // namespace vdc
