// Continuous collision detection by coplanarity roots (Provot 1997; Bridson et al. 2002, 6.4).
#include "collision/ccd.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <initializer_list>

#include "collision/distance.hpp"

namespace vdc {

namespace {

double eval(const std::array<double, 4>& k, double t) { return ((k[3] * t + k[2]) * t + k[1]) * t + k[0]; }

// Candidate times without a heap allocation (continuous detection tests every candidate pair):
// at most 10 from the cubic (2 ends, 2 critical points, 2 per bisected sign change over 3
// intervals), 6 line crossings and 65 sampled minima, 81 in all.
class Times {
 public:
  void push_back(double t) {
    if (size_ < times_.size()) times_[size_++] = t;
  }
  const double* begin() const { return times_.data(); }
  const double* end() const { return times_.data() + size_; }
  double* begin() { return times_.data(); }
  double* end() { return times_.data() + size_; }
  std::size_t size() const { return size_; }
  double operator[](std::size_t i) const { return times_[i]; }

 private:
  std::array<double, 96> times_{};
  std::size_t size_ = 0;
};

// Roots of k[0] + k[1] t + k[2] t^2 in [0, 1] (all of them when the polynomial vanishes).
void quadratic_roots(double c0, double c1, double c2, Times& out) {
  const double scale = std::max({std::abs(c0), std::abs(c1), std::abs(c2)});
  if (scale == 0) return;
  if (std::abs(c2) <= 1e-14 * scale) {
    if (std::abs(c1) > 1e-14 * scale) out.push_back(-c0 / c1);
    return;
  }
  const double disc = c1 * c1 - 4 * c2 * c0;
  if (disc < 0) {
    out.push_back(-c1 / (2 * c2));  // nearest approach of a complex pair: a candidate anyway
    return;
  }
  const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
  out.push_back(q / c2);
  if (q != 0) out.push_back(c0 / q);
}

// Candidate times of the cubic k on [0, 1]: ends, critical points, bisected sign changes.
Times cubic_candidates(const std::array<double, 4>& k) {
  Times cuts;
  cuts.push_back(0.0);
  cuts.push_back(1.0);
  Times crit;
  quadratic_roots(k[1], 2 * k[2], 3 * k[3], crit);
  for (double t : crit)
    if (t > 0 && t < 1) cuts.push_back(t);
  std::sort(cuts.begin(), cuts.end());
  Times out = cuts;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    double lo = cuts[i], hi = cuts[i + 1];
    double flo = eval(k, lo), fhi = eval(k, hi);
    if ((flo < 0) == (fhi < 0)) continue;
    for (int it = 0; it < 60 && hi - lo > 1e-13; ++it) {
      const double mid = 0.5 * (lo + hi), fm = eval(k, mid);
      if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
      else hi = mid;
    }
    out.push_back(lo);
    out.push_back(hi);
  }
  return out;
}

// Minimises a distance function over [0, 1] by sampling and golden-section refinement: the
// fallback for motion that keeps the points coplanar throughout.
// `lipschitz` bounds |d'(t)|: a sample farther than lipschitz / 64 + eta from contact cannot
// have a contact within half a sample spacing, so only closer local minima are refined.
void sampled_minima(const std::function<double(double)>& dist, double lipschitz, double eta, Times& out) {
  constexpr int kSamples = 64;
  std::array<double, kSamples + 1> d{};
  for (int i = 0; i <= kSamples; ++i) d[static_cast<std::size_t>(i)] = dist(static_cast<double>(i) / kSamples);
  for (int i = 0; i <= kSamples; ++i) {
    const double left = i > 0 ? d[static_cast<std::size_t>(i - 1)] : INFINITY, right = i < kSamples ? d[static_cast<std::size_t>(i + 1)] : INFINITY;
    const double here = d[static_cast<std::size_t>(i)];
    if (here > left || here > right || here > lipschitz / kSamples + eta) continue;
    double lo = std::max(0.0, (i - 1.0) / kSamples), hi = std::min(1.0, (i + 1.0) / kSamples);
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    for (int it = 0; it < 60; ++it) {
      const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
      if (dist(m1) <= dist(m2)) hi = m2;
      else lo = m1;
    }
    out.push_back(0.5 * (lo + hi));
  }
}

template <class Points, class Distance>
Impact earliest(const Times& candidates, const Points& at, const Distance& distance, double eta) {
  Impact r;
  for (double t : candidates) {
    if (!(t >= 0 && t <= 1) || (r.hit && t >= r.t)) continue;
    if (distance(at(t)) <= eta) {
      r.hit = true;
      r.t = t;
    }
  }
  return r;
}

// The cubic is so small over the whole step that its roots are not to be trusted (coplanar or
// nearly coplanar motion, parallel or nearly parallel edges): relative to the size of the
// vectors involved, below 1e-6.
bool nearly_degenerate(const std::array<double, 4>& k, std::initializer_list<Vec3> vectors) {
  double scale = 0;
  for (const Vec3& v : vectors) scale = std::max(scale, v.norm());
  return std::abs(k[0]) + std::abs(k[1]) + std::abs(k[2]) + std::abs(k[3]) <= 1e-6 * scale * scale * scale;
}

// Times at which point p crosses the line through a and b, in the plane with normal n (fixed).
void line_crossings(const Vec3& p, const Vec3& dp, const Vec3& a, const Vec3& da, const Vec3& b, const Vec3& db, const Vec3& n,
                    Times& out) {
  // g(t) = ((b - a) x (p - a)) . n, quadratic in t.
  const Vec3 e = b - a, de = db - da, w = p - a, dw = dp - da;
  const double c0 = e.cross(w).dot(n), c1 = (e.cross(dw) + de.cross(w)).dot(n), c2 = de.cross(dw).dot(n);
  quadratic_roots(c0, c1, c2, out);
}

// How far the distance between the primitives can change over the step. The distance does not
// change under a common translation, so take out the mean displacement: moving every point by
// at most m (relative to that) changes the distance by at most 2 m. A pair that starts farther
// apart than this cannot touch during the step, however fast the pair moves together.
double relative_reach(const Vec3& d0, const Vec3& d1, const Vec3& d2, const Vec3& d3) {
  const Vec3 mean = 0.25 * (d0 + d1 + d2 + d3);
  return 2 * std::max({(d0 - mean).norm(), (d1 - mean).norm(), (d2 - mean).norm(), (d3 - mean).norm()});
}

}  // namespace

