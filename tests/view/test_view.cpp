// View-dependent sizing, one test per equation of Koh et al. 2014's section 3 on hand-built
// configurations with analytic answers.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/mesh_build.hpp"
#include "view/view_sizing.hpp"
#include "support/front_camera.hpp"

namespace vdc {
namespace {

using test::front_camera;

// A small triangle centred at p, counter-clockwise seen from +z (its outer side faces +z), or
// from -z when `flipped`.
std::array<Vec3, 3> tri(const Vec3& p, bool flipped = false, double r = 0.01) {
  std::array<Vec3, 3> t{p + Vec3(-r, -r, 0), p + Vec3(r, -r, 0), p + Vec3(0, r, 0)};
  if (flipped) std::swap(t[1], t[2]);
  return t;
}

FaceView view_of(const Camera& c, const std::array<Vec3, 3>& t, const ViewParams& p) { return face_view(Frustum(c), t[0], t[1], t[2], p); }

// front_camera() 5 m above a sheet in the x-z plane (outer side +y), looking straight down.
CameraPath from_above() {
  Camera lens = front_camera();
  lens.up = Vec3(0, 0, -1);
  return CameraPath(lens, {{0.0, Vec3(0.1, 5, -0.1), Vec3(0.1, 0, -0.1), false}});
}

// The shortest and the longest edge a sizing tensor asks for.
double finest_edge(const Mat2& t) { return 1 / std::sqrt(Eigen::SelfAdjointEigenSolver<Mat2>(t).eigenvalues()[1]); }
double coarsest_edge(const Mat2& t) { return 1 / std::sqrt(Eigen::SelfAdjointEigenSolver<Mat2>(t).eigenvalues()[0]); }

TEST(ViewFactor, FaceInFrameFacingTheCameraGetsOne) {
  ViewParams p;
  FaceView v = view_of(front_camera(), tri(Vec3(0.2, -0.3, 0)), p);
  EXPECT_EQ(v.distance, 0);
  EXPECT_TRUE(v.front);
  EXPECT_EQ(v.factor, 1.0);
}

TEST(ViewFactor, FaceBehindTheCameraBeyondTheMarginGetsVOut) {
  ViewParams p;
  FaceView v = view_of(front_camera(), tri(Vec3(0, 0, 6)), p);  // 1 m behind the camera
  EXPECT_GE(v.distance, p.margin);
  EXPECT_EQ(v.factor, p.v_out);
}

TEST(ViewFactor, BackFacingFaceInFrameGetsVBack) {
  ViewParams p;
  FaceView v = view_of(front_camera(), tri(Vec3(0, 0, 0), true), p);
  EXPECT_EQ(v.distance, 0);
  EXPECT_FALSE(v.front);
  EXPECT_EQ(v.factor, p.v_back);
}

TEST(ViewFactor, HalfTheMarginBeyondTheFarPlaneIsHalfway) {
  ViewParams p;  // margin 0.4 m
  // The far plane is at z = -5; a face 0.2 m beyond it, on the axis, facing the camera.
  FaceView v = view_of(front_camera(), tri(Vec3(0, 0, -5.2)), p);
  EXPECT_NEAR(v.distance, 0.2, 1e-12);
  EXPECT_NEAR(v.factor, 1 - 0.5 * (1 - p.v_out), 1e-12);
  // Beside the frustum: 0.1 m right of the right side plane at depth 3 (x = 3 tan(fov_x / 2)).
  const double tx = std::tan(20 * M_PI / 180) * 1280 / 720;
  const Vec3 side_normal = Vec3(1, 0, tx).normalized();  // outward normal of the right plane
  const Vec3 on_plane(3 * tx, 0, 2);
  FaceView w = face_view(Frustum(front_camera()), on_plane + 0.1 * side_normal + Vec3(0, -0.001, 0),
                         on_plane + 0.1 * side_normal + Vec3(0, 0.001, 0) + 0.001 * Vec3(-tx, 0, 1).normalized(),
                         on_plane + 0.1 * side_normal + Vec3(0, 0.001, 0), p);
  EXPECT_NEAR(w.distance, 0.1, 1e-3);
}

TEST(ViewFactor, AnticipationRampsUpLinearlyBeforeACut) {
  ViewParams p;  // T = 5 frames
  const double frame = 0.04, window = p.anticipation * frame, t0 = 2.0;
  Camera lens = front_camera();
  // First shot looks away from the origin (+z); the cut at t0 looks at it.
  std::vector<CameraKey> keys{{0.0, Vec3(0, 0, 5), Vec3(0, 0, 10), false}, {t0, Vec3(0, 0, 5), Vec3(0, 0, 0), true},
                              {t0 + 1, Vec3(0, 0, 5), Vec3(0, 0, 0), false}};
  CameraPath path(lens, keys);
  const auto t = tri(Vec3::Zero());
  for (double before : {0.0, 0.01, 0.05, 0.1, 0.15, 0.19, 0.2, 0.3, 1.0}) {
    const double now = t0 - before;
    const double expected = before == 0 ? 1.0 : std::max(p.v_out, 1 - before / window);
    EXPECT_NEAR(anticipated_view_factor(AnticipationWindow(path, now, frame, p), t[0], t[1], t[2], p), expected, 1e-12)
        << before << " s before the cut";
  }
}

// With a lead of 10 frames (0.4 s), a face seen after the cut is at 1 from 0.4 s before it, and
// the ramp of 5 frames comes before that: 1 - (before - 0.4) / 0.2, down to v_out.
TEST(ViewFactor, ALeadHoldsFullResolutionBeforeTheCutAndRampsBeforeThat) {
  ViewParams p;
  p.lead = 10;
  const double frame = 0.04, lead = p.lead * frame, ramp = p.anticipation * frame, t0 = 2.0;
  std::vector<CameraKey> keys{{0.0, Vec3(0, 0, 5), Vec3(0, 0, 10), false}, {t0, Vec3(0, 0, 5), Vec3(0, 0, 0), true},
                              {t0 + 1, Vec3(0, 0, 5), Vec3(0, 0, 0), false}};
  CameraPath path(front_camera(), keys);
  const auto t = tri(Vec3::Zero());
  for (double before : {0.0, 0.05, 0.2, 0.39, 0.4, 0.45, 0.5, 0.55, 0.6, 0.7, 1.0}) {
    const double expected = before <= lead ? 1.0 : std::max(p.v_out, 1 - (before - lead) / ramp);
    EXPECT_NEAR(anticipated_view_factor(AnticipationWindow(path, t0 - before, frame, p), t[0], t[1], t[2], p), expected, 1e-12)
        << before << " s before the cut";
  }
}

TEST(ViewFactor, SilhouetteResamplingRaisesOnlyTheLessVisibleSide) {
  // Three faces in a row: 0 | 1 | 2 sharing edges 0-1 and 1-2.
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));  // two faces
  ASSERT_EQ(m.num_faces(), 2);
  std::vector<double> v{1.0, 0.01};
  resample_silhouettes(m, v, 0.5);
  EXPECT_EQ(v[0], 1.0);
  EXPECT_NEAR(v[1], 0.505, 1e-15);
  std::vector<double> w{0.2, 0.9};
  resample_silhouettes(m, w, 0.5);
  EXPECT_NEAR(w[0], 0.55, 1e-15);
  EXPECT_EQ(w[1], 0.9);
  std::vector<double> small{0.6, 0.9};  // within the threshold: unchanged
  resample_silhouettes(m, small, 0.5);
  EXPECT_EQ(small, (std::vector<double>{0.6, 0.9}));
}

