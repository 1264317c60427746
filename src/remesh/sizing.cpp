// Physical sizing field (Narain et al. 2012, section 5, eqs. for curvature, velocity and
// compression metrics).
#include "remesh/sizing.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/task_order.hpp"
#include "remesh/remesher.hpp"

namespace vdc {

namespace {

// Gradient over the face, in material space, of a quantity given at its three nodes: 3x2.
Mat32 material_gradient(const Mesh& mesh, FaceId f, const Vec3& q0, const Vec3& q1, const Vec3& q2) {
  const auto& vs = mesh.face_verts(f);
  Mat2 du;
  du.col(0) = mesh.u(vs[1]) - mesh.u(vs[0]);
  du.col(1) = mesh.u(vs[2]) - mesh.u(vs[0]);
  Mat32 dq;
  dq.col(0) = q1 - q0;
  dq.col(1) = q2 - q0;
  return dq * du.inverse();
}

// Applies f to the eigenvalues of a symmetric 2x2 matrix.
template <class F>
Mat2 eigen_map(const Mat2& m, F&& f) {
  Eigen::SelfAdjointEigenSolver<Mat2> eig;
  eig.computeDirect(0.5 * (m + m.transpose()));
  Vec2 l(f(eig.eigenvalues()[0]), f(eig.eigenvalues()[1]));
  return eig.eigenvectors() * l.asDiagonal() * eig.eigenvectors().transpose();
}

// Compression metric: resolve the buckles that compressive strain e = F^T F - I would form with
// curvature S2, at wavelength set by c (Narain et al. 2012): max(-e + sqrt(e^T e - 4 c^2
// adj(S2)), 0) / (2 c^2), with the square root and max taken on eigenvalues.
Mat2 compression_metric(const Mat2& e, const Mat2& s2, double c) {
  Mat2 adj;
  adj << s2(1, 1), -s2(0, 1), -s2(1, 0), s2(0, 0);
  Mat2 d = e.transpose() * e - 4 * c * c * adj;
  Mat2 root = eigen_map(d, [](double l) { return std::sqrt(std::max(l, 0.0)); });
  return eigen_map(-e + root, [c](double l) { return std::max(l, 0.0) / (2 * c * c); });
}

std::vector<Vec3> node_normals(const Mesh& mesh) {
  std::vector<Vec3> n(static_cast<std::size_t>(mesh.node_capacity()), Vec3::Zero());
  for (FaceId f : mesh.faces()) {
    Vec3 an = area_normal(mesh.x(mesh.face_node(f, 0)), mesh.x(mesh.face_node(f, 1)), mesh.x(mesh.face_node(f, 2)));
    for (int i = 0; i < 3; ++i) n[static_cast<std::size_t>(mesh.face_node(f, i).idx)] += an;
  }
  for (auto& v : n)
    if (v.norm() > 0) v.normalize();
  return n;
}

}  // namespace

Mat2 tensor_max(const Mat2& a, const Mat2& b) {
  Eigen::SelfAdjointEigenSolver<Mat2> eig;
  eig.computeDirect(a + b);
  const Mat2& q = eig.eigenvectors();
  Vec2 l;
  for (int i = 0; i < 2; ++i) l[i] = std::max(q.col(i).dot(a * q.col(i)), q.col(i).dot(b * q.col(i)));
  return q * l.asDiagonal() * q.transpose();
}

double metric_ratio(const Mat2& m, const Mat2& in) {
  Eigen::SelfAdjointEigenSolver<Mat2> eig;
  eig.computeDirect(0.5 * (in + in.transpose()));
  const Vec2 inv_sqrt = eig.eigenvalues().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Mat2 w = eig.eigenvectors() * inv_sqrt.asDiagonal() * eig.eigenvectors().transpose();
  Eigen::SelfAdjointEigenSolver<Mat2> r;
  r.computeDirect(0.5 * (w * m * w + (w * m * w).transpose()));
  return r.eigenvalues().maxCoeff();
}

Mat2 obstacle_metric(const Mesh& mesh, FaceId f, const std::vector<ObstaclePlane>& planes) {
  Mat2 o = Mat2::Zero();
  for (int v = 0; v < 3; ++v) {
    const ObstaclePlane& plane = planes[static_cast<std::size_t>(mesh.face_node(f, v).idx)];
    if (plane.normal.squaredNorm() == 0) continue;
    Vec3 h;
    for (int k = 0; k < 3; ++k) h[k] = plane.normal.dot(mesh.x(mesh.face_node(f, k)) - plane.point);
    const Mat32 grad = material_gradient(mesh, f, Vec3(h[0], 0, 0), Vec3(h[1], 0, 0), Vec3(h[2], 0, 0));
    const Vec2 dh = grad.row(0).transpose();
    const double hv = std::max(std::abs(h[v]), 1e-6);
    o += dh * dh.transpose() / (hv * hv);
  }
  return o / 3.0;
}

SizingCriteria sizing_criteria(const Mesh& mesh, FaceId f, const std::vector<Vec3>& normals, const SizingParams& p) {
  auto at = [&](const std::vector<Vec3>& v, int i) { return v[static_cast<std::size_t>(mesh.face_node(f, i).idx)]; };
  const NodeId n0 = mesh.face_node(f, 0), n1 = mesh.face_node(f, 1), n2 = mesh.face_node(f, 2);
  const Mat32 dn = material_gradient(mesh, f, at(normals, 0), at(normals, 1), at(normals, 2));
  const Mat32 dv = material_gradient(mesh, f, mesh.v(n0), mesh.v(n1), mesh.v(n2));
  const Mat32 dx = material_gradient(mesh, f, mesh.x(n0), mesh.x(n1), mesh.x(n2));
  const Mat2 s2 = dn.transpose() * dn;
  return {s2 / (p.refine_angle * p.refine_angle), dv.transpose() * dv / (p.refine_velocity * p.refine_velocity),
          compression_metric(dx.transpose() * dx - Mat2::Identity(), s2, p.refine_compression)};
}

Mat2 motion_sizing(const SizingCriteria& c, const SizingParams& p, bool compression) {
  return clamp_sizing(compression ? tensor_max(c.velocity, c.compression) : c.velocity, p);
}

namespace {
bool held(const Mesh& mesh, FaceId f, const std::vector<ObstaclePlane>& planes) {
  for (int v = 0; v < 3; ++v)
    if (!planes[static_cast<std::size_t>(mesh.face_node(f, v).idx)].held) return false;
  return true;
}

// The largest of a face's criteria, obstacle proximity included. The compression criterion
// resolves buckles the cloth would form (Narain et al. 2012, section 5); cloth pressed between
// two surfaces cannot form them, and refining it there only multiplies its contacts.
Mat2 largest_criterion(const SizingCriteria& c, const Mesh& mesh, FaceId f, const std::vector<ObstaclePlane>& planes) {
  Mat2 m = tensor_max(c.curvature, c.velocity);
  if (planes.empty() || !held(mesh, f, planes)) m = tensor_max(m, c.compression);
  return planes.empty() ? m : tensor_max(m, obstacle_metric(mesh, f, planes));
}
}  // namespace

Mat2 face_sizing_unclamped(const Mesh& mesh, FaceId f, const std::vector<Vec3>& normals, const SizingParams& p,
                           const std::vector<ObstaclePlane>& planes) {
  return largest_criterion(sizing_criteria(mesh, f, normals, p), mesh, f, planes);
}

Mat2 clamp_sizing(const Mat2& m, const SizingParams& p) {
  const double lo = 1.0 / (p.size_max * p.size_max), hi = 1.0 / (p.size_min * p.size_min);
  Eigen::SelfAdjointEigenSolver<Mat2> eig;
  eig.computeDirect(0.5 * (m + m.transpose()));
  Vec2 l = eig.eigenvalues().cwiseMax(lo).cwiseMin(hi);
  const double floor = l.maxCoeff() * p.aspect_min * p.aspect_min;
  l = l.cwiseMax(floor);
  return eig.eigenvectors() * l.asDiagonal() * eig.eigenvectors().transpose();
}

void compute_sizing(Mesh& mesh, const SizingParams& p, const FaceSizingModifier* modifier, const std::vector<ObstaclePlane>& planes,
                    int threads) {
  auto& face = mesh.face_attrs().get_or_add<Mat2>(kFaceSizingAttr, Mat2::Zero());
  const std::vector<Vec3> normals = node_normals(mesh);
  std::vector<Mat2> motion(modifier ? static_cast<std::size_t>(mesh.face_capacity()) : 0, Mat2::Zero());
  const bool keeps_compression = modifier && modifier->keeps_compression();
  const std::vector<FaceId> faces = mesh.faces().list();
  for_each_index(static_cast<int64_t>(faces.size()), threads, [&](int64_t k) {
    const FaceId f = faces[static_cast<std::size_t>(k)];
    const SizingCriteria c = sizing_criteria(mesh, f, normals, p);
    face[f] = clamp_sizing(largest_criterion(c, mesh, f, planes), p);
    if (modifier)
      motion[static_cast<std::size_t>(f.idx)] =
          motion_sizing(c, p, keeps_compression && (planes.empty() || !held(mesh, f, planes)));
  });
  if (modifier) {
    const std::vector<Mat2> before = face.raw();
    modifier->modify(mesh, motion, face);
    // A modifier trades visual detail, not collision safety: what it changed stays within
    // size_max, where the obstacle planes are searched, and keeps the obstacle-proximity tensor,
    // so a coarsened garment cannot cut into the body it hangs on.
    auto& coarsening = mesh.face_attrs().get_or_add<double>(kCoarseningAttr, 1.0);
    auto& fold_led = mesh.face_attrs().get_or_add<double>(kFoldLedAttr, 0.0);
    for_each_index(static_cast<int64_t>(faces.size()), threads, [&](int64_t k) {
    const FaceId f = faces[static_cast<std::size_t>(k)];
      const Mat2& physical = before[static_cast<std::size_t>(f.idx)];
      if (face[f] != physical) face[f] = clamp_sizing(planes.empty() ? face[f] : tensor_max(face[f], obstacle_metric(mesh, f, planes)), p);
      const double against_physics = face[f] == physical ? 1.0 : metric_ratio(physical, face[f]);
      const double against_folds = modifier->fold_coarsening(mesh, f, face[f]);
      coarsening[f] = std::max(against_physics, against_folds);
      fold_led[f] = against_folds > against_physics ? 1.0 : 0.0;
    });
  }
  auto& vert = mesh.vert_attrs().get_or_add<Mat2>(kSizingAttr, Mat2::Zero());
  const std::vector<VertId> verts = mesh.verts().list();
  for_each_index(static_cast<int64_t>(verts.size()), threads, [&](int64_t k) {
    const VertId v = verts[static_cast<std::size_t>(k)];
    Mat2 sum = Mat2::Zero();
    double area = 0;
    for (FaceId f : mesh.vert_faces(v)) {
      const double a = mesh.material_area(f);
      sum += a * face[f];
      area += a;
    }
    vert[v] = area > 0 ? Mat2(sum / area) : Mat2::Zero();
    if (p.resolution_scale != 1.0) vert[v] /= p.resolution_scale * p.resolution_scale;
  });
}

void set_uniform_sizing(Mesh& mesh, double h) {
  auto& vert = mesh.vert_attrs().get_or_add<Mat2>(kSizingAttr, Mat2::Zero());
  for (VertId v : mesh.verts()) vert[v] = Mat2::Identity() / (h * h);
}

}  // namespace vdc
