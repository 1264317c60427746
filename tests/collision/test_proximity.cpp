// Proximity pairs on hand-built configurations: the right pair, weights, normal and distance,
// one pair per vertex and side even over a shared edge, obstacles pushing outward, nothing
// beyond the band, and no pair inside a flat sheet.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "collision/collider.hpp"
#include "collision/distance.hpp"
#include "remesh/obstacle_planes.hpp"
#include "core/mesh_build.hpp"

namespace vdc {
namespace {

struct Scenario {
  std::vector<std::array<int32_t, 3>> faces;
  Eigen::VectorXd x, v;
  std::vector<CollisionMesh> obstacles;
  std::vector<std::vector<Vec3>> ox, ov;
  std::vector<ProximityPair> find(double band) {
    Collider c(faces, obstacles, static_cast<int32_t>(x.size() / 3));
    std::vector<char> fixed(static_cast<std::size_t>(x.size() / 3), 0);
    return c.proximities(x, v, fixed, ox, ov, band, 2);
  }
};

Eigen::VectorXd stack(std::initializer_list<Vec3> pts) {
  Eigen::VectorXd x(3 * static_cast<int64_t>(pts.size()));
  int i = 0;
  for (const Vec3& p : pts) x.segment<3>(3 * i++) = p;
  return x;
}

TEST(Proximity, VertexOverAFaceGivesOnePairWithItsBarycentricWeights) {
  Scenario s;
  // Two faces of a unit square at y = 0 sharing the diagonal 1-2, and a lone triangle whose
  // corner 4 hangs 3 mm over the point (0.25, 0, 0.5) of face 0.
  s.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}};
  s.x = stack({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0.25, 0.003, 0.5}, {0.25, 0.5, 2}, {-0.5, 0.5, 2}});
  s.v = Eigen::VectorXd::Zero(s.x.size());
  auto pairs = s.find(0.004);
  ASSERT_EQ(pairs.size(), 1u);
  const ProximityPair& p = pairs[0];
  EXPECT_EQ(p.nodes[0], 4);
  EXPECT_NEAR(p.distance, 0.003, 1e-15);
  EXPECT_NEAR(p.normal.y(), 1.0, 1e-12);
  Vec3 sep = Vec3::Zero();
  double wsum = 0;
  for (std::size_t j = 0; j < 4; ++j) {
    sep += p.weights[j] * s.x.segment<3>(3 * p.nodes[j]);
    wsum += p.weights[j];
  }
  EXPECT_NEAR(wsum, 0, 1e-15);
  EXPECT_LT((sep - Vec3(0, 0.003, 0)).norm(), 1e-14);
  EXPECT_TRUE(s.find(0.0029).empty());
}

TEST(Proximity, VertexOverASharedEdgeIsCountedOncePerSide) {
  Scenario s;
  s.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}};
  // Node 4 right over the middle of the shared diagonal, 2 mm above.
  s.x = stack({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0.5, 0.002, 0.5}, {0.5, 0.5, 2}, {-0.5, 0.5, 2}});
  s.v = Eigen::VectorXd::Zero(s.x.size());
  auto pairs = s.find(0.004);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_NEAR(pairs[0].distance, 0.002, 1e-15);
  // A layer on each side: one pair per side.
  s.faces.push_back({7, 8, 9});
  s.x.conservativeResize(30);
  s.x.segment<3>(21) = Vec3(0, 0.004, 0);
  s.x.segment<3>(24) = Vec3(1, 0.004, 1);
  s.x.segment<3>(27) = Vec3(1, 0.004, 0);
  s.v = Eigen::VectorXd::Zero(s.x.size());
  pairs = s.find(0.0025);
  int over_node4 = 0;
  for (const auto& p : pairs)
    if (p.nodes[0] == 4 && p.weights[0] == 1.0) ++over_node4;  // vertex-face pairs of node 4
  EXPECT_EQ(over_node4, 2);
}