// A sheet seen from behind, in frame: eq. 2 scales the shape tensor by v_back^2 but keeps what the
// motion asks for (axis by axis, both tensors sharing the material axes here); before `settle`
// every factor is 1 and the tensors pass unchanged.
TEST(ViewSizing, EqTwoCoarsensTheShapeButNotTheMotionAndWaitsForTheDrape) {
  Mesh m = build_mesh(make_grid(0.2, 0.2, 1, 1));  // in the x-z plane, outer side +y
  Camera lens = front_camera();
  lens.up = Vec3(0, 0, 1);
  const CameraPath path(lens, {{0.0, Vec3(0.1, -5, -0.1), Vec3(0.1, 0, -0.1), false}});  // from below
  ViewParams p;
  p.settle = 0.4;
  const Mat2 shape = Vec2(1 / (0.01 * 0.01), 1 / (0.01 * 0.01)).asDiagonal();  // 1 cm edges
  const Mat2 motion_x = Vec2(1 / (0.02 * 0.02), 1 / (0.2 * 0.2)).asDiagonal();  // 2 cm along x
  const std::vector<Mat2> motion(static_cast<std::size_t>(m.face_capacity()), motion_x);
  for (double t : {0.2, 1.0}) {
    ViewSizing view(path, p, t, 0.04);
    view.evaluate(m);
    auto& sizing = m.face_attrs().get_or_add<Mat2>("test_sizing", Mat2::Zero());
    for (FaceId f : m.faces()) sizing[f] = shape;
    view.modify(m, motion, sizing);
    EXPECT_EQ(view.counts().back_facing, 2) << "t = " << t;
    for (FaceId f : m.faces()) EXPECT_EQ(view.reasons()[static_cast<std::size_t>(f.idx)], ViewReason::back_facing);
    for (FaceId f : m.faces()) {
      if (t < p.settle) {
        EXPECT_EQ(view.factors()[static_cast<std::size_t>(f.idx)], 1.0);
        EXPECT_EQ(sizing[f], shape);
        continue;
      }
      EXPECT_EQ(view.factors()[static_cast<std::size_t>(f.idx)], p.v_back);
      // Along x the motion's 2 cm wins over 1 cm / v_back = 5 cm; along y the shape's 5 cm.
      EXPECT_NEAR(sizing[f](0, 0), 1 / (0.02 * 0.02), 1e-9);
      EXPECT_NEAR(sizing[f](1, 1), p.v_back * p.v_back / (0.01 * 0.01), 1e-9);
      EXPECT_NEAR(sizing[f](0, 1), 0.0, 1e-9);
    }
  }
}

