// Perspective camera, its frustum, and keyframed camera paths with cuts.
#include "view/camera.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/distance.hpp"
#include "collision/intersection.hpp"

namespace vdc {

std::array<Vec3, 3> Camera::basis() const {
  const Vec3 f = (target - position).normalized();
  Vec3 r = f.cross(up);
  if (r.squaredNorm() < 1e-24) r = f.cross(std::abs(f.y()) < 0.9 ? Vec3(0, 1, 0) : Vec3(1, 0, 0));
  r.normalize();
  return {r, r.cross(f), f};
}

double Camera::focal_pixels() const { return 0.5 * height / std::tan(0.5 * fov_y_degrees * M_PI / 180.0); }

double Camera::focal_length_mm() const { return 0.5 * sensor_height_mm / std::tan(0.5 * fov_y_degrees * M_PI / 180.0); }

// The thin-lens circle of confusion (e.g. Potmesil and Chakravarty 1981, eq. 1).
double Camera::blur_circle_pixels(double depth) const {
  if (focus_distance <= 0 || f_stop <= 0 || depth <= 0) return 0;
  const double f = 1e-3 * focal_length_mm();  // m
  if (focus_distance <= f) return 0;
  const double on_sensor = (f / f_stop) * std::abs(depth - focus_distance) / depth * f / (focus_distance - f);  // m
  return on_sensor / (1e-3 * sensor_height_mm) * height;
}

Vec2 Camera::project(const Vec3& x, double* depth) const { return Projection(*this)(x, depth); }

Projection::Projection(const Camera& camera)
    : basis(camera.basis()), position(camera.position), focal(camera.focal_pixels()), half_width(0.5 * camera.width), half_height(0.5 * camera.height) {}

Vec2 Projection::operator()(const Vec3& x, double* depth) const {
  const auto& [r, u, f] = basis;
  const Vec3 p = x - position;
  const double z = p.dot(f);
  if (depth) *depth = z;
  return Vec2(half_width + focal * p.dot(r) / z, half_height - focal * p.dot(u) / z);
}

Mat23 Camera::projection_jacobian(const Vec3& x) const {
  const auto [r, u, f] = basis();
  const Vec3 p = x - position;
  const double z = p.dot(f), fp = focal_pixels();
  Mat23 j;
  j.row(0) = (fp * (r / z - p.dot(r) * f / (z * z))).transpose();
  j.row(1) = (-fp * (u / z - p.dot(u) * f / (z * z))).transpose();
  return j;
}

double Camera::pixels_per_metre(const Vec3& x) const {
  const Mat23 j = projection_jacobian(x);
  Eigen::SelfAdjointEigenSolver<Mat2> eig;
  eig.computeDirect(j * j.transpose());
  return std::sqrt(std::max(eig.eigenvalues()[1], 0.0));
}

std::array<std::pair<Vec3, double>, 6> Camera::frustum_planes() const {
  const auto [r, u, f] = basis();
  const double ty = std::tan(0.5 * fov_y_degrees * M_PI / 180.0), tx = ty * width / height;
  // Side planes pass through the camera position; their inward normals are f scaled against
  // the side direction: for the right plane, x_r <= tx z  <=>  (tx f - r) . p >= 0.
  auto through_eye = [&](const Vec3& n_raw) {
    const Vec3 n = n_raw.normalized();
    return std::make_pair(n, -n.dot(position));
  };
  return {std::make_pair(f, -f.dot(position) - near), std::make_pair(Vec3(-f), f.dot(position) + far), through_eye(tx * f - r),
          through_eye(tx * f + r), through_eye(ty * f - u), through_eye(ty * f + u)};
}

std::array<Vec3, 8> Camera::frustum_corners() const {
  const auto [r, u, f] = basis();
  const double ty = std::tan(0.5 * fov_y_degrees * M_PI / 180.0), tx = ty * width / height;
  std::array<Vec3, 8> c;
  for (int k = 0; k < 2; ++k) {
    const double z = k == 0 ? near : far;
    const Vec3 centre = position + z * f;
    c[static_cast<std::size_t>(4 * k + 0)] = centre - z * tx * r - z * ty * u;
    c[static_cast<std::size_t>(4 * k + 1)] = centre + z * tx * r - z * ty * u;
    c[static_cast<std::size_t>(4 * k + 2)] = centre + z * tx * r + z * ty * u;
    c[static_cast<std::size_t>(4 * k + 3)] = centre - z * tx * r + z * ty * u;
  }
  return c;
}

Frustum::Frustum(const Camera& camera) : eye(camera.position), planes(camera.frustum_planes()), corners(camera.frustum_corners()) {}

double frustum_plane_separation(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c) {
  double separation = 0;
  for (const auto& [n, offset] : frustum.planes)
    separation = std::max(separation, -std::max({n.dot(a) + offset, n.dot(b) + offset, n.dot(c) + offset}));
  return separation;
}

double distance_to_frustum(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c, double cap) {
  const auto& planes = frustum.planes;
  const std::array<Vec3, 3> tri{a, b, c};
  // Fast paths: a corner inside, or the whole face at least cap beyond one plane.
  for (const Vec3& p : tri)
    if (std::all_of(planes.begin(), planes.end(), [&](const auto& pl) { return pl.first.dot(p) + pl.second >= 0; })) return 0;
  if (frustum_plane_separation(frustum, a, b, c) >= cap) return cap;
  // Two disjoint convex sets: the distance is the smallest vertex-to-face or edge-to-edge one;
  // they meet when an edge of either crosses a face of the other.
  const auto& k = frustum.corners;
  static constexpr int kFaces[12][3] = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}, {0, 3, 7}, {0, 7, 4},
                                        {1, 5, 6}, {1, 6, 2}, {0, 4, 5}, {0, 5, 1}, {3, 2, 6}, {3, 6, 7}};
  static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  auto corner = [&](int i) -> const Vec3& { return k[static_cast<std::size_t>(i)]; };
  for (int e = 0; e < 3; ++e) {
    const Vec3 &p = tri[static_cast<std::size_t>(e)], &q = tri[static_cast<std::size_t>((e + 1) % 3)];
    for (const auto& f : kFaces)
      if (segment_crosses_triangle(p, q, corner(f[0]), corner(f[1]), corner(f[2]))) return 0;
  }
  for (const auto& e : kEdges)
    if (segment_crosses_triangle(corner(e[0]), corner(e[1]), a, b, c)) return 0;
  double d = cap;
  for (const Vec3& p : tri)
    for (const auto& f : kFaces) d = std::min(d, point_triangle_distance(p, corner(f[0]), corner(f[1]), corner(f[2])));
  for (const Vec3& p : k) d = std::min(d, point_triangle_distance(p, a, b, c));
  for (int e = 0; e < 3; ++e)
    for (const auto& fe : kEdges)
      d = std::min(d, segment_segment_distance(tri[static_cast<std::size_t>(e)], tri[static_cast<std::size_t>((e + 1) % 3)], corner(fe[0]), corner(fe[1])));
  return d;
}

