// Exact distances between the primitives of collision handling.
#pragma once
#include <optional>

#include "core/math.hpp"

namespace vdc {

// Distance from p to the triangle (a, b, c), degenerate triangles included.
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
// Distance between segments [a, b] and [c, d], parallel and degenerate ones included.
double segment_segment_distance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b);

// Barycentric weights (of a, b, c) of the point of the triangle closest to p.
Vec3 closest_triangle_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
// Parameters (s, u) of the closest points a + s (b - a) and c + u (d - c) of two segments.
Vec2 closest_segment_params(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
// The one candidate of closest_segment_params that can lie inside both segments: the lines'
// closest points, s clamped to [0, 1] and u then clamped; none for parallel or degenerate
// segments. Every other candidate has s or u at 0 or 1, so when this one is not strictly inside
// both, neither is the closest pair.
std::optional<Vec2> closest_line_params(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace vdc
