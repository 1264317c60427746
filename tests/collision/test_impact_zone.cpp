// Impact-zone projection: constraints satisfied, linear momentum of the zone conserved exactly,
// obstacle points unmoved, and an already separated zone left alone; the collider projects an
// impact to the impact separation.
#include <gtest/gtest.h>

#include <random>

#include "collision/collider.hpp"
#include "collision/impact_zone.hpp"

namespace vdc {
namespace {

Vec3 momentum(const std::vector<Vec3>& x, const std::vector<Vec3>& x0, const std::vector<double>& m) {
  Vec3 p = Vec3::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) p += m[i] * (x[i] - x0[i]);
  return p;
}

TEST(ImpactZone, VertexThroughFaceIsPushedBackAndMomentumIsConserved) {
  // A vertex 1 mm below a triangle it should be above (thickness 1 mm): separation -1 mm.
  std::vector<Vec3> x{Vec3(0.2, 0.2, -0.001), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  std::vector<double> m{0.01, 0.02, 0.03, 0.04};
  ImpactConstraint c{{0, 1, 2, 3}, {1.0, -0.6, -0.2, -0.2}, {}, Vec3(0, 0, 1)};
  const auto x0 = x;
  ProjectionReport r = project_impact_zone(x, m, {c}, 0.001, 1e-12);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(separation(c, x), 0.001, 1e-12);
  EXPECT_LT(momentum(x, x0, m).norm(), 1e-18);
}

TEST(ImpactZone, ManyRandomConstraintsConserveMomentumToRounding) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1), W(0, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 30;
    std::vector<Vec3> x(n);
    std::vector<double> m(n);
    for (int i = 0; i < n; ++i) {
      x[static_cast<std::size_t>(i)] = Vec3(U(rng), U(rng), U(rng)) * 0.05;
      m[static_cast<std::size_t>(i)] = 1e-3 * (1 + W(rng));
    }
    std::vector<ImpactConstraint> cs;
    for (int k = 0; k < 20; ++k) {
      ImpactConstraint c;
      std::array<int32_t, 4> idx{};
      for (auto& v : idx) v = static_cast<int32_t>(rng() % n);
      if (idx[0] == idx[1] || idx[0] == idx[2] || idx[0] == idx[3] || idx[1] == idx[2] || idx[1] == idx[3] || idx[2] == idx[3]) continue;
      double a = W(rng), b = W(rng) * (1 - a);
      c.nodes = idx;
      c.weights = {1.0, -a, -b, -(1 - a - b)};  // vertex minus a point of the face: sums to zero
      c.normal = Vec3(U(rng), U(rng), U(rng)).normalized();
      cs.push_back(c);
    }
    const auto x0 = x;
    ProjectionReport r = project_impact_zone(x, m, cs, 0.002, 1e-9, 5000);
    EXPECT_TRUE(r.converged) << "trial " << trial << " worst " << r.worst_violation;
    // Each step moves the zone's mass-weighted sum by zero: rounding only.
    EXPECT_LT(momentum(x, x0, m).norm(), 1e-15) << "trial " << trial;
    for (const auto& c : cs) EXPECT_GE(separation(c, x), 0.002 - 1e-9);
  }
}

TEST(ImpactZone, ObstaclePointsStayAndSeparatedZonesAreUntouched) {
  // Edge-edge against an obstacle edge (fixed points): only the cloth edge moves.
  std::vector<Vec3> x{Vec3(0, 0, -0.0005), Vec3(1, 0, -0.0005)};
  std::vector<double> m{0.01, 0.01};
  ImpactConstraint c{{0, 1, -1, -1}, {0.5, 0.5, -0.5, -0.5}, {Vec3::Zero(), Vec3::Zero(), Vec3(0.5, -1, 0), Vec3(0.5, 1, 0)},
                     Vec3(0, 0, -1)};
  ProjectionReport r = project_impact_zone(x, m, {c}, 0.001, 1e-12);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(x[0].z(), -0.001, 1e-12);
  EXPECT_NEAR(x[1].z(), -0.001, 1e-12);
  std::vector<Vec3> apart{Vec3(0, 0, -0.01), Vec3(1, 0, -0.01)};
  const auto before = apart;
  project_impact_zone(apart, m, {c}, 0.001, 1e-12);
  EXPECT_EQ(apart, before);
}

}  // namespace
}  // namespace vdc

