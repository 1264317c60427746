// Sizing field: clamping, the tensor max, and the curvature and velocity criteria against
// analytic values.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <tuple>

#include "core/mesh_build.hpp"
#include "remesh/remesher.hpp"
#include "remesh/sizing.hpp"

namespace vdc {
namespace {

Vec2 eigenvalues(const Mat2& m) {
  Eigen::SelfAdjointEigenSolver<Mat2> eig;
  eig.computeDirect(m);
  return eig.eigenvalues();
}

TEST(Sizing, ClampBoundsEigenvaluesAndAnisotropy) {
  SizingParams p;  // sizes 1 cm to 20 cm, aspect 0.2
  Mat2 tiny = Mat2::Identity() * 1e-6, huge = Mat2::Identity() * 1e9;
  EXPECT_NEAR(eigenvalues(clamp_sizing(tiny, p))[0], 1 / (0.2 * 0.2), 1e-9);
  EXPECT_NEAR(eigenvalues(clamp_sizing(huge, p))[1], 1 / (0.01 * 0.01), 1e-6);
  // Strongly anisotropic: 1/(1 cm)^2 along u, nothing along v. The v eigenvalue is raised to
  // aspect^2 times the u one: 0.04 * 10^4 = 400 (5 cm edges along v).
  Mat2 aniso = Mat2::Zero();
  aniso(0, 0) = 1e4;
  Vec2 l = eigenvalues(clamp_sizing(aniso, p));
  EXPECT_NEAR(l[0], 400, 1e-9);
  EXPECT_NEAR(l[1], 1e4, 1e-9);
}

TEST(Sizing, TensorMaxIsTheMaxOnSharedAxesAndDominatesOnRandomPairs) {
  Mat2 a = Vec2(4, 1).asDiagonal(), b = Vec2(2, 3).asDiagonal();
  EXPECT_LT((tensor_max(a, b) - Mat2(Vec2(4, 3).asDiagonal())).norm(), 1e-12);
  EXPECT_LT((tensor_max(a, Mat2::Zero()) - a).norm(), 1e-12);
}

TEST(Sizing, CurvatureCriterionOnACylinderMatchesKappaOverRefineAngle) {
  // A sheet rolled on a cylinder of radius R about the material v axis: the normal turns at
  // rate 1/R along u and not along v, so the face tensor is diag(1/(R a)^2, 0) before clamping
  // (a = refine_angle): edges along u at most a R long.
  const double radius = 0.5;
  Mesh mesh = build_mesh(make_grid(0.6, 0.6, 30, 30));
  for (NodeId n : mesh.nodes()) {
    const Vec2& u = mesh.u(mesh.node_verts(n).front());
    double t = u.x() / radius;
    mesh.x(n) = Vec3(radius * std::sin(t), radius * (1 - std::cos(t)), -u.y());
  }
  SizingParams p;
  std::vector<Vec3> normals(static_cast<std::size_t>(mesh.node_capacity()));
  for (NodeId n : mesh.nodes()) {
    const Vec2& u = mesh.u(mesh.node_verts(n).front());
    double t = u.x() / radius;
    normals[static_cast<std::size_t>(n.idx)] = Vec3(-std::sin(t), std::cos(t), 0);  // exact cylinder normals
  }
  const double expected = 1 / std::pow(radius * p.refine_angle, 2);
  for (FaceId f : mesh.faces()) {
    Mat2 m = face_sizing_unclamped(mesh, f, normals, p);
    EXPECT_NEAR(m(0, 0), expected, 0.01 * expected);
    EXPECT_NEAR(m(1, 1), 0.0, 1e-6 * expected);
  }
}

TEST(Sizing, VelocityCriterionMatchesTheGradient) {
  // v = (0, w u_x, 0): a shear flow whose velocity changes by w per metre along u.
  const double w = 2.0;
  Mesh mesh = build_mesh(make_grid(1, 1, 4, 4));
  for (NodeId n : mesh.nodes()) mesh.v(n) = Vec3(0, w * mesh.x(n).x(), 0);
  SizingParams p;
  std::vector<Vec3> flat(static_cast<std::size_t>(mesh.node_capacity()), Vec3(0, 1, 0));
  for (FaceId f : mesh.faces()) {
    Mat2 m = face_sizing_unclamped(mesh, f, flat, p);
    EXPECT_NEAR(m(0, 0), w * w / (p.refine_velocity * p.refine_velocity), 1e-9);
    EXPECT_NEAR(m(1, 1), 0.0, 1e-9);
  }
}

// A modifier that scales every face tensor, remembering the motion tensors it was given.
class ScalingModifier final : public FaceSizingModifier {
 public:
  explicit ScalingModifier(double s, bool keeps_compression = false) : scale_(s), keeps_compression_(keeps_compression) {}
  void modify(const Mesh& mesh, const std::vector<Mat2>& motion, Attribute<FaceTag, Mat2>& face) const override {
    motion_ = motion;
    for (FaceId f : mesh.faces()) face[f] = scale_ * face[f];
  }
  bool keeps_compression() const override { return keeps_compression_; }
  mutable std::vector<Mat2> motion_;

