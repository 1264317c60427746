// The fidelity measures: wrinkle detail against shapes whose shading normals are known (a flat
// square, a pleated sheet, two flat pieces with a depth step between them), and the shot
// summaries and their verdict against records made by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/fidelity.hpp"
#include "render/rasterizer.hpp"

namespace vdc {
namespace {

// At (0, 0, 5) looking down -z (x right, y up), 40 degrees, 64 x 48 pixels.
Camera small_camera() { return Camera{.position = Vec3(0, 0, 5), .target = Vec3::Zero(), .fov_y_degrees = 40, .width = 64, .height = 48}; }

// Horizontal and vertical neighbour pairs of a 64 x 48 image.
constexpr double kAllPairs = 48 * 63 + 47 * 64;

// A flat quad with its own four vertices: its pixels all get its normal exactly.
void add_quad(RenderMesh& mesh, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto first = static_cast<int32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
  mesh.faces.push_back({first, first + 1, first + 2});
  mesh.faces.push_back({first, first + 2, first + 3});
}

double detail_of(const RenderedFrame& f, const std::vector<char>& cloth) {
  return wrinkle_detail(f, cloth, small_camera().focal_pixels());
}

TEST(WrinkleDetail, AFlatSheetHasNone) {
  RenderMesh square;
  add_quad(square, {-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0});
  const RenderedFrame f = render(small_camera(), {square});
  ASSERT_GT(std::count(f.mesh.begin(), f.mesh.end(), 0), 100);
  EXPECT_EQ(detail_of(f, {1}), 0.0);
  // Tilted, it is still flat; and the background alone has no pairs.
  RenderMesh tilted;
  add_quad(tilted, {-0.5, -0.5, 0.3}, {0.5, -0.5, -0.3}, {0.5, 0.5, -0.3}, {-0.5, 0.5, 0.3});
  EXPECT_NEAR(detail_of(render(small_camera(), {tilted}), {1}), 0.0, 1e-9);
  EXPECT_EQ(detail_of(render(small_camera(), {}), {}), 0.0);
}

// Vertical pleats filling the whole image: flat strips 0.5 m wide, each turned 30 degrees about
// the vertical, alternately towards +x and -x, so that neighbouring strips meet at a ridge at
// 60 degrees (each strip has its own vertices: a sharp crease). Each row of pixels then has one
// pair across each ridge in view, at 60 degrees, and every other pair is at 0: the mean is
// rows x ridges x 60 degrees over all horizontal and vertical pairs.
TEST(WrinkleDetail, APleatedSheetGivesTheRidgeAnglesOverAllPairs) {
  const Camera camera = small_camera();
  const double alpha = M_PI / 6, width = 0.5, depth = width * std::tan(alpha);
  RenderMesh pleats;
  int ridges_in_view = 0;
  for (int k = 0; k < 14; ++k) {
    const double x0 = -3.4 + k * width, x1 = x0 + width;
    const double z0 = k % 2 == 0 ? 0 : -depth, z1 = k % 2 == 0 ? -depth : 0;
    add_quad(pleats, {x0, -3, z0}, {x1, -3, z1}, {x1, 3, z1}, {x0, 3, z0});
    if (k == 0) continue;
    // The ridge at x0 is a vertical line on screen; between the centres of the first and last
    // pixel of a row it makes one pair across it.
    const double ridge = camera.project(Vec3(x0, 0, z0)).x();
    ASSERT_GT(std::abs(ridge - std::floor(ridge) - 0.5), 1e-3) << "ridge " << k << " on a pixel centre";
    ridges_in_view += ridge > 0.5 && ridge < 63.5;
  }
  ASSERT_LT(camera.project(Vec3(-3.4, 0, 0)).x(), 0);
  ASSERT_GT(camera.project(Vec3(-3.4 + 14 * width, 0, 0)).x(), 64);
  ASSERT_GE(ridges_in_view, 8);
  const RenderedFrame f = render(camera, {pleats});
  ASSERT_EQ(std::count(f.mesh.begin(), f.mesh.end(), 0), 64 * 48) << "the pleats fill the image";
  EXPECT_NEAR(detail_of(f, {1}), 48 * ridges_in_view * 60.0 / kAllPairs, 1e-9);
}

// Two flat pieces of one mesh meeting on the same vertical line of the screen, the left facing
// the camera, the right turned 40 degrees, the right one `step` metres further away. Only with a
// step under 4 pixel footprints (7.6 cm a footprint at 5 m here) do the pairs across the line
// count: one a row, at 40 degrees.
RenderedFrame step_scene(double step, bool one_mesh) {
  const Camera camera = small_camera();
  const double beta = 40 * M_PI / 180, edge = 0.1;  // the line, at x = 0.1 on the near piece
  const double far_edge = edge * (5 + step) / 5;   // the same line on screen at the far piece's depth
  RenderMesh near, far;
  add_quad(near, {-4, -10, 0}, {edge, -10, 0}, {edge, 10, 0}, {-4, 10, 0});
  const Vec3 run(std::cos(beta), 0, -std::sin(beta));
  const Vec3 a(far_edge, -10, -step), b(far_edge, 10, -step);
  add_quad(one_mesh ? near : far, a, a + 8 * run, b + 8 * run, b);
  return render(camera, one_mesh ? std::vector<RenderMesh>{near} : std::vector<RenderMesh>{near, far});
}

TEST(WrinkleDetail, PairsAcrossADepthStepOrAnotherMeshDoNotCount) {
  const RenderedFrame joined = step_scene(0.01, true);
  ASSERT_EQ(std::count(joined.mesh.begin(), joined.mesh.end(), 0), 64 * 48);
  EXPECT_NEAR(detail_of(joined, {1}), 48 * 40.0 / kAllPairs, 1e-9);
  EXPECT_NEAR(detail_of(step_scene(1.0, true), {1}), 0.0, 1e-9);  // a step of 13 footprints
  EXPECT_NEAR(detail_of(step_scene(0.01, false), {1, 1}), 0.0, 1e-9);
  EXPECT_EQ(detail_of(joined, {0}), 0.0);  // not cloth
}

// Five frames in two shots; popping is measured from the second frame of each shot on.
std::vector<FrameFidelity> two_shots(bool with_floor) {
  const double none = kNotMeasured;
  std::vector<FrameFidelity> r(5);
  const double overlap[] = {0.95, 0.90, 0.85, 0.99, 0.97}, floor[] = {0.97, 0.96, 0.95, 0.99, 0.98};
  const double detail_run[] = {2, 2, 2, 0, 0}, detail_reference[] = {2.5, 2.5, 2.5, 0, 0};
  const double popping_run[] = {none, 3, 5, none, 2}, popping_reference[] = {none, 4, 4, none, 0};
  const double detail_floor[] = {2.5, 2, 2, 0, 0}, popping_floor[] = {none, 2, 4, none, 1};
  for (int k = 0; k < 5; ++k) {
    FrameFidelity& f = r[static_cast<std::size_t>(k)];
    f.frame = 10 + k;
    f.shot = k < 3 ? 0 : 1;
    f.overlap = overlap[k];
    f.floor_overlap = with_floor ? floor[k] : none;
    f.detail_run = detail_run[k];
    f.detail_reference = detail_reference[k];
    f.popping_run = popping_run[k];
    f.popping_reference = popping_reference[k];
    f.detail_floor = with_floor ? detail_floor[k] : none;
    f.popping_floor = with_floor ? popping_floor[k] : none;
  }
  return r;
}

TEST(FidelitySummary, ShotsAndTheWholeRunAreSummedAndJudged) {
  const std::vector<ShotFidelity> s = summarise_shots(two_shots(true), FidelityTargets{});
  ASSERT_EQ(s.size(), 3u);
  // Shot 0: overlap 0.90 mean / 0.85 min against a floor of 0.96 / 0.95, both beyond their
  // margins; detail 2 / 2.5 = 0.8 < 0.9; popping (3 + 5) / (4 + 4) = 1.
  EXPECT_EQ(s[0].shot, 0);
  EXPECT_EQ(s[0].first_frame, 10);
  EXPECT_EQ(s[0].last_frame, 12);
  EXPECT_EQ(s[0].frames, 3);
  EXPECT_NEAR(s[0].overlap_mean, 0.90, 1e-12);
  EXPECT_EQ(s[0].overlap_min, 0.85);
  EXPECT_NEAR(s[0].floor_overlap_mean, 0.96, 1e-12);
  EXPECT_EQ(s[0].floor_overlap_min, 0.95);
  EXPECT_NEAR(s[0].detail_ratio, 0.8, 1e-12);
  EXPECT_EQ(s[0].popping_pairs, 2);
  EXPECT_EQ(s[0].popping_ratio, 1.0);
  EXPECT_EQ(s[0].failed, (std::vector<std::string>{"overlap mean", "overlap min", "detail"}));
  EXPECT_FALSE(s[0].pass());
  // Shot 1: overlap 0.98 / 0.97 against 0.985 / 0.98, within the margins; no detail in either
  // (0 / 0: alike); popping where the reference has none (2 / 0: infinitely more).
  EXPECT_EQ(s[1].shot, 1);
  EXPECT_EQ(s[1].first_frame, 13);
  EXPECT_EQ(s[1].last_frame, 14);
  EXPECT_NEAR(s[1].overlap_mean, 0.98, 1e-12);
  EXPECT_EQ(s[1].detail_ratio, 1.0);
  EXPECT_EQ(s[1].popping_pairs, 1);
  EXPECT_EQ(s[1].popping_ratio, std::numeric_limits<double>::infinity());
  EXPECT_EQ(s[1].failed, (std::vector<std::string>{"popping"}));
  // The whole run: overlap 4.66 / 5, min 0.85; floor 4.85 / 5, min 0.95; detail 6 / 7.5;
  // popping (3 + 5 + 2) / (4 + 4 + 0).
  EXPECT_EQ(s[2].shot, -1);
  EXPECT_EQ(s[2].first_frame, 10);
  EXPECT_EQ(s[2].last_frame, 14);
  EXPECT_EQ(s[2].frames, 5);
  EXPECT_NEAR(s[2].overlap_mean, 0.932, 1e-12);
  EXPECT_NEAR(s[2].floor_overlap_mean, 0.97, 1e-12);
  EXPECT_NEAR(s[2].detail_ratio, 0.8, 1e-12);
  EXPECT_EQ(s[2].popping_pairs, 3);
  EXPECT_NEAR(s[2].popping_ratio, 1.25, 1e-12);
  EXPECT_EQ(s[2].failed, (std::vector<std::string>{"overlap mean", "overlap min", "detail", "popping"}));
  // The floor run's own ratios, reported beside and not judged: detail (2.5 + 2 + 2) / 7.5 in
  // shot 0 and over the run (shot 1: 0 / 0, alike); popping (2 + 4) / (4 + 4) in shot 0, 1 / 0
  // in shot 1, (2 + 4 + 1) / 8 over the run.
  EXPECT_NEAR(s[0].detail_floor_ratio, 6.5 / 7.5, 1e-12);
  EXPECT_EQ(s[1].detail_floor_ratio, 1.0);
  EXPECT_NEAR(s[2].detail_floor_ratio, 6.5 / 7.5, 1e-12);
  EXPECT_EQ(s[0].popping_floor_ratio, 0.75);
  EXPECT_EQ(s[1].popping_floor_ratio, std::numeric_limits<double>::infinity());
  EXPECT_NEAR(s[2].popping_floor_ratio, 0.875, 1e-12);
}

// Two floor runs, by hand: over shot 0 the first gives 0.97, 0.96, 0.95 (mean 0.96, min 0.95),
// the second 0.99, 0.92, 0.93 (mean 2.84 / 3, min 0.92); the floor is the mean of their means,
// 0.953333, and of their minima, 0.935. The run's 0.90 mean and 0.85 minimum fail against 0.02
// and 0.05 below those, and pass with margins of 0.06 and 0.09. Shot 1 and the whole run
// likewise; one floor run given as a list of one is that run, as before.
TEST(FidelitySummary, SeveralFloorRunsGiveTheMeanOfTheirMeansAndOfTheirMinima) {
  std::vector<FrameFidelity> frames = two_shots(true);
  const std::vector<std::vector<double>> floors{{0.97, 0.99}, {0.96, 0.92}, {0.95, 0.93}, {0.99, 0.97}, {0.98, 0.96}};
  for (std::size_t k = 0; k < frames.size(); ++k) {
    frames[k].floor_overlaps = floors[k];
    frames[k].floor_overlap = 0.5 * (floors[k][0] + floors[k][1]);
  }
  const std::vector<ShotFidelity> s = summarise_shots(frames, FidelityTargets{});
  ASSERT_EQ(s.size(), 3u);
  ASSERT_EQ(s[0].floor_overlap_means.size(), 2u);
  EXPECT_NEAR(s[0].floor_overlap_means[0], 0.96, 1e-12);
  EXPECT_NEAR(s[0].floor_overlap_means[1], 2.84 / 3, 1e-12);
  EXPECT_EQ(s[0].floor_overlap_mins, (std::vector<double>{0.95, 0.92}));
  EXPECT_NEAR(s[0].floor_overlap_mean, 0.5 * (0.96 + 2.84 / 3), 1e-12);
  EXPECT_NEAR(s[0].floor_overlap_min, 0.935, 1e-12);
  EXPECT_EQ(s[0].failed, (std::vector<std::string>{"overlap mean", "overlap min", "detail"}));
  // Shot 1: 0.99, 0.98 and 0.97, 0.96: means 0.985 and 0.965, minima 0.98 and 0.96.
  EXPECT_NEAR(s[1].floor_overlap_mean, 0.975, 1e-12);
  EXPECT_NEAR(s[1].floor_overlap_min, 0.97, 1e-12);
  // The whole run: means 4.85 / 5 and 4.77 / 5, minima 0.95 and 0.92.
  EXPECT_NEAR(s[2].floor_overlap_mean, 0.5 * (0.97 + 0.954), 1e-12);
  EXPECT_NEAR(s[2].floor_overlap_min, 0.935, 1e-12);
  FidelityTargets wide;
  wide.min_margin = 0.09;      // 0.85 >= 0.935 - 0.09
  wide.overlap_margin = 0.06;  // 0.90 >= 0.953333 - 0.06
  wide.detail = 0.75;          // 0.8 >= 0.75
  EXPECT_TRUE(summarise_shots(frames, wide)[0].pass()) << summarise_shots(frames, wide)[0].failed.size();
  // One floor run given as a list of one: as floor_overlap alone.
  std::vector<FrameFidelity> single = two_shots(true);
  for (FrameFidelity& f : single) f.floor_overlaps = {f.floor_overlap};
  const std::vector<ShotFidelity> one = summarise_shots(single, FidelityTargets{});
  const std::vector<ShotFidelity> plain = summarise_shots(two_shots(true), FidelityTargets{});
  for (std::size_t k = 0; k < one.size(); ++k) {
    EXPECT_EQ(one[k].floor_overlap_mean, plain[k].floor_overlap_mean) << k;
    EXPECT_EQ(one[k].floor_overlap_min, plain[k].floor_overlap_min) << k;
    EXPECT_EQ(plain[k].floor_overlap_means.size(), 1u) << k;
  }
}

// Two runs of the same method, by hand: the second has overlaps 0.97, 0.97, 0.96 | 0.99, 0.99
// (shot 0 mean 0.966667, min 0.96), detail 2.5 at every frame of shot 0 and popping 4 and 3.
// Shot 0 judged: overlap (0.90 + 0.966667) / 2 = 0.933333 (fails against 0.96 - 0.02), min
// (0.85 + 0.96) / 2 = 0.905 (passes against 0.95 - 0.05), detail (2 + 2.5) / 2 / 2.5 = 0.9
// (passes), popping ((3 + 5) / 2 + (4 + 3) / 2) / 2 / 4 = 0.9375. The reference's and the floor's
// figures are unchanged; one run alone is returned as it is.
TEST(FidelitySummary, SeveralRunsOfTheMethodAreJudgedByTheirMeans) {
  const std::vector<FrameFidelity> first = two_shots(true);
  std::vector<FrameFidelity> second = first;
  const double overlap[] = {0.97, 0.97, 0.96, 0.99, 0.99}, popping[] = {kNotMeasured, 4, 3, kNotMeasured, 2};
  for (std::size_t k = 0; k < second.size(); ++k) {
    second[k].overlap = overlap[k];
    second[k].popping_run = popping[k];
    if (k < 3) second[k].detail_run = 2.5;
  }
  const FidelityTargets targets;
  const std::vector<ShotFidelity> a = summarise_shots(first, targets), b = summarise_shots(second, targets);
  const std::vector<ShotFidelity> s = summarise_samples({a, b}, targets);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NEAR(s[0].overlap_mean, 0.5 * (0.90 + 2.90 / 3), 1e-12);
  EXPECT_NEAR(s[0].overlap_min, 0.905, 1e-12);
  EXPECT_NEAR(s[0].sample_overlap_means[1], 2.90 / 3, 1e-12);
  EXPECT_EQ(s[0].sample_overlap_mins, (std::vector<double>{0.85, 0.96}));
  EXPECT_NEAR(s[0].detail_ratio, 0.9, 1e-12);
  EXPECT_NEAR(s[0].popping_ratio, 0.9375, 1e-12);
  EXPECT_EQ(s[0].failed, (std::vector<std::string>{"overlap mean"}));
  EXPECT_EQ(s[0].floor_overlap_mean, a[0].floor_overlap_mean);
  EXPECT_EQ(s[0].detail_reference_mean, a[0].detail_reference_mean);
  // Shot 1: overlap (0.98 + 0.99) / 2, popping (2 + 2) / 2 over 0: still where the reference has none.
  EXPECT_NEAR(s[1].overlap_mean, 0.985, 1e-12);
  EXPECT_EQ(s[1].popping_ratio, std::numeric_limits<double>::infinity());
  EXPECT_EQ(s[1].failed, (std::vector<std::string>{"popping"}));
  const std::vector<ShotFidelity> one = summarise_samples({a}, targets);
  ASSERT_EQ(one.size(), a.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(one[k].overlap_mean, a[k].overlap_mean);
    EXPECT_EQ(one[k].failed, a[k].failed);
    EXPECT_TRUE(one[k].sample_overlap_means.empty());
  }
  EXPECT_THROW(summarise_samples({a, {b[0]}}, targets), std::invalid_argument);
}

TEST(FidelitySummary, TargetsMoveTheVerdict) {
  FidelityTargets lenient;
  lenient.overlap_margin = 0.0625;  // 0.90 >= 0.96 - 0.0625
  lenient.min_margin = 0.125;       // 0.85 >= 0.95 - 0.125
  lenient.detail = 0.75;            // 0.8 >= 0.75
  const std::vector<ShotFidelity> s = summarise_shots(two_shots(true), lenient);
  EXPECT_TRUE(s[0].pass()) << s[0].failed.size();
  EXPECT_EQ(s[1].failed, (std::vector<std::string>{"popping"}));  // infinite whatever the target
  EXPECT_EQ(s[2].failed, (std::vector<std::string>{"popping"}));  // 1.25 > 1.2
  lenient.popping = 1.3;
  EXPECT_TRUE(summarise_shots(two_shots(true), lenient)[2].pass());
}

TEST(FidelitySummary, WithoutAFloorTheOverlapIsReportedButNotJudged) {
  const std::vector<ShotFidelity> s = summarise_shots(two_shots(false), FidelityTargets{});
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NEAR(s[0].overlap_mean, 0.90, 1e-12);
  EXPECT_TRUE(std::isnan(s[0].floor_overlap_mean));
  EXPECT_TRUE(std::isnan(s[0].floor_overlap_min));
  EXPECT_TRUE(std::isnan(s[0].detail_floor_ratio));
  EXPECT_TRUE(std::isnan(s[2].popping_floor_ratio));
  EXPECT_EQ(s[0].failed, (std::vector<std::string>{"detail"}));
}

TEST(FidelitySummary, PoppingWithoutPairsIsNotJudgedAndStillnessIsAlike) {
  std::vector<FrameFidelity> one(1);
  one[0].detail_run = one[0].detail_reference = 3;
  std::vector<ShotFidelity> s = summarise_shots(one, FidelityTargets{});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].popping_pairs, 0);
  EXPECT_TRUE(std::isnan(s[0].popping_ratio));
  EXPECT_TRUE(s[0].pass());
  // Two frames where nothing moves in either run: 0 / 0.
  std::vector<FrameFidelity> still(2);
  still[1].frame = 1;
  still[1].popping_run = still[1].popping_reference = 0;
  s = summarise_shots(still, FidelityTargets{});
  EXPECT_EQ(s[0].popping_ratio, 1.0);
  EXPECT_EQ(s[0].detail_ratio, 1.0);
  EXPECT_TRUE(s[0].pass());
  EXPECT_TRUE(summarise_shots({}, FidelityTargets{}).empty());
}