// With `linger` 5, a face that turned away falls from the factor it had last frame (the mesh's
// view_factor attribute) by at most 1/5 a frame: from 1 to 0.8, from 0.5 to 0.3, from 0.3 to
// v_back 0.2 (not 0.1); without a factor from last frame, with linger 0, or while settling, the
// factor is eq. 4's alone.
TEST(ViewSizing, LingerLetsAFactorFallByOneOverLingerAFrame) {
  Mesh m = build_mesh(make_grid(0.2, 0.2, 1, 1));  // in the x-z plane, outer side +y
  Camera lens = front_camera();
  lens.up = Vec3(0, 0, 1);
  const CameraPath path(lens, {{0.0, Vec3(0.1, -5, -0.1), Vec3(0.1, 0, -0.1), false}});  // from below: turned away
  ViewParams p;
  p.linger = 5;
  p.settle = 0.4;
  auto factor_of = [&](const ViewParams& params, double t) {
    ViewSizing view(path, params, t, 0.04);
    view.evaluate(m);
    const double v = view.factors()[static_cast<std::size_t>((*m.faces().begin()).idx)];
    for (FaceId f : m.faces()) EXPECT_EQ(view.factors()[static_cast<std::size_t>(f.idx)], v);
    return v;
  };
  EXPECT_EQ(factor_of(p, 1.0), p.v_back);  // no factor from last frame
  auto& before = m.face_attrs().get_or_add<double>(kViewFactorAttr, 1.0);
  for (const auto& [had, now] : std::vector<std::pair<double, double>>{{1.0, 0.8}, {0.5, 0.3}, {0.3, 0.2}, {0.01, 0.2}}) {
    for (FaceId f : m.faces()) before[f] = had;
    EXPECT_NEAR(factor_of(p, 1.0), now, 1e-15) << "from " << had;
  }
  for (FaceId f : m.faces()) before[f] = 1.0;
  EXPECT_EQ(factor_of(p, 0.2), 1.0);  // settling: every factor 1
  ViewParams at_once = p;
  at_once.linger = 0;
  EXPECT_EQ(factor_of(at_once, 1.0), p.v_back);
}

// Before `settle` the view changes no sizing at all: a sheet in plain view 5 m below the camera
// keeps 1 mm and 1 m edges that the screen-space bounds hold to 4 and 10 px (4 * 5 / f and
// 10 * 5 / f metres, f = 360 / tan(20 deg)) after it, and no face counts as standing for folds
// (2 cm folds span 0.02 f / 5 = 3.96 px there, under the 4 px floor: weighted after settle).
TEST(ViewSizing, BeforeSettleNeitherFactorsNorScreenSpaceBoundsChangeTheSizing) {
  Mesh m = build_mesh(make_grid(0.2, 0.2, 1, 1));  // in the x-z plane, outer side +y
  const CameraPath path = from_above();
  ViewParams p;
  p.settle = 0.4;
  p.l_min = 4;
  p.l_max = 10;
  const double f = 360 / std::tan(20 * M_PI / 180);
  const std::vector<Mat2> no_motion(static_cast<std::size_t>(m.face_capacity()), Mat2::Zero());
  const Mat2 fine = Mat2::Identity() / (0.001 * 0.001), coarse = Mat2::Identity();
  for (double t : {0.2, 0.4}) {
    const bool settling = t < p.settle;
    ViewSizing view(path, p, t, 0.04);
    view.evaluate(m);
    EXPECT_EQ(view.counts().visible, 2) << "t = " << t;
    auto& sizing = m.face_attrs().get_or_add<Mat2>("test_sizing", Mat2::Zero());
    for (FaceId face : m.faces()) sizing[face] = fine;
    view.modify(m, no_motion, sizing);
    for (FaceId face : m.faces()) {
      EXPECT_EQ(view.factors()[static_cast<std::size_t>(face.idx)], 1.0);
      if (settling) {
        EXPECT_EQ(sizing[face], fine);
        EXPECT_EQ(view.fold_coarsening(m, face, sizing[face]), 0.0);
      } else {
        EXPECT_NEAR(finest_edge(sizing[face]), 4 * 5 / f, 1e-6);
        EXPECT_GT(view.fold_coarsening(m, face, sizing[face]), 1.0);
      }
    }
    for (FaceId face : m.faces()) sizing[face] = coarse;
    view.modify(m, no_motion, sizing);
    for (FaceId face : m.faces()) {
      if (settling)
        EXPECT_EQ(sizing[face], coarse);
      else
        EXPECT_NEAR(coarsest_edge(sizing[face]), 10 * 5 / f, 1e-6);
    }
  }
}