std::array<double, 4> coplanarity_cubic(const Vec3& e1, const Vec3& de1, const Vec3& e2, const Vec3& de2, const Vec3& w,
                                        const Vec3& dw) {
  const Vec3 a = e1.cross(e2), b = e1.cross(de2) + de1.cross(e2), c = de1.cross(de2);
  return {a.dot(w), a.dot(dw) + b.dot(w), b.dot(dw) + c.dot(w), c.dot(dw)};
}

Impact vertex_face_ccd(const Vec3& p0, const Vec3& p1, const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1,
                       const Vec3& c0, const Vec3& c1, double eta) {
  const Vec3 dp = p1 - p0, da = a1 - a0, db = b1 - b0, dc = c1 - c0;
  const double reach = relative_reach(dp, da, db, dc) + eta;
  if (point_triangle_distance(p0, a0, b0, c0) > reach) return {};
  const auto k = coplanarity_cubic(b0 - a0, db - da, c0 - a0, dc - da, p0 - a0, dp - da);
  auto at = [&](double t) { return std::array<Vec3, 4>{p0 + t * dp, a0 + t * da, b0 + t * db, c0 + t * dc}; };
  auto dist = [](const std::array<Vec3, 4>& q) { return point_triangle_distance(q[0], q[1], q[2], q[3]); };
  Times cand = cubic_candidates(k);
  if (nearly_degenerate(k, {b0 - a0, c0 - a0, p0 - a0, db - da, dc - da, dp - da})) {
    // Coplanar motion: the point can only enter the triangle across an edge line.
    Vec3 n = (b0 - a0).cross(c0 - a0);
    if (n.squaredNorm() == 0) n = (b1 - a1).cross(c1 - a1);
    line_crossings(p0, dp, a0, da, b0, db, n, cand);
    line_crossings(p0, dp, b0, db, c0, dc, n, cand);
    line_crossings(p0, dp, c0, dc, a0, da, n, cand);
    sampled_minima([&](double t) { return dist(at(t)); }, reach, eta, cand);
  }
  return earliest(cand, at, dist, eta);
}

Impact edge_edge_ccd(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const Vec3& c0, const Vec3& c1,
                     const Vec3& d0, const Vec3& d1, double eta) {
  const Vec3 da = a1 - a0, db = b1 - b0, dc = c1 - c0, dd = d1 - d0;
  const double reach = relative_reach(da, db, dc, dd) + eta;
  if (segment_segment_distance(a0, b0, c0, d0) > reach) return {};
  const auto k = coplanarity_cubic(b0 - a0, db - da, d0 - c0, dd - dc, c0 - a0, dc - da);
  auto at = [&](double t) { return std::array<Vec3, 4>{a0 + t * da, b0 + t * db, c0 + t * dc, d0 + t * dd}; };
  auto dist = [](const std::array<Vec3, 4>& q) { return segment_segment_distance(q[0], q[1], q[2], q[3]); };
  Times cand = cubic_candidates(k);
  if (nearly_degenerate(k, {b0 - a0, d0 - c0, c0 - a0, db - da, dd - dc, dc - da})) sampled_minima([&](double t) { return dist(at(t)); }, reach, eta, cand);
  return earliest(cand, at, dist, eta);
}

}  // namespace vdc