 private:
  double scale_;
  bool keeps_compression_;
};

TEST(Sizing, ModifiersGetTheMotionCriteriaAndTheCoarseningTheyCauseIsRecorded) {
  EXPECT_NEAR(metric_ratio(Vec2(100, 4).asDiagonal(), Vec2(25, 4).asDiagonal()), 4.0, 1e-12);
  const Mat2 r = Eigen::Rotation2Dd(0.3).toRotationMatrix();
  EXPECT_NEAR(metric_ratio(r * Mat2(Vec2(9, 1).asDiagonal()) * r.transpose(), Mat2::Identity()), 9.0, 1e-12);
  // The shear flow of VelocityCriterionMatchesTheGradient at w = 5: 100 along u (10 cm edges),
  // nothing along v, clamped to 1/(20 cm)^2 = 25. A quarter of it is clamped back to 25 along
  // both axes: the face may be 2 times longer along u than physics asks, 4 in the metric.
  const double w = 5.0;
  Mesh mesh = build_mesh(make_grid(1, 1, 4, 4));
  for (NodeId n : mesh.nodes()) mesh.v(n) = Vec3(0, w * mesh.x(n).x(), 0);
  SizingParams p;
  ScalingModifier quarter(0.25);
  compute_sizing(mesh, p, &quarter);
  const auto& face = mesh.face_attrs().get<Mat2>(kFaceSizingAttr);
  const auto& coarsening = mesh.face_attrs().get<double>(kCoarseningAttr);
  for (FaceId f : mesh.faces()) {
    const Mat2& motion = quarter.motion_[static_cast<std::size_t>(f.idx)];
    EXPECT_NEAR(motion(0, 0), 100, 1e-9);
    EXPECT_NEAR(motion(1, 1), 25, 1e-9);
    EXPECT_NEAR(face[f](0, 0), 25, 1e-9);
    EXPECT_NEAR(face[f](1, 1), 25, 1e-9);
    EXPECT_NEAR(coarsening[f], 4.0, 1e-9);
  }
  // Compression is not a motion criterion (unless the modifier keeps it, below): a sheet at rest
  // squeezed to 90% along u asks for finer faces by its compression criterion, but the modifier
  // is given only the clamped velocity criterion, the coarsest size.
  Mesh squeezed = build_mesh(make_grid(1, 1, 4, 4));
  for (NodeId n : squeezed.nodes()) squeezed.x(n).x() *= 0.9;
  const std::vector<Vec3> up(static_cast<std::size_t>(squeezed.node_capacity()), Vec3(0, 0, 1));
  for (FaceId f : squeezed.faces())
    EXPECT_GT(clamp_sizing(sizing_criteria(squeezed, f, up, p).compression, p)(0, 0), 100.0);
  compute_sizing(squeezed, p, &quarter);
  for (FaceId f : squeezed.faces())
    EXPECT_LT((quarter.motion_[static_cast<std::size_t>(f.idx)] - 25 * Mat2::Identity()).norm(), 1e-9);
  // Refining is no coarsening.
  ScalingModifier four(4);
  compute_sizing(mesh, p, &four);
  for (FaceId f : mesh.faces()) EXPECT_NEAR(mesh.face_attrs().get<double>(kCoarseningAttr)[f], 0.25, 1e-9);
}

// A modifier that scales every face tensor and says every face is `folds` times coarser than
// folds it cannot show.
class FoldingModifier final : public FaceSizingModifier {
 public:
  FoldingModifier(double scale, double folds) : scale_(scale), folds_(folds) {}
  void modify(const Mesh& mesh, const std::vector<Mat2>&, Attribute<FaceTag, Mat2>& face) const override {
    for (FaceId f : mesh.faces()) face[f] = scale_ * face[f];
  }
  double fold_coarsening(const Mesh&, FaceId, const Mat2&) const override { return folds_; }