// With occlusion, a hidden face is no finer than a seen one beside it: the screen-space floor
// l_min bounds it too (4 px at 5 m: 4 * 5 / f metres, f = 360 / tan(20 deg)), but l_max does not
// refine it (1 m edges stay 1 m where a seen face is held to 10 px, 10 * 5 / f).
TEST(ViewSizing, HiddenFacesKeepTheScreenSpaceFloorButNotTheCeiling) {
  Mesh m = build_mesh(make_grid(0.2, 0.2, 1, 1));  // in the x-z plane, outer side +y
  const CameraPath path = from_above();
  ViewParams p;
  p.occlusion = true;
  p.v_occluded = 1;  // the floor alone
  p.l_min = 4;
  p.l_max = 10;
  const AnticipationWindow window(path, 0.0, 0.04, p);
  // A square at y = 1 between the camera and the sheet, facing up.
  const Vec3 a(-1, 1, 1), b(1, 1, 1), c(1, 1, -1), d(-1, 1, -1);
  const std::vector<std::vector<DepthImage>> hiding{occlusion_images(window, [&](DepthImage& image, double) { image.draw({{a, b, c}, {a, c, d}}); }, p)};
  const std::vector<std::vector<DepthImage>> open{occlusion_images(window, [&](DepthImage&, double) {}, p)};
  const double f = 360 / std::tan(20 * M_PI / 180);
  const std::vector<Mat2> no_motion(static_cast<std::size_t>(m.face_capacity()), Mat2::Zero());
  for (const bool hidden : {true, false}) {
    ViewSizing view(path, p, 0.0, 0.04);
    view.evaluate(m, hidden ? &hiding : &open);
    EXPECT_EQ(view.counts().hidden, hidden ? 2 : 0);
    auto& sizing = m.face_attrs().get_or_add<Mat2>("test_sizing", Mat2::Zero());
    for (FaceId face : m.faces()) sizing[face] = Mat2::Identity() / (0.001 * 0.001);  // 1 mm edges
    view.modify(m, no_motion, sizing);
    for (FaceId face : m.faces()) {
      EXPECT_EQ(view.reasons()[static_cast<std::size_t>(face.idx)], hidden ? ViewReason::hidden : ViewReason::seen);
      EXPECT_NEAR(finest_edge(sizing[face]), 4 * 5 / f, 1e-6);
    }
    for (FaceId face : m.faces()) sizing[face] = Mat2::Identity();  // 1 m edges
    view.modify(m, no_motion, sizing);
    for (FaceId face : m.faces()) EXPECT_NEAR(coarsest_edge(sizing[face]), hidden ? 1.0 : 10 * 5 / f, 1e-6);
  }
}