TEST(Proximity, CrossingEdgesGiveAnEdgePairAndObstaclesPushOutward) {
  Scenario s;
  // A cloth triangle whose edge 0-1 runs along x at height 1 mm over an obstacle edge along z
  // (the shared edge of two obstacle faces, outward +y); no vertex is over a face.
  s.faces = {{0, 1, 2}};
  s.x = stack({{-1, 0.001, 0}, {1, 0.001, 0}, {0, 0.5, -0.5}});
  s.v = Eigen::VectorXd::Zero(9);
  CollisionMesh roof;
  roof.faces = {{0, 1, 2}, {0, 3, 1}};
  s.obstacles = {roof};
  // Two faces meeting at the ridge 0-1 along z, sloping down on both sides.
  s.ox = {{Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(1, -1, 0), Vec3(-1, -1, 0)}};
  s.ov = {{Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)}};
  auto pairs = s.find(0.004);
  ASSERT_EQ(pairs.size(), 1u);
  const ProximityPair& p = pairs[0];
  EXPECT_EQ(p.nodes[0], 0);
  EXPECT_EQ(p.nodes[1], 1);
  EXPECT_EQ(p.nodes[2], -1);
  EXPECT_NEAR(p.weights[0], 0.5, 1e-12);
  EXPECT_NEAR(p.weights[2], -0.5, 1e-12);
  EXPECT_NEAR(p.distance, 0.001, 1e-12);
  EXPECT_NEAR(p.normal.y(), 1.0, 1e-12);
  EXPECT_EQ(p.obstacle_velocity[2], Vec3(0, 0, 1));
  // Sunk 1 mm below the ridge: still pushed up (outward), with a negative distance.
  s.x.segment<3>(0) = Vec3(-1, -0.001, 0);
  s.x.segment<3>(3) = Vec3(1, -0.001, 0);
  pairs = s.find(0.004);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_NEAR(pairs[0].distance, -0.001, 1e-12);
  EXPECT_NEAR(pairs[0].normal.y(), 1.0, 1e-12);
}

TEST(Proximity, AFlatSheetDoesNotRepelItselfEvenWhenTheBandReachesPastItsNeighbours) {
  // A 10 cm sheet of 1 cm cells at y = 0, its nodes jittered in the plane so the triangles are
  // irregular, and a band of 1.5 cm, past every node's 2-ring: nearest points of non-incident
  // faces are all on their borders and in the plane, and none of them may become a pair.
  const MeshSource grid = make_grid(0.1, 0.1, 10, 10);
  Scenario s;
  s.faces = position_triangles(grid);
  const auto n = static_cast<int64_t>(grid.positions.size());
  s.x.resize(3 * n);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.002, 0.002);
  for (int64_t i = 0; i < n; ++i) {
    const Vec3& p = grid.positions[static_cast<std::size_t>(i)];
    s.x.segment<3>(3 * i) = Vec3(p.x() + jitter(rng), 0, p.z() + jitter(rng));
  }
  s.v = Eigen::VectorXd::Zero(s.x.size());
  const double band = 0.015;
  int in_plane_neighbours = 0;  // what a closest-point test alone would have paired
  for (int64_t i = 0; i < n; ++i)
    for (const auto& t : s.faces) {
      if (t[0] == i || t[1] == i || t[2] == i) continue;
      const Vec3 p = s.x.segment<3>(3 * i);
      if (point_triangle_distance(p, s.x.segment<3>(3 * t[0]), s.x.segment<3>(3 * t[1]), s.x.segment<3>(3 * t[2])) < band) {
        ++in_plane_neighbours;
        break;
      }
    }
  EXPECT_EQ(in_plane_neighbours, n);
  EXPECT_TRUE(s.find(band).empty());

  // Folded over itself 5 mm higher, shifted half a cell so its nodes are inside faces below,
  // the sheet repels its copy: every node of the copy over the sheet pairs with a face below.
  const int32_t base = static_cast<int32_t>(n);
  for (const auto& t : position_triangles(grid)) s.faces.push_back({t[0] + base, t[2] + base, t[1] + base});
  s.x.conservativeResize(6 * n);
  for (int64_t i = 0; i < n; ++i) {
    const Vec3& p = grid.positions[static_cast<std::size_t>(i)];
    s.x.segment<3>(3 * (n + i)) = Vec3(p.x() + 0.005, 0.005, p.z() - 0.005);
  }
  s.v = Eigen::VectorXd::Zero(s.x.size());
  int over_the_sheet = 0, paired = 0;
  const auto pairs = s.find(band);
  for (int64_t i = n; i < 2 * n; ++i) {
    const Vec3 p = s.x.segment<3>(3 * i);
    if (p.x() > 0.001 && p.x() < 0.099 && p.z() < -0.001 && p.z() > -0.099) ++over_the_sheet;
    for (const auto& pr : pairs)
      if (pr.nodes[0] == i && pr.weights[0] == 1.0 && pr.nodes[1] < base) {
        EXPECT_NEAR(pr.distance, 0.005, 1e-12);
        EXPECT_NEAR(pr.normal.y(), 1.0, 1e-12);
        ++paired;
        break;
      }
  }
  EXPECT_EQ(over_the_sheet, 100);
  EXPECT_EQ(paired, over_the_sheet);
}

}  // namespace
}  // namespace vdc

