// Several cameras in one view-dependent sizing: each face takes the most any camera asks of it,
// the largest of the single-camera factors and the finer of the single-camera tensors,
// face by face; a face one camera sees is as that camera alone would have it, one out of every
// frame is coarse, and a camera's cut is anticipated for that camera alone.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/mesh_build.hpp"
#include "view/view_sizing.hpp"
#include "support/front_camera.hpp"

namespace vdc {
namespace {

using test::front_camera;

// A 4 m square sheet in the x-z plane (x 0 to 4, z 0 to -4), outer side +y, of 512 faces.
Mesh four_metre_sheet() { return build_mesh(make_grid(4.0, 4.0, 16, 16)); }

// front_camera()'s lens looking straight down from `height` above (x, 0, -2).
CameraPath looking_down(double x, double height) {
  Camera lens = front_camera();
  lens.up = Vec3(0, 0, -1);
  return CameraPath(lens, {{0.0, Vec3(x, height, -2), Vec3(x, 0, -2), false}});
}

double shortest_edge(const Mat2& t) { return 1 / std::sqrt(Eigen::SelfAdjointEigenSolver<Mat2>(t).eigenvalues()[1]); }

// The view's tensors of every face for 1 mm physical edges and no motion.
std::vector<Mat2> view_tensors(ViewSizing& view, Mesh& m) {
  auto& sizing = m.face_attrs().get_or_add<Mat2>("test_sizing", Mat2::Zero());
  for (FaceId f : m.faces()) sizing[f] = Mat2::Identity() / (0.001 * 0.001);
  view.modify(m, std::vector<Mat2>(static_cast<std::size_t>(m.face_capacity()), Mat2::Zero()), sizing);
  std::vector<Mat2> out(static_cast<std::size_t>(m.face_capacity()), Mat2::Zero());
  for (FaceId f : m.faces()) out[static_cast<std::size_t>(f.idx)] = sizing[f];
  return out;
}

// Camera 0 2 m above the left of the sheet (x -0.5 to 2.1 in frame), camera 1 3 m above its
// right (x 1.3 to 5.1), both framing z within 0.7 m (1.1 m) of -2: faces seen by one camera, by
// both, and by neither (the sheet's far edges, up to 1.3 m out of frame).
TEST(ViewCameras, EachFaceTakesTheMostAnyCameraAsksOfIt) {
  Mesh m = four_metre_sheet();
  const CameraPath left = looking_down(0.8, 2), right = looking_down(3.2, 3);
  ViewParams p;
  p.l_min = 4;
  ViewSizing a(left, p, 0.0, 0.04), b(right, p, 0.0, 0.04), both({&left, &right}, p, 0.0, 0.04);
  a.evaluate(m);
  b.evaluate(m);
  both.evaluate(m);
  const std::vector<Mat2> ta = view_tensors(a, m), tb = view_tensors(b, m), t2 = view_tensors(both, m);
  ASSERT_EQ(both.cameras(), 2u);
  int left_only = 0, right_only = 0, seen_twice = 0, unseen = 0;
  for (FaceId f : m.faces()) {
    const auto i = static_cast<std::size_t>(f.idx);
    const double fa = a.factors()[i], fb = b.factors()[i];
    EXPECT_EQ(both.factors()[i], std::max(fa, fb)) << "face " << i;
    EXPECT_EQ(both.camera_factors(0)[i], fa);
    EXPECT_EQ(both.camera_factors(1)[i], fb);
    if (fa != fb) {
      EXPECT_EQ(both.deciders()[i], fa > fb ? 0 : 1) << "face " << i;
    }
    EXPECT_EQ(t2[i], finer_tensor(ta[i], tb[i])) << "face " << i;
    // At least as fine as each camera asks; as camera 0 (1) alone where camera 1 (0) sees the
    // face not at all, far out of its frame (v_out), and the nearer camera's floor where both see it.
    const double finest = std::min(shortest_edge(ta[i]), shortest_edge(tb[i]));
    EXPECT_LE(shortest_edge(t2[i]), finest * (1 + 1e-9)) << "face " << i;
    const bool seen_a = a.reasons()[i] == ViewReason::seen, seen_b = b.reasons()[i] == ViewReason::seen;
    if (seen_a && fb == p.v_out) {
      ++left_only;
      EXPECT_EQ(both.reasons()[i], ViewReason::seen);
      EXPECT_NEAR(shortest_edge(t2[i]), shortest_edge(ta[i]), 1e-9 * shortest_edge(ta[i])) << "as camera 0 alone, face " << i;
    } else if (seen_b && fa == p.v_out) {
      ++right_only;
      EXPECT_NEAR(shortest_edge(t2[i]), shortest_edge(tb[i]), 1e-9 * shortest_edge(tb[i])) << "as camera 1 alone, face " << i;
    } else if (seen_a && seen_b) {
      ++seen_twice;
      // The nearer camera's floor: edges of 4 of its pixels, 2 m away rather than 3.
      EXPECT_NEAR(shortest_edge(t2[i]), shortest_edge(ta[i]), 1e-9 * shortest_edge(ta[i])) << "face " << i;
      EXPECT_LT(shortest_edge(ta[i]), shortest_edge(tb[i]));
    } else if (a.reasons()[i] == ViewReason::out_of_frame && b.reasons()[i] == ViewReason::out_of_frame) {
      ++unseen;
      EXPECT_LT(both.factors()[i], 1.0) << "coarse, face " << i;
      EXPECT_EQ(both.reasons()[i], ViewReason::out_of_frame);
    }
  }
  EXPECT_GT(left_only, 20);
  EXPECT_GT(right_only, 20);
  EXPECT_GT(seen_twice, 20);
  EXPECT_GT(unseen, 20);
  int seen_by_either = 0;
  for (FaceId f : m.faces())
    seen_by_either += a.reasons()[static_cast<std::size_t>(f.idx)] == ViewReason::seen || b.reasons()[static_cast<std::size_t>(f.idx)] == ViewReason::seen;
  EXPECT_EQ(both.counts().visible, seen_by_either);
}

// Camera 0 looks up, away from the sheet, and cuts at 0.1 s to looking down at it; camera 1 looks
// up all along. At time 0 eq. 4's window (5 frames of 0.04 s) holds camera 0's cut, weighted
// 1 - 0.1 / 0.2 = 0.5: the faces it will show take 0.5 from camera 0, while camera 1's own
// factors stay what it alone gives (v_out everywhere).
TEST(ViewCameras, ACutIsAnticipatedForItsCameraAlone) {
  Mesh m = four_metre_sheet();
  Camera lens = front_camera();
  lens.up = Vec3(0, 0, -1);
  const CameraPath cutting(lens, {{0.0, Vec3(2, 2, -2), Vec3(2, 4, -2), false}, {0.1, Vec3(2, 2, -2), Vec3(2, 0, -2), true}});
  const CameraPath away(lens, {{0.0, Vec3(2, 2, -2), Vec3(2, 4, -2), false}});
  ViewParams p;
  ViewSizing alone(away, p, 0.0, 0.04), both({&cutting, &away}, p, 0.0, 0.04);
  alone.evaluate(m);
  both.evaluate(m);
  int shown_after_cut = 0;
  for (FaceId f : m.faces()) {
    const auto i = static_cast<std::size_t>(f.idx);
    EXPECT_EQ(alone.factors()[i], p.v_out) << "face " << i;
    EXPECT_EQ(both.camera_factors(1)[i], alone.factors()[i]) << "face " << i;
    EXPECT_EQ(both.reasons()[i], ViewReason::out_of_frame);
    if (both.camera_factors(0)[i] == 0.5) {
      ++shown_after_cut;
      EXPECT_EQ(both.factors()[i], 0.5);
      EXPECT_EQ(both.deciders()[i], 0);
    }
  }
  EXPECT_GT(shown_after_cut, 100);
}

// The finer of two tensors: the one at least as fine in every direction, as it is; else their
// tensor_max, finer than either along the axes of their sum.
TEST(ViewCameras, TheFinerTensorKeepsTheOneThatAsksMore) {
  const Mat2 fine = Vec2(400, 100).asDiagonal(), coarse = Vec2(100, 25).asDiagonal();
  Mat2 tilted;
  tilted << 300, 120, 120, 90;
  EXPECT_EQ(finer_tensor(fine, coarse), fine);
  EXPECT_EQ(finer_tensor(coarse, fine), fine);
  EXPECT_EQ(finer_tensor(tilted, tilted), tilted);
  const Mat2 crossing = Vec2(100, 400).asDiagonal();  // finer along y, coarser along x
  EXPECT_EQ(finer_tensor(fine, crossing), tensor_max(fine, crossing));
  EXPECT_EQ(finer_tensor(fine, crossing), Mat2(Vec2(400, 400).asDiagonal()));
}

// A pair of cameras at one place is that camera: the same factors and tensors, bit for bit.
TEST(ViewCameras, TwoCopiesOfOneCameraAreThatCamera) {
  Mesh m = four_metre_sheet();
  const CameraPath path = looking_down(1.5, 2.5);
  ViewParams p;
  p.l_min = 4;
  p.l_max = 40;
  ViewSizing one(path, p, 0.0, 0.04), two({&path, &path}, p, 0.0, 0.04);
  one.evaluate(m);
  two.evaluate(m);
  const std::vector<Mat2> t1 = view_tensors(one, m), t2 = view_tensors(two, m);
  for (FaceId f : m.faces()) {
    const auto i = static_cast<std::size_t>(f.idx);
    EXPECT_EQ(two.factors()[i], one.factors()[i]);
    EXPECT_EQ(two.deciders()[i], 0);
    EXPECT_EQ(t2[i], t1[i]) << "face " << i;
  }
  EXPECT_EQ(two.counts().visible, one.counts().visible);
}

}  // namespace
}  // namespace vdc