// floor_in_frame: a face turned away in frame is no finer than l_min on screen either, whatever
// its motion asks (1 mm edges for the velocity criterion become 4 * 5 / f); without it only v_back
// coarsens it, and the motion keeps its 1 mm; nor is it floored when a cut within the window will
// show it, but it is when the camera swings round to it without a cut.
TEST(ViewSizing, FloorInFrameBoundsTheFacesTurnedAwayToo) {
  Mesh m = build_mesh(make_grid(0.2, 0.2, 1, 1));  // in the x-z plane, outer side +y
  Camera lens = front_camera();
  lens.up = Vec3(0, 0, 1);
  const double f = 360 / std::tan(20 * M_PI / 180);
  const std::vector<Mat2> fast(static_cast<std::size_t>(m.face_capacity()), Mat2::Identity() / (0.001 * 0.001));
  // Each face's view factor and the finest edge its tensor allows after modify(), 1 mm asked.
  auto sized = [&](const CameraPath& path, bool floor_in_frame) {
    ViewParams p;
    p.floor_in_frame = floor_in_frame;
    ViewSizing view(path, p, 0.0, 0.04);
    view.evaluate(m);
    auto& sizing = m.face_attrs().get_or_add<Mat2>("test_sizing", Mat2::Zero());
    for (FaceId face : m.faces()) sizing[face] = Mat2::Identity() / (0.001 * 0.001);
    view.modify(m, fast, sizing);
    std::vector<std::pair<double, double>> out;
    for (FaceId face : m.faces()) {
      EXPECT_EQ(view.reasons()[static_cast<std::size_t>(face.idx)], ViewReason::back_facing);
      out.emplace_back(view.factors()[static_cast<std::size_t>(face.idx)],
                       1 / std::sqrt(Eigen::SelfAdjointEigenSolver<Mat2>(sizing[face]).eigenvalues()[1]));
    }
    return out;
  };
  const CameraPath below(lens, {{0.0, Vec3(0.1, -5, -0.1), Vec3(0.1, 0, -0.1), false}});  // turned away
  for (const bool floored : {false, true})
    for (const auto& [factor, finest] : sized(below, floored)) {
      EXPECT_EQ(factor, ViewParams{}.v_back);
      EXPECT_NEAR(finest, floored ? 4 * 5 / f : 0.001, 1e-6);
    }
  // A cut to the other side within the window (0.1 s of 0.2): eq. 4 raises the factor to
  // w(0.1 s) = 1 - 0.1 / 0.2, and the face keeps what its motion asks, ready to be seen.
  const CameraPath cut(lens, {{0.0, Vec3(0.1, -5, -0.1), Vec3(0.1, 0, -0.1), false}, {0.1, Vec3(0.1, 5, -0.1), Vec3(0.1, 0, -0.1), true}});
  for (const auto& [factor, finest] : sized(cut, true)) {
    EXPECT_NEAR(factor, 0.5, 1e-12);
    EXPECT_NEAR(finest, 0.001, 1e-9);
  }
  // The camera swinging round to the other side without a cut: eq. 4 raises the factor too,
  // but the camera's scale changes little within the window, and the floor holds.
  const CameraPath swing(lens, {{0.0, Vec3(0.1, -5, -0.1), Vec3(0.1, 0, -0.1), false},
                                {0.05, Vec3(5.1, 0, -0.1), Vec3(0.1, 0, -0.1), false},
                                {0.1, Vec3(0.1, 5, -0.1), Vec3(0.1, 0, -0.1), false}});
  for (const auto& [factor, finest] : sized(swing, true)) {
    EXPECT_GT(factor, ViewParams{}.v_back);
    EXPECT_NEAR(finest, 4 * 5 / f, 1e-6);
  }
}

// A metre at depth 5 on the axis spans f / 5 pixels; a metre off the axis at (1, 0, 0), depth
// 5, spans f sqrt(0.2^2 + 0.04^2) along x (the forward term of the Jacobian, -x f / z^2) and
// f / 5 along y: the larger.
TEST(Camera, PixelsPerMetreIsTheJacobiansLargestStretch) {
  const Camera c = front_camera();
  const double f = 360 / std::tan(20 * M_PI / 180);
  EXPECT_NEAR(c.pixels_per_metre(Vec3::Zero()), f / 5, 1e-9);
  EXPECT_NEAR(c.pixels_per_metre(Vec3(1, 0, 0)), f * std::sqrt(0.04 + 0.0016), 1e-9);
}

TEST(FoldWeight, FullUpToHalfTheFloorThenFallingToNothingAtTheFloor) {
  EXPECT_EQ(fold_weight(1, 4), 1.0);
  EXPECT_EQ(fold_weight(2, 4), 1.0);
  EXPECT_NEAR(fold_weight(3, 4), 0.5, 1e-15);
  EXPECT_EQ(fold_weight(4, 4), 0.0);
  EXPECT_EQ(fold_weight(9, 4), 0.0);
  EXPECT_EQ(fold_weight(1, 0), 0.0);
}