namespace vdc {
namespace {

// A cap of cloth over a ball, some nodes inside the band and some sunk: every obstacle vertex's
// pair is its nearest cloth face within the band, as a search over all faces finds it, and the
// same pairs come whether the obstacle's hierarchies are refit for the query or kept from a
// continuous detection whose step ended at these positions.
TEST(Proximity, ObstacleVerticesPairWithTheirNearestClothFaceWhetherHierarchiesAreKeptOrRefit) {
  const MeshSource ball = make_icosphere(0.1, 3);
  CollisionMesh sphere;
  for (const auto& f : ball.faces) sphere.faces.push_back({f[0].node, f[1].node, f[2].node});
  const MeshSource sheet = make_grid(0.24, 0.24, 24, 24);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> gap(-0.001, 0.005);
  Scenario s;
  s.faces = position_triangles(sheet);
  s.x.resize(3 * static_cast<int64_t>(sheet.positions.size()));
  for (std::size_t i = 0; i < sheet.positions.size(); ++i) {
    const Vec3& q = sheet.positions[i];  // (u, 0, -v) on [0, 0.24]^2
    s.x.segment<3>(3 * static_cast<int64_t>(i)) = Vec3(q.x() - 0.12, 0.1, q.z() + 0.12).normalized() * (0.1 + gap(rng));
  }
  s.v = Eigen::VectorXd::Zero(s.x.size());
  s.obstacles = {sphere};
  s.ox = {ball.positions};
  std::vector<Vec3> velocity_tag(ball.positions.size());  // names the vertex of each pair
  for (std::size_t i = 0; i < velocity_tag.size(); ++i) velocity_tag[i] = Vec3(static_cast<double>(i), 0, 0);
  s.ov = {velocity_tag};
  const double band = 0.004;
  auto vertex_pairs = [&](const std::vector<ProximityPair>& pairs) {
    std::map<int, ProximityPair> by_vertex;
    for (const auto& p : pairs)
      if (p.nodes[3] < 0 && p.weights[3] == -1.0 && p.nodes[0] >= 0) by_vertex[static_cast<int>(p.obstacle_velocity[3].x())] = p;
    return by_vertex;
  };
  const auto refit = vertex_pairs(s.find(band));

  Collider kept(s.faces, s.obstacles, static_cast<int32_t>(s.x.size() / 3));
  std::vector<char> fixed(static_cast<std::size_t>(s.x.size() / 3), 0);
  std::vector<Vec3> earlier = ball.positions;  // the ball was 1 cm lower at the step's start
  for (Vec3& p : earlier) p.y() -= 0.01;
  Eigen::VectorXd x_end = s.x;
  kept.resolve(s.x, x_end, std::vector<double>(s.x.size() / 3, 1.0), fixed, {earlier}, s.ox, CollisionParams{});
  const auto reused = vertex_pairs(kept.proximities(s.x, s.v, fixed, s.ox, s.ov, band, 2));

  int near = 0;
  for (std::size_t i = 0; i < ball.positions.size(); ++i) {
    const Vec3& p = ball.positions[i];
    double best = band;
    for (const auto& f : s.faces)
      best = std::min(best, point_triangle_distance(p, s.x.segment<3>(3 * f[0]), s.x.segment<3>(3 * f[1]), s.x.segment<3>(3 * f[2])));
    const int vi = static_cast<int>(i);
    if (best >= band) {
      EXPECT_EQ(refit.count(vi), 0u) << i;
      EXPECT_EQ(reused.count(vi), 0u) << i;
      continue;
    }
    ++near;
    for (const auto* found : {&refit, &reused}) {
      ASSERT_EQ(found->count(vi), 1u) << i;
      const ProximityPair& pair = found->at(vi);
      Vec3 sep = -p;
      for (std::size_t j = 0; j < 3; ++j) sep += pair.weights[j] * s.x.segment<3>(3 * pair.nodes[j]);
      EXPECT_NEAR(sep.norm(), best, 1e-12) << i;
    }
  }
  EXPECT_GT(near, 50);  // the cap covers a good part of the ball within the band
}

// A collider keeps a search's cloth pairs for the next searches while the cloth stays near where
// they were found, the common motion taken out: a sheet folded over itself 3 mm apart, searched,
// then carried 6 cm with every node jittered by up to a millimetre and two nodes 2 cm (answered
// from the lists), then crumpled by 5 mm everywhere (searched again), gives at each the very pairs
// a new collider finds.
TEST(Proximity, ASearchFromTheKeptPairsFindsWhatANewSearchFinds) {
  const MeshSource grid = make_grid(0.1, 0.1, 12, 12);
  const auto n = static_cast<int64_t>(grid.positions.size());
  Scenario s;
  s.faces = position_triangles(grid);
  for (const auto& t : position_triangles(grid)) s.faces.push_back({t[0] + static_cast<int32_t>(n), t[2] + static_cast<int32_t>(n), t[1] + static_cast<int32_t>(n)});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> mm(-0.001, 0.001);
  s.x.resize(6 * n);
  for (int64_t i = 0; i < n; ++i) {
    const Vec3& p = grid.positions[static_cast<std::size_t>(i)];
    s.x.segment<3>(3 * i) = Vec3(p.x(), mm(rng), p.z());
    s.x.segment<3>(3 * (n + i)) = Vec3(p.x() + 0.004, 0.003 + mm(rng), p.z() - 0.004);
  }
  s.v = Eigen::VectorXd::Zero(s.x.size());
  const double band = 0.004;
  Collider kept(s.faces, {}, static_cast<int32_t>(2 * n));
  const std::vector<char> fixed(static_cast<std::size_t>(2 * n), 0);
  auto same_pairs = [&](const char* when) {
    const std::vector<ProximityPair> got = kept.proximities(s.x, s.v, fixed, {}, {}, band, 2), fresh = s.find(band);
    EXPECT_GT(fresh.size(), 50u) << when;
    ASSERT_EQ(got.size(), fresh.size()) << when;
    for (std::size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].nodes, fresh[k].nodes) << when << ", pair " << k;
      EXPECT_EQ(got[k].weights, fresh[k].weights) << when << ", pair " << k;
      EXPECT_EQ(got[k].normal, fresh[k].normal) << when << ", pair " << k;
      EXPECT_EQ(got[k].distance, fresh[k].distance) << when << ", pair " << k;
    }
  };
  same_pairs("first search");
  for (int64_t i = 0; i < 2 * n; ++i) s.x.segment<3>(3 * i) += Vec3(0.06, 0.01, -0.02) + Vec3(mm(rng), mm(rng), mm(rng));
  for (const int64_t i : {n / 2, n + n / 3}) s.x.segment<3>(3 * i) += Vec3(0.02, 0, 0.01);
  same_pairs("carried");
  std::uniform_real_distribution<double> five_mm(-0.005, 0.005);
  for (int64_t i = 0; i < 2 * n; ++i) s.x.segment<3>(3 * i) += Vec3(five_mm(rng), 0.2 * five_mm(rng), five_mm(rng));
  same_pairs("crumpled");
}

