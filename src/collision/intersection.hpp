// Static intersection tests used to check the result of collision handling: triangle-triangle
// intersection by segment-triangle crossings (Moller 1997's case analysis reduced to its
// crossing tests), in double precision with orientation signs taken strictly.
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "core/bvh.hpp"
#include "core/math.hpp"

namespace vdc {

// True when segment [p, q] crosses the interior or boundary of triangle (a, b, c) transversally.
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);
// The plane of triangle s, for Moller 1997's first rejection: a triangle, or a whole box of
// them, wholly on one side of it by far more than the crossing tests' tolerance.
class PlaneOf {
 public:
  explicit PlaneOf(const std::array<Vec3, 3>& s);
  // True when t lies wholly on one side of the plane, by five times the crossing tests'
  // tolerance: then no edge of either triangle crosses the other.
  bool separates(const std::array<Vec3, 3>& t) const;
  // True when every point of b lies on one side of the plane by more than twice separates'
  // margin: then separates(t) holds for every triangle t within b.
  bool clears(const Aabb& b) const {
    // The box's points are at least |n.(c - p)| - sum |n_i| h_i from the plane (times |n|), and
    // within |c - p| + |h| of the corner p that separates measures from; squared, with
    // (a + b)^2 <= 2 a^2 + 2 b^2.
    const Vec3 centre = 0.5 * (b.lo + b.hi), half = 0.5 * (b.hi - b.lo);
    const double nearest = std::abs(normal_.dot(centre - corner_)) - normal_.cwiseAbs().dot(half);
    return nearest > 0 && nearest * nearest > 8e-22 * normal_length2_ * ((centre - corner_).squaredNorm() + half.squaredNorm());
  }

 private:
  Vec3 corner_, normal_;
  double normal_length2_;
};
// True when the triangles intersect (a transversal crossing of an edge of either through the other).
bool triangles_intersect(const std::array<Vec3, 3>& s, const std::array<Vec3, 3>& t);
// Number of intersecting pairs of triangles that share no node.
int count_self_intersections(const std::vector<std::array<int32_t, 3>>& faces, const std::vector<Vec3>& x);
// Number of intersecting pairs of a face of A (positions xa) and a face of B (positions xb).
int count_intersections_between(const std::vector<std::array<int32_t, 3>>& faces_a, const std::vector<Vec3>& xa,
                                const std::vector<std::array<int32_t, 3>>& faces_b, const std::vector<Vec3>& xb);

}  // namespace vdc