// 2 cm folds on a sheet 20 m away span about a pixel, under half of l_min's 4: a face allowed
// 10 cm edges is (10 / 2)^2 = 25 times coarser than its folds, seen or turned away. 2 m away
// they span about 10 pixels and nothing is said (0); at the distance where they span 3 pixels
// the weight is a half, 1 + 0.5 * 24; out of frame, or with fold_length 0, nothing either.
TEST(ViewSizing, FoldsFinerThanTheScreenFloorCountAsCoarsening) {
  Mesh m = build_mesh(make_grid(0.2, 0.2, 1, 1));  // in the x-z plane, outer side +y
  Camera lens = front_camera();
  lens.far = 100;
  const Mat2 ten_cm = Mat2::Identity() / (0.1 * 0.1);
  const double f = 360 / std::tan(20 * M_PI / 180);
  auto folds = [&](const Vec3& eye, const Vec3& target, const Vec3& up, double fold_length, ViewReason reason) {
    lens.up = up;
    const CameraPath path(lens, {{0.0, eye, target, false}});
    ViewParams p;
    p.fold_length = fold_length;
    ViewSizing view(path, p, 0.0, 0.04);
    view.evaluate(m);
    std::vector<double> out;
    for (FaceId face : m.faces()) {
      EXPECT_EQ(view.reasons()[static_cast<std::size_t>(face.idx)], reason);
      out.push_back(view.fold_coarsening(m, face, ten_cm));
    }
    return out;
  };
  const Vec3 centre(0.1, 0, -0.1), above(0, 0, -1), below(0, 0, 1);
  for (double c : folds(centre + Vec3(0, 20, 0), centre, above, 0.02, ViewReason::seen)) EXPECT_NEAR(c, 25, 1e-9);
  for (double c : folds(centre - Vec3(0, 20, 0), centre, below, 0.02, ViewReason::back_facing)) EXPECT_NEAR(c, 25, 1e-9);
  for (double c : folds(centre + Vec3(0, 2, 0), centre, above, 0.02, ViewReason::seen)) EXPECT_EQ(c, 0.0);
  for (double c : folds(centre + Vec3(0, 20, 0), centre + Vec3(0, 40, 0), above, 0.02, ViewReason::out_of_frame)) EXPECT_EQ(c, 0.0);
  for (double c : folds(centre + Vec3(0, 20, 0), centre, above, 0.0, ViewReason::seen)) EXPECT_EQ(c, 0.0);
  // 3 pixels: 0.02 f / d = 3. The face centres lie 3.3 cm off the axis, which lengthens a
  // metre on screen by a factor 1 + O(1e-5) at that distance: the weight within 1e-3 of a half.
  for (double c : folds(centre + Vec3(0, 0.02 * f / 3, 0), centre, above, 0.02, ViewReason::seen)) EXPECT_NEAR(c, 1 + 0.5 * 24, 0.03);
}

// Screen length, in pixels, of the shortest edge the tensor allows along material direction d.
double screen_edge(const Mat2& m, const Mat23& j, const Mat32& f, const Vec2& d) {
  const Vec2 u = d.normalized() / std::sqrt(d.normalized().dot(m * d.normalized()));
  return (j * f * u).norm();
}

TEST(ScreenSpaceFloor, NoEdgeFinerThanLMinPixels) {
  Camera c = front_camera();
  c.position = Vec3::Zero();
  c.target = Vec3(0, 0, -1);
  const double l_min = 4, depth = 10, fp = 360 / std::tan(20 * M_PI / 180);
  const Vec3 centre(0.5, -0.2, -depth);
  const Mat23 j = c.projection_jacobian(centre);
  // Material u along world x, v along world y, then tilted 60 degrees about x (foreshortened).
  for (double tilt : {0.0, 60.0}) {
    const double a = tilt * M_PI / 180;
    Mat32 f;
    f << 1, 0, 0, std::cos(a), 0, std::sin(a);
    const Mat2 fine = Mat2::Identity() / (0.001 * 0.001);  // 1 mm edges
    const Mat2 floored = screen_space_bounds(fine, j, f, l_min, 0);
    for (double angle = 0; angle < M_PI; angle += M_PI / 12) {
      const Vec2 d(std::cos(angle), std::sin(angle));
      EXPECT_GE(screen_edge(floored, j, f, d), l_min * (1 - 1e-9)) << "tilt " << tilt << " direction " << angle;
    }
    // Facing the camera, the bound is exact: l_min pixels at depth z are l_min z / fp metres.
    if (tilt == 0) {
      Eigen::SelfAdjointEigenSolver<Mat2> eig(floored);
      EXPECT_NEAR(1 / std::sqrt(eig.eigenvalues()[1]), l_min * depth / fp, 1e-3 * l_min * depth / fp);
    }
    // A tensor already coarser than l_min on screen is left as it is.
    const Mat2 coarse = Mat2::Identity() / (0.5 * 0.5);
    EXPECT_LT((screen_space_bounds(coarse, j, f, l_min, 0) - coarse).norm(), 1e-9 * coarse.norm());
  }
}