 private:
  double scale_, folds_;
};

// The coarsening recorded is the larger of the physical one and the folds', also where the
// modifier left the tensor as physics asked (a smooth coarse mesh whose physics asks nothing).
TEST(Sizing, TheCoarseningRecordedIsAlsoAgainstTheFoldsAModifierCannotShow) {
  SizingParams p;
  Mesh rest = build_mesh(make_grid(1, 1, 4, 4));  // every face at size_max: physics asks nothing
  const FoldingModifier unchanged(1, 9);
  compute_sizing(rest, p, &unchanged);
  for (FaceId f : rest.faces()) {
    EXPECT_NEAR(rest.face_attrs().get<double>(kCoarseningAttr)[f], 9.0, 1e-12);
    EXPECT_EQ(rest.face_attrs().get<double>(kFoldLedAttr)[f], 1.0);
  }
  // The shear flow above: a quarter of the tensor is a coarsening of 4 against physics, which
  // leads against folds of 2 and not against folds of 16.
  Mesh shear = build_mesh(make_grid(1, 1, 4, 4));
  for (NodeId n : shear.nodes()) shear.v(n) = Vec3(0, 5 * shear.x(n).x(), 0);
  for (const auto& [folds, recorded, led] : {std::tuple{2.0, 4.0, 0.0}, std::tuple{16.0, 16.0, 1.0}}) {
    const FoldingModifier quarter(0.25, folds);
    compute_sizing(shear, p, &quarter);
    for (FaceId f : shear.faces()) {
      EXPECT_NEAR(shear.face_attrs().get<double>(kCoarseningAttr)[f], recorded, 1e-9);
      EXPECT_EQ(shear.face_attrs().get<double>(kFoldLedAttr)[f], led);
    }
  }
}


// Sizing on two threads is the one-thread field, tensor for tensor: a curved, sheared sheet
// under a modifier (faces, coarsening and verts).
TEST(Sizing, TwoThreadsComputeTheOneThreadField) {
  SizingParams p;
  const FoldingModifier quarter(0.25, 2.0);
  std::vector<Mesh> meshes;
  for (int threads : {1, 2}) {
    Mesh mesh = build_mesh(make_grid(1, 1, 24, 24));
    for (NodeId n : mesh.nodes()) {
      const Vec3 x = mesh.x(n);
      mesh.x(n) = Vec3(x.x(), 0.05 * std::sin(7 * x.x()) * std::cos(5 * x.z()), x.z());
      mesh.v(n) = Vec3(0, 5 * x.x() * x.z(), 0);
    }
    compute_sizing(mesh, p, &quarter, {}, threads);
    meshes.push_back(std::move(mesh));
  }
  const Mesh& one = meshes[0];
  const Mesh& two = meshes[1];
  EXPECT_EQ(one.face_attrs().get<Mat2>(kFaceSizingAttr).raw(), two.face_attrs().get<Mat2>(kFaceSizingAttr).raw());
  EXPECT_EQ(one.face_attrs().get<double>(kCoarseningAttr).raw(), two.face_attrs().get<double>(kCoarseningAttr).raw());
  EXPECT_EQ(one.vert_attrs().get<Mat2>(kSizingAttr).raw(), two.vert_attrs().get<Mat2>(kSizingAttr).raw());
  // Not a uniform field: the comparison above has something to compare.
  const auto& verts = one.vert_attrs().get<Mat2>(kSizingAttr).raw();
  EXPECT_NE(verts.front(), verts[verts.size() / 2]);
}

// A modifier that gives each face its own isotropic tensor, inside the clamp (1/0.2^2 to 1/0.01^2).
class PerFaceModifier final : public FaceSizingModifier {
 public:
  void modify(const Mesh& mesh, const std::vector<Mat2>&, Attribute<FaceTag, Mat2>& face) const override {
    for (FaceId f : mesh.faces()) face[f] = (30.0 + 10.0 * f.idx) * Mat2::Identity();
  }
};

TEST(Sizing, VertsAverageTheirFacesByArea) {
  Mesh mesh = build_mesh(make_grid(1, 1, 2, 2));
  SizingParams p;
  compute_sizing(mesh, p);
  // A flat sheet at rest asks for the coarsest size everywhere.
  const auto& vert = mesh.vert_attrs().get<Mat2>(kSizingAttr);
  for (VertId v : mesh.verts()) EXPECT_LT((vert[v] - Mat2::Identity() / (0.2 * 0.2)).norm(), 1e-9);

  // Faces of unequal tensors and areas (the middle vert moved off centre in material space):
  // each vert gets the area-weighted mean of its faces' tensors, computed here by hand.
  VertId middle;
  for (VertId v : mesh.verts())
    if ((mesh.u(v) - Vec2(0.5, 0.5)).norm() < 1e-12) middle = v;
  ASSERT_TRUE(middle.valid());
  mesh.u(middle) = Vec2(0.3, 0.65);
  const PerFaceModifier modifier;
  compute_sizing(mesh, p, &modifier);
  double plain_mean = 0, weighted = 0, total = 0;
  for (VertId v : mesh.verts()) {
    Mat2 sum = Mat2::Zero();
    double area = 0, count = 0;
    for (FaceId f : mesh.vert_faces(v)) {
      sum += mesh.material_area(f) * (30.0 + 10.0 * f.idx) * Mat2::Identity();
      area += mesh.material_area(f);
      count += 1;
      if (v == middle) plain_mean += 30.0 + 10.0 * f.idx;
    }
    EXPECT_LT((vert[v] - sum / area).norm(), 1e-9 * (sum / area).norm()) << "vert " << v.idx;
    if (v == middle) weighted = vert[v](0, 0), total = count;
  }
  // The middle vert's eight faces: weighting by area is not the plain mean there.
  EXPECT_EQ(total, 8);
  EXPECT_GT(std::abs(weighted - plain_mean / total), 1.0);
}

// --perturb-resolution: every vert's tensor divided by (1 + E)^2, so an edge of metric length
// exactly 1 before is 1 / (1 + E) after: the remesher lets it be 1 + E times as long.
TEST(Sizing, ResolutionScaleLetsEveryEdgeBeThatManyTimesAsLong) {
  Mesh mesh = build_mesh(make_grid(1, 1, 2, 2));
  const PerFaceModifier modifier;  // faces of unequal tensors
  SizingParams p;
  compute_sizing(mesh, p, &modifier);
  const std::vector<Mat2> plain = mesh.vert_attrs().get<Mat2>(kSizingAttr).raw();
  p.resolution_scale = 1.01;
  compute_sizing(mesh, p, &modifier);
  const auto& scaled = mesh.vert_attrs().get<Mat2>(kSizingAttr);
  for (VertId v : mesh.verts()) {
    const Mat2& before = plain[static_cast<std::size_t>(v.idx)];
    EXPECT_LT((scaled[v] * 1.0201 - before).norm(), 1e-12 * before.norm()) << "vert " << v.idx;
  }
}

TEST(Sizing, ObstacleMetricResolvesTheGapAlongTheSlope) {
  // One face, material (0,0), (0.1,0), (0,0.1) placed at (u, 0.01 + 0.5 u, v): its height over the
  // plane y = 0 grows at 0.5 per metre along u and not at all along v.
  MeshSource src;
  src.positions = {Vec3(0, 0.01, 0), Vec3(0.1, 0.06, 0), Vec3(0, 0.01, 0.1)};
  src.uvs = {Vec2(0, 0), Vec2(0.1, 0), Vec2(0, 0.1)};
  src.faces = {{Corner{0, 0}, Corner{1, 1}, Corner{2, 2}}};
  Mesh m = build_mesh(src);
  const FaceId f = *m.faces().begin();
  std::vector<ObstaclePlane> planes(3, ObstaclePlane{Vec3(0, 0, 0), Vec3(0, 1, 0)});
  // Node heights 0.01, 0.06, 0.01: (1/3) (0.25/0.01^2 + 0.25/0.06^2 + 0.25/0.01^2) along u.
  const double expected = (0.25 / 1e-4 + 0.25 / 0.0036 + 0.25 / 1e-4) / 3;
  Mat2 o = obstacle_metric(m, f, planes);
  EXPECT_NEAR(o(0, 0), expected, 1e-9 * expected);
  EXPECT_NEAR(o(1, 1), 0, 1e-9);
  EXPECT_NEAR(o(0, 1), 0, 1e-9);
  // A node with no obstacle near contributes nothing; a plane parallel to the face, nothing.
  planes[1].normal = Vec3::Zero();
  EXPECT_NEAR(obstacle_metric(m, f, planes)(0, 0), (0.25 / 1e-4 + 0.25 / 1e-4) / 3, 1e-6);
  std::vector<ObstaclePlane> parallel(3, ObstaclePlane{Vec3(0, 0, 0), Vec3(0.5, -1, 0).normalized()});
  EXPECT_LT(obstacle_metric(m, f, parallel).norm(), 1e-9);
}

TEST(Sizing, CompressionIsNotRefinedWhereTheClothIsHeld) {
  // The squeezed sheet of ModifiersGetTheMotionCriteria..., at rest and flat in y = 0: its
  // compression criterion alone asks for refinement. Held at every node (between two surfaces;
  // the plane 2 mm below is parallel to it, so proximity asks nothing) it asks for nothing; a
  // node let go gives its faces their compression criterion back.
  SizingParams p;
  Mesh squeezed = build_mesh(make_grid(1, 1, 4, 4));
  for (NodeId n : squeezed.nodes()) squeezed.x(n).x() *= 0.9;
  const std::vector<Vec3> up(static_cast<std::size_t>(squeezed.node_capacity()), Vec3(0, 1, 0));
  std::vector<ObstaclePlane> planes(static_cast<std::size_t>(squeezed.node_capacity()), ObstaclePlane{Vec3(0, -0.002, 0), Vec3(0, 1, 0), true});
  for (FaceId f : squeezed.faces()) EXPECT_LT(face_sizing_unclamped(squeezed, f, up, p, planes).norm(), 1e-9);
  const NodeId freed = *squeezed.nodes().begin();
  planes[static_cast<std::size_t>(freed.idx)].held = false;
  int touching = 0;
  for (FaceId f : squeezed.faces()) {
    bool has = false;
    for (int k = 0; k < 3; ++k) has |= squeezed.face_node(f, k) == freed;
    touching += has;
    const Mat2 expected = has ? sizing_criteria(squeezed, f, up, p).compression : Mat2::Zero();
    EXPECT_GT(sizing_criteria(squeezed, f, up, p).compression(0, 0), 100.0);
    EXPECT_LT((face_sizing_unclamped(squeezed, f, up, p, planes) - expected).norm(), 1e-9 * (1 + expected.norm())) << f.idx;
  }
  EXPECT_GE(touching, 1);
}

// A modifier that keeps the compression criterion is given it in the motion tensors of the
// squeezed sheet at rest (velocity asks nothing: the clamped compression criterion itself, edges
// under 1 cm along u), but not where every node is held, as the physical tensor is not; a node
// let go gives its faces the criterion back.
TEST(Sizing, AModifierKeepingCompressionGetsItInTheMotionTensorsWhereTheClothIsFree) {
  SizingParams p;
  Mesh squeezed = build_mesh(make_grid(1, 1, 4, 4));
  for (NodeId n : squeezed.nodes()) squeezed.x(n).x() *= 0.9;
  const std::vector<Vec3> up(static_cast<std::size_t>(squeezed.node_capacity()), Vec3(0, 1, 0));  // flat in y = 0
  ScalingModifier keeping(0.25, true);
  compute_sizing(squeezed, p, &keeping);
  for (FaceId f : squeezed.faces()) {
    const Mat2 compression = clamp_sizing(sizing_criteria(squeezed, f, up, p).compression, p);
    EXPECT_GT(compression(0, 0), 100.0);
    EXPECT_LT((keeping.motion_[static_cast<std::size_t>(f.idx)] - compression).norm(), 1e-9 * compression.norm());
  }
  std::vector<ObstaclePlane> planes(static_cast<std::size_t>(squeezed.node_capacity()), ObstaclePlane{Vec3(0, -0.002, 0), Vec3(0, 1, 0), true});
  const NodeId freed = *squeezed.nodes().begin();
  planes[static_cast<std::size_t>(freed.idx)].held = false;
  compute_sizing(squeezed, p, &keeping, planes);
  for (FaceId f : squeezed.faces()) {
    bool has = false;
    for (int k = 0; k < 3; ++k) has |= squeezed.face_node(f, k) == freed;
    const Mat2 expected = has ? clamp_sizing(sizing_criteria(squeezed, f, up, p).compression, p) : Mat2(25 * Mat2::Identity());
    EXPECT_LT((keeping.motion_[static_cast<std::size_t>(f.idx)] - expected).norm(), 1e-9 * expected.norm()) << f.idx;
  }
}

}  // namespace
}  // namespace vdc