TEST(ObstaclePlanes, NearestPointMatchesBruteForce) {
  const MeshSource ball = make_icosphere(0.1, 2);
  CollisionMesh sphere;
  for (const auto& f : ball.faces) sphere.faces.push_back({f[0].node, f[1].node, f[2].node});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-0.3, 0.3);
  std::vector<Vec3> points;
  for (int i = 0; i < 300; ++i) points.emplace_back(U(rng), U(rng), U(rng));
  const double radius = 0.2;
  auto planes = nearest_obstacle_planes(points, {sphere}, {ball.positions}, radius, 0, 2);
  const auto serial = nearest_obstacle_planes(points, {sphere}, {ball.positions}, radius, 0, 1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(planes[i].point, serial[i].point) << i;  // the same on any number of threads
    EXPECT_EQ(planes[i].normal, serial[i].normal) << i;
    double best = radius;
    for (const auto& f : sphere.faces)
      best = std::min(best, point_triangle_distance(points[i], ball.positions[static_cast<std::size_t>(f[0])],
                                                     ball.positions[static_cast<std::size_t>(f[1])], ball.positions[static_cast<std::size_t>(f[2])]));
    if (best < radius) {
      ASSERT_GT(planes[i].normal.norm(), 0.5) << i;
      EXPECT_NEAR((points[i] - planes[i].point).norm(), best, 1e-12) << i;
      // The normal points from the obstacle point to the node.
      EXPECT_NEAR(planes[i].normal.dot(points[i] - planes[i].point), best, 1e-12) << i;
    } else {
      EXPECT_EQ(planes[i].normal.norm(), 0) << i;
    }
  }
}

