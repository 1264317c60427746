// Continuous collision detection for linear motion over a step (Provot 1997; Bridson, Fedkiw and
// Anderson 2002, section 6.4): the primitives can only touch when their four points are
// coplanar, a cubic in time; the distance is checked at every candidate time.
//
// Tolerance, stated: a contact is reported when the exact distance at a candidate time is at
// most `eta` (absolute, metres). Candidates are t = 0, t = 1, the critical points of the cubic
// (so a double root, a tangency, is never missed even without a sign change), every sign-change
// root refined by bisection to 1e-13 in t, and, when the cubic is nearly zero over the
// whole step (coplanar motion, parallel edges), the times at which one point crosses the line
// of another edge, plus 65 samples refined by golden-section search on the distance. Nearly
// zero means the cubic's coefficients sum to at most 1e-6 of the cube of the largest vector. A real
// collision is never missed; false positives within eta are allowed. Choose eta at least 1e-6 of
// the primitives' size: for edges within 1e-7 rad of parallel the closest points themselves lose
// digits (tested down to that angle).
#pragma once
#include <array>

#include "core/math.hpp"

namespace vdc {

struct Impact {
  bool hit = false;
  double t = 1;  // earliest candidate time with distance <= eta
};

// Point p moving from p0 to p1 against triangle (a, b, c) moving from (a0, b0, c0).
Impact vertex_face_ccd(const Vec3& p0, const Vec3& p1, const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1,
                       const Vec3& c0, const Vec3& c1, double eta);
// Edge (a, b) against edge (c, d).
Impact edge_edge_ccd(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const Vec3& c0, const Vec3& c1,
                     const Vec3& d0, const Vec3& d1, double eta);

// The coplanarity cubic (e1(t) x e2(t)) . w(t) for linearly moving vectors, as coefficients of
// 1, t, t^2, t^3.
std::array<double, 4> coplanarity_cubic(const Vec3& e1, const Vec3& de1, const Vec3& e2, const Vec3& de2, const Vec3& w,
                                        const Vec3& dw);

}  // namespace vdc
