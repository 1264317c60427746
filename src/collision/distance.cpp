// Point-triangle and segment-segment distances (closest points by region, as in Ericson,
// "Real-Time Collision Detection", sections 5.1.5 and 5.1.9).
#include "collision/distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace vdc {

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 w = closest_triangle_weights(p, a, b, c);
  return (p - (w[0] * a + w[1] * b + w[2] * c)).norm();
}

double segment_segment_distance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 d1 = b - a, d2 = d - c, r = a - c;
  const double aa = d1.squaredNorm(), ee = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (aa <= 0 && ee <= 0) return r.norm();
  if (aa <= 0) {
    t = std::clamp(f / ee, 0.0, 1.0);
  } else {
    const double cc = d1.dot(r);
    if (ee <= 0) {
      s = std::clamp(-cc / aa, 0.0, 1.0);
    } else {
      const double bb = d1.dot(d2), denom = aa * ee - bb * bb;
      s = denom > 1e-14 * aa * ee ? std::clamp((bb * f - cc * ee) / denom, 0.0, 1.0) : 0.0;
      t = (bb * s + f) / ee;
      if (t < 0) {
        t = 0;
        s = std::clamp(-cc / aa, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((bb - cc) / aa, 0.0, 1.0);
      }
    }
  }
  const double closest = ((a + s * d1) - (c + t * d2)).norm();
  // Parallel segments: the clamped pair above may miss an overlap; the endpoint distances bound it.
  return std::min({closest, point_segment_distance(a, c, d), point_segment_distance(b, c, d), point_segment_distance(c, a, b),
                   point_segment_distance(d, a, b)});
}

}  // namespace vdc

namespace vdc {

namespace {
double segment_param(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  return l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
}
}  // namespace

Vec3 closest_triangle_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (n2 > 0) {
    const Vec3 q = p - (p - a).dot(n) / n2 * n;
    const double u = (b - q).cross(c - q).dot(n), v = (c - q).cross(a - q).dot(n), w = (a - q).cross(b - q).dot(n);
    if (u >= 0 && v >= 0 && w >= 0) return Vec3(u, v, w) / n2;
  }
  // Closest point on the boundary: the best of the three edges.
  const double t_ab = segment_param(p, a, b), t_bc = segment_param(p, b, c), t_ca = segment_param(p, c, a);
  const double d_ab = (p - (a + t_ab * (b - a))).squaredNorm(), d_bc = (p - (b + t_bc * (c - b))).squaredNorm(),
               d_ca = (p - (c + t_ca * (a - c))).squaredNorm();
  if (d_ab <= d_bc && d_ab <= d_ca) return Vec3(1 - t_ab, t_ab, 0);
  if (d_bc <= d_ca) return Vec3(0, 1 - t_bc, t_bc);
  return Vec3(t_ca, 0, 1 - t_ca);
}

std::optional<Vec2> closest_line_params(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 d1 = b - a, d2 = d - c, r = a - c;
  const double aa = d1.squaredNorm(), ee = d2.squaredNorm(), bb = d1.dot(d2), denom = aa * ee - bb * bb;
  if (!(denom > 1e-14 * aa * ee && aa > 0 && ee > 0)) return std::nullopt;
  const double s = std::clamp((bb * d2.dot(r) - d1.dot(r) * ee) / denom, 0.0, 1.0);
  return Vec2(s, std::clamp((bb * s + d2.dot(r)) / ee, 0.0, 1.0));
}

Vec2 closest_segment_params(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // Candidates: the interior solution (if not parallel) and the four endpoint projections.
  std::array<Vec2, 5> cand;
  int n = 0;
  const Vec3 d1 = b - a, d2 = d - c;
  if (const std::optional<Vec2> lines = closest_line_params(a, b, c, d)) cand[static_cast<std::size_t>(n++)] = *lines;
  cand[static_cast<std::size_t>(n++)] = Vec2(0, segment_param(a, c, d));
  cand[static_cast<std::size_t>(n++)] = Vec2(1, segment_param(b, c, d));
  cand[static_cast<std::size_t>(n++)] = Vec2(segment_param(c, a, b), 0);
  cand[static_cast<std::size_t>(n++)] = Vec2(segment_param(d, a, b), 1);
  Vec2 best = cand[0];
  double best_d = INFINITY;
  for (int i = 0; i < n; ++i) {
    const Vec2& q = cand[static_cast<std::size_t>(i)];
    const double dist = ((a + q.x() * d1) - (c + q.y() * d2)).squaredNorm();
    if (dist < best_d) best_d = dist, best = q;
  }
  return best;
}

}  // namespace vdc