// Two squares 1 m wide at heights `heights` (one obstacle mesh, or one mesh each), as obstacles.
struct Squares {
  std::vector<CollisionMesh> meshes;
  std::vector<std::vector<Vec3>> x;
};
Squares squares_at(const std::vector<double>& heights, bool one_mesh) {
  Squares s;
  for (double y : heights) {
    if (!one_mesh || s.meshes.empty()) {
      s.meshes.emplace_back();
      s.x.emplace_back();
    }
    auto& x = s.x.back();
    const auto k = static_cast<int32_t>(x.size());
    for (Vec3 c : {Vec3(-0.5, y, -0.5), Vec3(0.5, y, -0.5), Vec3(0.5, y, 0.5), Vec3(-0.5, y, 0.5)}) x.push_back(c);
    s.meshes.back().faces.push_back({k, k + 1, k + 2});
    s.meshes.back().faces.push_back({k, k + 2, k + 3});
  }
  return s;
}

TEST(ObstaclePlanes, HeldOnlyBetweenTwoSurfacesBothWithinTheHoldDistance) {
  for (bool one_mesh : {false, true}) {
    const Squares layers = squares_at({0.0, 0.005}, one_mesh);
    // Between the layers: 2 mm below and 3 mm above; 1.5 mm and 3.5 mm; above both.
    const std::vector<Vec3> points = {Vec3(0.1, 0.002, 0), Vec3(-0.2, 0.0015, 0.3), Vec3(0, 0.007, 0)};
    const auto wide = nearest_obstacle_planes(points, layers.meshes, layers.x, 0.2, 0.0036, 2);
    EXPECT_TRUE(wide[0].held) << one_mesh;
    EXPECT_TRUE(wide[1].held) << one_mesh;
    EXPECT_FALSE(wide[2].held) << one_mesh;  // both layers on the same side
    const auto narrow = nearest_obstacle_planes(points, layers.meshes, layers.x, 0.2, 0.0032, 2);
    EXPECT_TRUE(narrow[0].held) << one_mesh;
    EXPECT_FALSE(narrow[1].held) << one_mesh;  // the far layer 3.5 mm off
    EXPECT_FALSE(nearest_obstacle_planes(points, layers.meshes, layers.x, 0.2, 0, 2)[0].held) << one_mesh;
    // The nearest point and its direction are those of the search without holding.
    EXPECT_EQ(wide[0].point, narrow[0].point);
    for (const ObstaclePlane& plane : wide) EXPECT_LT((plane.normal - Vec3(0, 1, 0)).norm(), 1e-12) << one_mesh;
  }
  // A node on a convex obstacle is never held by it, however near: every other point of a ball
  // lies behind the plane of its nearest point.
  const MeshSource ball = make_icosphere(0.1, 3);
  CollisionMesh sphere;
  for (const auto& f : ball.faces) sphere.faces.push_back({f[0].node, f[1].node, f[2].node});
  std::vector<Vec3> around;
  for (const Vec3& p : ball.positions) around.push_back(p * 1.02);
  int near = 0;
  for (const ObstaclePlane& plane : nearest_obstacle_planes(around, {sphere}, {ball.positions}, 0.2, 0.01, 2)) {
    near += plane.normal.norm() > 0;
    EXPECT_FALSE(plane.held);
  }
  EXPECT_EQ(near, static_cast<int>(around.size()));
}

}  // namespace
}  // namespace vdc