TEST(ScreenSpaceBounds, NoVisibleEdgeLongerThanLMaxPixels) {
  Camera c = front_camera();
  c.position = Vec3::Zero();
  c.target = Vec3(0, 0, -1);
  const double l_min = 4, l_max = 20, depth = 2, fp = 360 / std::tan(20 * M_PI / 180);
  const Vec3 centre(0.3, 0.1, -depth);
  const Mat23 j = c.projection_jacobian(centre);
  for (double tilt : {0.0, 60.0}) {
    const double a = tilt * M_PI / 180;
    Mat32 f;
    f << 1, 0, 0, std::cos(a), 0, std::sin(a);
    const Mat2 coarse = Mat2::Identity() / (0.5 * 0.5);  // 50 cm edges: hundreds of pixels
    const Mat2 bounded = screen_space_bounds(coarse, j, f, l_min, l_max);
    for (double angle = 0; angle < M_PI; angle += M_PI / 12) {
      const Vec2 d(std::cos(angle), std::sin(angle));
      EXPECT_LE(screen_edge(bounded, j, f, d), l_max * (1 + 1e-9)) << "tilt " << tilt << " direction " << angle;
      EXPECT_GE(screen_edge(bounded, j, f, d), l_min * (1 - 1e-9)) << "tilt " << tilt << " direction " << angle;
    }
    // Facing the camera, the bound is exact: l_max pixels at depth z are l_max z / fp metres.
    if (tilt == 0) {
      Eigen::SelfAdjointEigenSolver<Mat2> eig(bounded);
      EXPECT_NEAR(1 / std::sqrt(eig.eigenvalues()[0]), l_max * depth / fp, 1e-3 * l_max * depth / fp);
    }
    // A tensor between the bounds on screen is left as it is (2 cm is about 10 pixels here,
    // 5 across the tilt).
    const Mat2 between = Mat2::Identity() / (0.02 * 0.02);
    EXPECT_LT((screen_space_bounds(between, j, f, l_min, l_max) - between).norm(), 1e-9 * between.norm());
  }
}

// A thin lens of 40 degrees on a 24 mm sensor: f = 12 mm / tan 20 deg = 32.970 mm; at f/2 focused
// at 2 m, a point at 4 m blurs into A |4 - 2| / 4 * f / (2 m - f) = 0.13815 mm on the sensor,
// 6.2169 of 1080 pixels; at 1 m twice that; in focus, nothing.
TEST(Camera, BlurCircleIsTheThinLensCircleOfConfusion) {
  Camera c = front_camera();
  c.height = 1080;
  c.width = 1920;
  EXPECT_NEAR(c.focal_length_mm(), 32.969729, 1e-6);
  EXPECT_EQ(c.blur_circle_pixels(4), 0.0) << "a pinhole";
  c.focus_distance = 2;
  c.f_stop = 2;
  EXPECT_NEAR(c.blur_circle_pixels(4), 6.2168764, 1e-6);
  EXPECT_NEAR(c.blur_circle_pixels(1), 12.4337528, 1e-6);
  EXPECT_EQ(c.blur_circle_pixels(2), 0.0);
  c.f_stop = 4;  // half the aperture, half the circle
  EXPECT_NEAR(c.blur_circle_pixels(4), 6.2168764 / 2, 1e-6);
}