CameraPath::CameraPath(const Camera& lens, std::vector<CameraKey> keys) : lens_(lens), keys_(std::move(keys)) {
  const bool rolls = std::any_of(keys_.begin(), keys_.end(), [](const CameraKey& k) { return k.up.has_value(); });
  const bool zooms = std::any_of(keys_.begin(), keys_.end(), [](const CameraKey& k) { return k.fov_y_degrees.has_value(); });
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const CameraKey& k = keys_[i];
    if (i == 0 || k.cut) shots_.push_back(Shot{i == 0 ? -std::numeric_limits<double>::infinity() : k.time, {}, {}, {}, {}});
    Shot& shot = shots_.back();
    shot.position.keys.push_back({k.time, k.position});
    shot.target.keys.push_back({k.time, k.target});
    if (rolls) shot.up.keys.push_back({k.time, k.up.value_or(lens_.up)});
    if (zooms) shot.fov.keys.push_back({k.time, Vec3(k.fov_y_degrees.value_or(lens_.fov_y_degrees), 0, 0)});
  }
}

Vec3 zxy_euler_degrees(const Camera& camera) {
  const auto [right, up, forward] = camera.basis();
  Mat3 r;  // camera to world: its columns are the camera's x, y and z (z points backwards)
  r.col(0) = right;
  r.col(1) = up;
  r.col(2) = -forward;
  // Ry(b) Rx(a) Rz(c) has row 1 (ca sc, ca cc, -sa), column 2 (sb ca, -sa, cb ca).
  const double a = std::asin(std::clamp(-r(1, 2), -1.0, 1.0));
  double b, c;
  if (std::abs(r(1, 2)) < 1 - 1e-12) {
    b = std::atan2(r(0, 2), r(2, 2));
    c = std::atan2(r(1, 0), r(1, 1));
  } else {  // gimbal lock: the heading takes the whole turn about y
    b = std::atan2(-r(2, 0), r(0, 0));
    c = 0;
  }
  return Vec3(a, b, c) * (180.0 / M_PI);
}

Mat3 zxy_rotation(const Vec3& degrees) {
  const Vec3 a = degrees * (M_PI / 180.0);
  return (Eigen::AngleAxisd(a.y(), Vec3::UnitY()) * Eigen::AngleAxisd(a.x(), Vec3::UnitX()) * Eigen::AngleAxisd(a.z(), Vec3::UnitZ())).toRotationMatrix();
}

bool ball_outside(const Frustum& frustum, const Vec3& centre, double radius) {
  for (const auto& [n, c] : frustum.planes)
    if (n.dot(centre) + c < -radius) return true;
  return false;
}

Camera CameraPath::at(double t) const {
  std::size_t s = 0;
  while (s + 1 < shots_.size() && shots_[s + 1].start <= t) ++s;
  Camera c = lens_;
  c.position = shots_[s].position.at(t);
  c.target = shots_[s].target.at(t);
  if (!shots_[s].up.empty()) c.up = shots_[s].up.at(t);
  if (!shots_[s].fov.empty()) c.fov_y_degrees = shots_[s].fov.at(t).x();
  if (c.focus_on_target) c.focus_distance = (c.target - c.position).norm();
  if (c.eye_offset != 0) {
    const Vec3 side = c.eye_offset * c.basis()[0];
    c.position += side;
    c.target += side;
  }
  return c;
}

std::vector<double> CameraPath::cuts_in(double t0, double t1) const {
  std::vector<double> out;
  for (std::size_t s = 1; s < shots_.size(); ++s)
    if (shots_[s].start > t0 && shots_[s].start <= t1) out.push_back(shots_[s].start);
  return out;
}

}  // namespace vdc
