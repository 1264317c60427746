// Vertex-face and edge-edge impacts (Bridson, Fedkiw and Anderson 2002, section 7.4).
#include "collision/narrow_phase.hpp"

#include <array>
#include <cmath>

#include "collision/ccd.hpp"
#include "collision/distance.hpp"

namespace vdc {

namespace {

// The constraint sum_j w_j x_j . n >= separation over the four points: movable ones by node,
// the others by their end positions, and the fixed points' displacement (weighted by |w_j|) for
// the fallback that carries a stuck zone along.
ImpactConstraint constraint_of(const std::array<const PointPath*, 4>& pts, const std::array<double, 4>& w, const Vec3& n) {
  ImpactConstraint c;
  c.weights = w;
  c.normal = n;
  double weight_fixed = 0;
  for (std::size_t j = 0; j < 4; ++j) {
    const PointPath& p = *pts[j];
    c.nodes[j] = p.node;
    c.fixed[j] = p.end;
    if (p.node < 0) {
      c.fixed_motion += std::abs(w[j]) * (p.end - p.start);
      weight_fixed += std::abs(w[j]);
    }
  }
  if (weight_fixed > 0) {
    c.fixed_motion /= weight_fixed;
    c.has_fixed = true;
  }
  return c;
}

Vec3 at_time(const PointPath& q, double t) { return Vec3(q.start + t * (q.end - q.start)); }

}  // namespace

std::optional<ImpactConstraint> vertex_face_impact(const PointPath& p, const PointPath& a, const PointPath& b, const PointPath& c,
                                                   double eta) {
  const Impact hit = vertex_face_ccd(p.start, p.end, a.start, a.end, b.start, b.end, c.start, c.end, eta);
  if (!hit.hit) return std::nullopt;
  const Vec3 pt = at_time(p, hit.t), at = at_time(a, hit.t), bt = at_time(b, hit.t), ct = at_time(c, hit.t);
  const Vec3 w = closest_triangle_weights(pt, at, bt, ct);
  Vec3 n = (bt - at).cross(ct - at);
  if (n.squaredNorm() == 0) n = (b.end - a.end).cross(c.end - a.end);
  if (n.squaredNorm() == 0) return std::nullopt;
  n.normalize();
  const Vec3 foot0 = w[0] * a.start + w[1] * b.start + w[2] * c.start;
  if (n.dot(p.start - foot0) < 0) n = -n;  // the side the vertex came from
  return constraint_of({&p, &a, &b, &c}, {1.0, -w[0], -w[1], -w[2]}, n);
}

std::optional<ImpactConstraint> edge_edge_impact(const PointPath& a, const PointPath& b, const PointPath& c, const PointPath& d,
                                                 double eta) {
  const Impact hit = edge_edge_ccd(a.start, a.end, b.start, b.end, c.start, c.end, d.start, d.end, eta);
  if (!hit.hit) return std::nullopt;
  const Vec3 at = at_time(a, hit.t), bt = at_time(b, hit.t), ct = at_time(c, hit.t), dt = at_time(d, hit.t);
  const Vec2 su = closest_segment_params(at, bt, ct, dt);
  const double s = su.x(), u = su.y();
  const Vec3 sep0 = (1 - s) * a.start + s * b.start - (1 - u) * c.start - u * d.start;
  Vec3 n = (bt - at).cross(dt - ct);
  if (n.squaredNorm() < 1e-20 * (bt - at).squaredNorm() * (dt - ct).squaredNorm()) n = sep0;
  if (n.squaredNorm() == 0) return std::nullopt;
  n.normalize();
  if (n.dot(sep0) < 0) n = -n;
  return constraint_of({&a, &b, &c, &d}, {1 - s, s, -(1 - u), -u}, n);
}

}  // namespace vdc
