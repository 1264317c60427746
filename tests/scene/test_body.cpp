// Procedural body on CMU motion capture (Debian's assimp-testmodels, scaled to metres): the
// rest mesh is closed, manifold and outward; skinning at the rest pose gives it back exactly;
// posed at several frames it stays closed and outward with a volume near the rest volume.
#include <gtest/gtest.h>

#include "core/isosurface.hpp"
#include "scene/bvh_motion.hpp"
#include "scene/body.hpp"
#include "scene/figure.hpp"

namespace vdc {
namespace {

TEST(Isosurface, SphereIsClosedOutwardAndNearTheTrueRadius) {
  Aabb box;
  box.grow(Vec3(-1.2, -1.2, -1.2));
  box.grow(Vec3(1.2, 1.2, 1.2));
  MeshSource s = polygonize([](const Vec3& p) { return p.norm() - 1.0; }, box, 0.1);
  with_canonical_uvs(s);
  Mesh m = build_mesh(s);  // throws on non-manifold or inconsistent orientation
  for (EdgeId e : m.edges()) ASSERT_FALSE(m.is_boundary(e));
  EXPECT_EQ(m.num_nodes() - m.num_edges() + m.num_faces(), 2);  // a sphere's Euler characteristic
  EXPECT_NEAR(enclosed_volume(s, s.positions), 4.0 / 3.0 * M_PI, 0.03 * 4.0 / 3.0 * M_PI);
  for (const Vec3& p : s.positions) EXPECT_NEAR(p.norm(), 1.0, 0.02);
}

TEST(Body, ClosedOutwardAndSkinnedExactlyAtRest) {
  for (const char* file : {"01_01.bvh", "Boxing_Toes.bvh"}) {
    Motion motion = read_bvh(std::string("/usr/share/assimp/models/BVH/") + file);
    // Scale so that the rest figure is 1.75 m tall.
    const auto rest = motion.world(Body::rest_pose(motion.skeleton));
    double lo = 1e9, hi = -1e9;
    for (const auto& t : rest) lo = std::min(lo, t.translation().y()), hi = std::max(hi, t.translation().y());
    scale_lengths(motion, 1.6 / (hi - lo));
    Body body(motion, BodyParams{});
    const MeshSource& mesh = body.rest_mesh();
    Mesh m = build_mesh(mesh);
    for (EdgeId e : m.edges()) ASSERT_FALSE(m.is_boundary(e)) << file;
    const double v0 = enclosed_volume(mesh, mesh.positions);
    EXPECT_GT(v0, 0.03) << file;  // outward, and a human's volume (0.06 to 0.08 m^3) in order of magnitude
    EXPECT_LT(v0, 0.15) << file;
    EXPECT_EQ(body.skin(Body::rest_pose(motion.skeleton)), mesh.positions) << file;
    for (std::size_t f : {std::size_t{0}, motion.frames.size() / 3, motion.frames.size() / 2, motion.frames.size() - 1}) {
      const std::vector<Vec3> x = body.skin(motion.frame_pose(f));
      const double v = enclosed_volume(mesh, x);
      EXPECT_GT(v, 0.8 * v0) << file << " frame " << f;
      EXPECT_LT(v, 1.2 * v0) << file << " frame " << f;
    }
  }
}

// A figure polygonized once serves every body made from the same capsules: the second body
// takes the first's mesh (bit for bit what polygonizing gives), a slimmer build makes its own.
TEST(Body, ACacheGivesTheSameFigureItsMeshAgain) {
  Motion figure;
  figure.skeleton = figure_skeleton();
  figure.frames.assign(1, std::vector<double>(static_cast<std::size_t>(figure.skeleton.num_channels), 0.0));
  BodyParams params;
  params.resolution = 0.05;
  const Body alone(figure, params);
  BodyMeshCache cache;
  const Body first(figure, params, &cache);
  EXPECT_EQ(cache.size(), 1u);
  const Body second(figure, params, &cache);
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_EQ(second.rest_mesh().positions, alone.rest_mesh().positions);
  EXPECT_EQ(second.rest_mesh().faces, alone.rest_mesh().faces);
  EXPECT_EQ(second.skin(Body::rest_pose(figure.skeleton)), alone.skin(Body::rest_pose(figure.skeleton)));
  params.build = 0.8;
  const Body slimmer(figure, params, &cache);
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_NE(slimmer.rest_mesh().positions, alone.rest_mesh().positions);
}

}  // namespace
}  // namespace vdc