// The screen-space floor of a visible face: l_min, the blur circle's diameter when the camera
// has depth of field, the streak of the face's image while the shutter is open when it has
// motion blur (here 1 m/s across the view at 4 m for half a 0.04 s frame: fp 0.02 / 4 = 7.4182
// pixels, fp = 540 / tan 20 deg); each off at scale 0; no streak across a cut. The sizing a
// visible face gets is bounded at that floor: at depth z, floor z / fp metres.
TEST(ViewSizing, DepthOfFieldAndMotionBlurRaiseTheScreenFloor) {
  Camera lens = front_camera();
  lens.height = 1080;
  lens.width = 1920;
  lens.position = Vec3(0.1, 4, -0.1);
  lens.target = Vec3(0.1, 0, -0.1);
  lens.up = Vec3(0, 0, -1);
  const Vec3 centre(0.1, 0, -0.1), across(1, 0, 0);
  const double fp = 540 / std::tan(20 * M_PI / 180);
  ViewParams p;  // l_min 4
  {
    const CameraPath path(lens, {{0.0, lens.position, lens.target, false}});
    EXPECT_EQ(ViewSizing(path, p, 0.2, 0.04).screen_floor(centre, across), p.l_min) << "pinhole, no shutter";
  }
  Camera blurred = lens;
  blurred.focus_distance = 2;
  blurred.f_stop = 2;
  blurred.shutter = 0.5;
  const CameraPath path(blurred, {{0.0, lens.position, lens.target, false}});
  EXPECT_NEAR(ViewSizing(path, p, 0.2, 0.04).screen_floor(centre, Vec3::Zero()), 6.2168764, 1e-6) << "defocus";
  EXPECT_NEAR(ViewSizing(path, p, 0.2, 0.04).screen_floor(centre, 2 * across), fp * 2 * 0.02 / 4, 1e-6) << "motion blur";
  ViewParams off = p;
  off.defocus_scale = 0;
  EXPECT_NEAR(ViewSizing(path, off, 0.2, 0.04).screen_floor(centre, across), fp * 0.02 / 4, 1e-6);
  off.motion_blur_scale = 0;
  EXPECT_EQ(ViewSizing(path, off, 0.2, 0.04).screen_floor(centre, 2 * across), p.l_min);
  const CameraPath cut(blurred, {{0.0, lens.position, lens.target, false}, {0.21, lens.position + Vec3(0, 1, 0), lens.target, true}});
  EXPECT_NEAR(ViewSizing(cut, p, 0.2, 0.04).screen_floor(centre, 2 * across), 6.2168764, 1e-6) << "the shutter spans a cut";

  // Millimetre sizing on a sheet facing the camera comes out at the floor: 6.2169 pixels at 4 m.
  Mesh m = build_mesh(make_grid(0.2, 0.2, 1, 1));  // in the x-z plane, outer side +y, towards the camera
  ViewSizing view(path, p, 0.2, 0.04);
  view.evaluate(m);
  auto& sizing = m.face_attrs().get_or_add<Mat2>("test_sizing", Mat2::Zero());
  for (FaceId f : m.faces()) sizing[f] = Mat2::Identity() / (0.001 * 0.001);
  const std::vector<Mat2> motion(static_cast<std::size_t>(m.face_capacity()), Mat2::Zero());
  view.modify(m, motion, sizing);
  ASSERT_EQ(view.counts().visible, 2);
  EXPECT_EQ(view.counts().defocused, 2) << "the sheet at rest: its floor is the blur circle";
  EXPECT_EQ(view.counts().blurred, 0);
  for (FaceId f : m.faces()) EXPECT_EQ(view.reasons()[static_cast<std::size_t>(f.idx)], ViewReason::defocused);
  for (FaceId f : m.faces()) {
    Eigen::SelfAdjointEigenSolver<Mat2> eig(sizing[f]);
    EXPECT_NEAR(1 / std::sqrt(eig.eigenvalues()[1]), 6.2168764 * 4 / fp, 0.01 * 6.2168764 * 4 / fp);
  }
  // Moving at 2 m/s across the view its streak (14.8 pixels) sets the floor; at rest with the
  // lens a pinhole and the shutter closed, l_min does.
  for (NodeId n : m.nodes()) m.v(n) = 2 * across;
  ViewSizing moving(path, p, 0.2, 0.04);
  moving.evaluate(m);
  EXPECT_EQ(moving.counts().blurred, 2);
  EXPECT_EQ(moving.counts().defocused, 0);
  for (FaceId f : m.faces()) EXPECT_EQ(moving.reasons()[static_cast<std::size_t>(f.idx)], ViewReason::motion_blurred);
  const CameraPath pinhole(lens, {{0.0, lens.position, lens.target, false}});
  ViewSizing sharp(pinhole, p, 0.2, 0.04);
  sharp.evaluate(m);
  EXPECT_EQ(sharp.counts().blurred + sharp.counts().defocused, 0);
  for (FaceId f : m.faces()) EXPECT_EQ(sharp.reasons()[static_cast<std::size_t>(f.idx)], ViewReason::seen);
}

TEST(CameraPath, InterpolatesWithinAShotAndJumpsAtACut) {
  Camera lens = front_camera();
  std::vector<CameraKey> keys{{0.0, Vec3(0, 0, 5), Vec3::Zero(), false}, {1.0, Vec3(2, 0, 5), Vec3::Zero(), false},
                              {2.0, Vec3(9, 9, 9), Vec3(1, 1, 1), true}};
  CameraPath path(lens, keys);
  EXPECT_NEAR(path.at(0.5).position.x(), 1.0, 1e-12);  // Hermite with zero end tangents: symmetric
  EXPECT_EQ(path.at(1.999).position, Vec3(2, 0, 5));   // held after the shot's last key
  EXPECT_EQ(path.at(2.0).position, Vec3(9, 9, 9));     // the new shot from the cut on
  EXPECT_EQ(path.cuts_in(1.0, 2.0), std::vector<double>{2.0});
  EXPECT_TRUE(path.cuts_in(2.0, 3.0).empty());
  EXPECT_EQ(path.at(0.5).focus_distance, 0.0);  // a pinhole
  lens.focus_on_target = true;  // the focus pulled to the target: its distance at every time
  const CameraPath pulled(lens, keys);
  EXPECT_DOUBLE_EQ(pulled.at(0.0).focus_distance, 5.0);
  EXPECT_DOUBLE_EQ(pulled.at(1.0).focus_distance, std::sqrt(29.0));
  EXPECT_DOUBLE_EQ(pulled.at(2.5).focus_distance, std::sqrt(3 * 64.0));
}

}  // namespace
}  // namespace vdc