// Garment x: 90 of 100 pixels alike at one frame, 150 of 300 at the next: 240 / 400 = 0.6 over
// the run (the frames' mean, 0.7, would let the smaller frame count as much); its floor 100 of
// 100 and 160 of 200: 260 / 300, so of its 400 pixels it loses 160 where the floor's rate loses
// 53.3. Garment z: 0.95 of 20 pixels, no floor. Garment y never shows.
TEST(FidelitySummary, GarmentsArePooledOverTheirPixelsLowestFirst) {
  auto frame = [](int k, const char* garment, int either, double overlap, int floor_either, double floor_overlap) {
    GarmentFrame g;
    g.frame = k;
    g.garment = garment;
    g.pixels_either = either;
    g.overlap = overlap;
    g.floor_pixels_either = floor_either;
    g.floor_overlap = floor_overlap;
    return g;
  };
  const double none = kNotMeasured;
  const std::vector<GarmentFidelity> g = summarise_garments({frame(0, "z", 20, 0.95, 0, none), frame(0, "x", 100, 0.9, 100, 1.0),
                                                             frame(0, "y", 0, 1.0, 0, 1.0), frame(1, "x", 300, 0.5, 200, 0.8),
                                                             frame(1, "y", 0, 1.0, 0, 1.0)});
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g[0].garment, "x");
  EXPECT_EQ(g[0].frames, 2);
  EXPECT_NEAR(g[0].overlap, 0.6, 1e-15);
  EXPECT_NEAR(g[0].floor_overlap, 260.0 / 300.0, 1e-15);
  // x shows in 400 pixels and loses 160 of them, where the floor's rate would lose 400 x 40/300.
  EXPECT_EQ(g[0].pixels, 400);
  EXPECT_NEAR(g[0].departure(), 160.0 - 400.0 * 40.0 / 300.0, 1e-12);
  EXPECT_EQ(g[1].garment, "z");
  EXPECT_EQ(g[1].frames, 1);
  EXPECT_NEAR(g[1].overlap, 0.95, 1e-15);
  EXPECT_TRUE(std::isnan(g[1].floor_overlap));
  EXPECT_EQ(g[1].pixels, 20);
  EXPECT_TRUE(std::isnan(g[1].departure()));
  EXPECT_TRUE(summarise_garments({}).empty());
}

TEST(FidelitySummary, RatioOfMeans) {
  EXPECT_EQ(ratio_of_means(3, 4), 0.75);
  EXPECT_EQ(ratio_of_means(0, 0), 1.0);
  EXPECT_EQ(ratio_of_means(2, 0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(ratio_of_means(0, 2), 0.0);
}

}  // namespace
}  // namespace vdc