namespace vdc {
namespace {

// Separation along +z of node a above node b (b < 0: above the fixed origin).
ImpactConstraint above(int32_t a, int32_t b) {
  ImpactConstraint c;
  c.nodes = {a, b, -1, -1};
  c.weights = {1.0, -1.0, 0.0, 0.0};
  c.normal = Vec3(0, 0, 1);
  return c;
}

// Nodes 0, 1, 2 stacked the wrong way round by two impacts that share node 1 (one zone), node 4
// under the fixed origin (a zone of its own), node 3 in no impact, and an impact between fixed
// points only. One projection must meet both constraints of the merged zone at once, conserve
// its momentum, and leave node 3 where it was; the fallback sends each zone back to its start,
// the one on a moving obstacle carried with it.
TEST(ImpactZones, ImpactsSharingANodeAreProjectedAsOneZoneAndFallBackTogether) {
  const double d = 0.01;
  Eigen::VectorXd x_start = Eigen::VectorXd::Zero(15), x(15);
  x << 0, 0, 0, 0, 0, 0.001, 0, 0, 0.002, 1, 0, 0, 0, 0, -0.005;
  const std::vector<double> mass = {1.0, 2.0, 0.5, 1.0, 3.0};
  ImpactConstraint on_obstacle = above(4, -1);
  on_obstacle.has_fixed = true;
  on_obstacle.fixed_motion = Vec3(0, 0, 0.3);
  ImpactConstraint fixed_only = above(-1, -1);
  ImpactZones zones(5);
  zones.add({above(0, 1), above(1, 2), on_obstacle, fixed_only});
  std::vector<char> moved(5, 1);
  const Eigen::VectorXd before = x;
  zones.project(x, mass, d, 1e-9, moved);
  EXPECT_GE(x[2] - x[5], d - 1e-9);   // node 0 above node 1
  EXPECT_GE(x[5] - x[8], d - 1e-9);   // node 1 above node 2
  EXPECT_NEAR(x[14], d, 1e-9);         // node 4 above the origin: only it moves
  double momentum_before = 0, momentum_after = 0;
  for (int n = 0; n < 3; ++n) {
    momentum_before += mass[static_cast<std::size_t>(n)] * before[3 * n + 2];
    momentum_after += mass[static_cast<std::size_t>(n)] * x[3 * n + 2];
  }
  EXPECT_NEAR(momentum_after, momentum_before, 1e-12);
  EXPECT_EQ(moved, (std::vector<char>{1, 1, 1, 0, 1}));
  EXPECT_EQ(x.segment<3>(9), before.segment<3>(9));

  EXPECT_EQ(zones.fall_back(x_start, x), 2);  // the merged zone and node 4's; not the fixed-only impact
  for (int n = 0; n < 3; ++n) EXPECT_EQ(Vec3(x.segment<3>(3 * n)), Vec3::Zero()) << n;
  EXPECT_LT((Vec3(x.segment<3>(12)) - Vec3(0, 0, 0.3)).norm(), 1e-15);
  EXPECT_EQ(x.segment<3>(9), before.segment<3>(9));
}

TEST(Collider, AVertexThatCrossesAnObstacleEndsTheStepAtTheImpactSeparationOnItsSide) {
  // A cloth triangle whose corner 0 drops from 1 mm above an obstacle floor (y = 0) to 10 mm
  // below it in one step; its other corners stay 0.5 m up. The projection moves only corner 0,
  // straight up, to the impact separation (not the whole thickness).
  Collider collider({{0, 1, 2}}, {CollisionMesh{{{0, 2, 1}, {0, 3, 2}}}}, 3);
  Eigen::VectorXd x0(9), x1(9);
  x0 << 0.3, 0.001, -0.2, 0.3, 0.5, 0.2, 0.5, 0.5, -0.2;
  x1 = x0;
  x1(1) = -0.01;
  const std::vector<Vec3> floor{Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(1, 0, 1), Vec3(-1, 0, 1)};
  CollisionParams params;
  params.thickness = 0.003;
  params.impact_separation = 0.0003;
  const CollisionStats stats = collider.resolve(x0, x1, {0.01, 0.01, 0.01}, {0, 0, 0}, {floor}, {floor}, params);
  EXPECT_EQ(stats.fallbacks, 0);
  EXPECT_GE(stats.impacts, 1);
  EXPECT_NEAR(x1(1), 0.0003, 1e-3 * params.thickness);
  EXPECT_NEAR(x1(0), 0.3, 1e-15);
  EXPECT_NEAR(x1(2), -0.2, 1e-15);
  EXPECT_EQ(x1.tail<6>(), x0.tail<6>());
}

// The work bound of a detection round. The step above meets 4 candidate pairs: corner 0 against
// both floor triangles (its path box reaches y = 0), and the cloth edges 0-1 and 0-2 against the
// floor's diagonal (the only floor edge whose box reaches z = -0.2 to 0.2); the corners up at
// 0.5 m meet nothing. Six cloth primitives (3 nodes, 3 edges): a bound of 1 a primitive (6)
// detects as before; 0 is over it, and every free node keeps its start position.
TEST(Collider, ADetectionRoundOverItsCandidateBoundStopsAndTheClothKeepsItsStart) {
  Collider collider({{0, 1, 2}}, {CollisionMesh{{{0, 2, 1}, {0, 3, 2}}}}, 3);
  Eigen::VectorXd x0(9);
  x0 << 0.3, 0.001, -0.2, 0.3, 0.5, 0.2, 0.5, 0.5, -0.2;
  Eigen::VectorXd x1 = x0;
  x1(1) = -0.01;
  x1(4) = 0.45;  // a free corner moving too, kept at its start when over the bound
  const std::vector<Vec3> floor{Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(1, 0, 1), Vec3(-1, 0, 1)};
  CollisionParams params;
  params.thickness = 0.003;
  params.impact_separation = 0.0003;
  // The step resolved at a bound of `per_primitive`, corner 2 held or not: its stats and end.
  auto resolved = [&](int per_primitive, char hold_corner_2, Eigen::VectorXd& x_end) {
    params.max_candidates_per_primitive = per_primitive;
    x_end = x1;
    return collider.resolve(x0, x_end, {0.01, 0.01, 0.01}, {0, 0, hold_corner_2}, {floor}, {floor}, params);
  };
  Eigen::VectorXd within, over;
  const CollisionStats ok = resolved(1, 0, within);
  EXPECT_EQ(ok.candidates, 4);
  EXPECT_FALSE(ok.over_budget);
  EXPECT_EQ(ok.fallbacks, 0);
  EXPECT_NEAR(within(1), 0.0003, 1e-3 * params.thickness);
  const CollisionStats stopped = resolved(0, 1, over);
  EXPECT_EQ(stopped.candidates, 4);
  EXPECT_TRUE(stopped.over_budget);
  EXPECT_EQ(stopped.fallbacks, 1);
  EXPECT_EQ(stopped.impacts, 0);
  EXPECT_EQ(over.head<6>(), x0.head<6>());    // free corners 0 and 1: their start
  EXPECT_EQ(over.tail<3>(), x1.tail<3>());    // corner 2, held: where its handle took it
}

// The state that ran away: a sheet of 20 x 20 cells whose nodes scatter up to a metre in one step
// meets pairs as the square of the sheet (every swept box meets most others). The default bound
// (400 a node or edge) stops the first round, and the sheet keeps its start.
TEST(Collider, ASheetScatteredInOneStepIsStoppedByTheBoundNotTestedPairByPair) {
  const int n = 20;
  std::vector<std::array<int32_t, 3>> faces;
  Eigen::VectorXd x0(3 * (n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) x0.segment<3>(3 * (j * (n + 1) + i)) = Vec3(0.05 * i, 0, 0.05 * j);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      faces.push_back({a, b, c});
      faces.push_back({a, c, d});
    }
  const auto nodes = static_cast<int32_t>(x0.size() / 3);
  Collider collider(faces, {}, nodes);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::VectorXd x1 = x0;
  for (Eigen::Index k = 0; k < x1.size(); ++k) x1(k) += U(rng);
  const Eigen::VectorXd scattered = x1;
  const CollisionStats stats =
      collider.resolve(x0, x1, std::vector<double>(static_cast<std::size_t>(nodes), 0.01), std::vector<char>(static_cast<std::size_t>(nodes), 0), {}, {},
                       CollisionParams{});
  // 441 nodes and 1,240 edges: a bound of 672,400 pairs, where the scattered sheet's swept boxes
  // meet more (each of its 800 faces' boxes spans most of the sheet's).
  EXPECT_TRUE(stats.over_budget);
  EXPECT_GT(stats.candidates, 400LL * (441 + 1240));
  EXPECT_EQ(stats.iterations, 1);
  EXPECT_EQ(x1, x0);
  EXPECT_NE(scattered, x0);
}

}  // namespace
}  // namespace vdc
