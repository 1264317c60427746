// Triangle-triangle intersection by edge-triangle crossings (after Moller 1997).
#include "collision/intersection.hpp"

#include <algorithm>
#include <cmath>

#include "core/bvh.hpp"

namespace vdc {

bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  double sp = orient3(a, b, c, p), sq = orient3(a, b, c, q);
  // Sides within rounding of the plane count as on it (1e-12 of the lengths involved), so that
  // triangles of one flat sheet, which rounding leaves a few ulps off each other's plane, are
  // not taken for crossings.
  const double tol = 1e-12 * (b - a).cross(c - a).norm() * ((p - a).norm() + (q - a).norm());
  if (std::abs(sp) <= tol) sp = 0;
  if (std::abs(sq) <= tol) sq = 0;
  if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0) || (sp == 0 && sq == 0)) return false;
  // The segment's line passes through the triangle when it sees the three edges turning the same way.
  const double e0 = orient3(p, q, a, b), e1 = orient3(p, q, b, c), e2 = orient3(p, q, c, a);
  return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

PlaneOf::PlaneOf(const std::array<Vec3, 3>& s)
    : corner_(s[0]), normal_((s[1] - s[0]).cross(s[2] - s[0])), normal_length2_(normal_.squaredNorm()) {}

bool PlaneOf::separates(const std::array<Vec3, 3>& t) const {
  const Vec3 r0 = t[0] - corner_, r1 = t[1] - corner_, r2 = t[2] - corner_;
  const double d0 = normal_.dot(r0), d1 = normal_.dot(r1), d2 = normal_.dot(r2);
  if (!((d0 > 0 && d1 > 0 && d2 > 0) || (d0 < 0 && d1 < 0 && d2 < 0))) return false;
  // The crossing tests take a side within 1e-12 |n| (|p - a| + |q - a|) <= 2e-12 |n| reach for
  // the plane; a margin five times that, compared squared.
  const double reach2 = std::max({r0.squaredNorm(), r1.squaredNorm(), r2.squaredNorm()});
  const double nearest = std::min({std::abs(d0), std::abs(d1), std::abs(d2)});
  return nearest * nearest > 1e-22 * normal_length2_ * reach2;
}

bool triangles_intersect(const std::array<Vec3, 3>& s, const std::array<Vec3, 3>& t) {
  if (PlaneOf(s).separates(t) || PlaneOf(t).separates(s)) return false;
  for (int i = 0; i < 3; ++i) {
    const auto i0 = static_cast<std::size_t>(i), i1 = static_cast<std::size_t>((i + 1) % 3);
    if (segment_crosses_triangle(s[i0], s[i1], t[0], t[1], t[2])) return true;
    if (segment_crosses_triangle(t[i0], t[i1], s[0], s[1], s[2])) return true;
  }
  return false;
}

int count_self_intersections(const std::vector<std::array<int32_t, 3>>& faces, const std::vector<Vec3>& x) {
  std::vector<Aabb> boxes(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int32_t n : faces[f]) boxes[f].grow(x[static_cast<std::size_t>(n)]);
  Bvh bvh(boxes);
  int count = 0;
  bvh.self_pairs([&](int32_t a, int32_t b) {
    const auto &fa = faces[static_cast<std::size_t>(a)], &fb = faces[static_cast<std::size_t>(b)];
    for (int32_t n : fa)
      if (n == fb[0] || n == fb[1] || n == fb[2]) return;
    auto tri = [&](const std::array<int32_t, 3>& f) {
      return std::array<Vec3, 3>{x[static_cast<std::size_t>(f[0])], x[static_cast<std::size_t>(f[1])], x[static_cast<std::size_t>(f[2])]};
    };
    if (triangles_intersect(tri(fa), tri(fb))) ++count;
  });
  return count;
}

int count_intersections_between(const std::vector<std::array<int32_t, 3>>& faces_a, const std::vector<Vec3>& xa,
                                const std::vector<std::array<int32_t, 3>>& faces_b, const std::vector<Vec3>& xb) {
  auto tri = [](const std::array<int32_t, 3>& f, const std::vector<Vec3>& x) {
    return std::array<Vec3, 3>{x[static_cast<std::size_t>(f[0])], x[static_cast<std::size_t>(f[1])], x[static_cast<std::size_t>(f[2])]};
  };
  std::vector<Aabb> boxes(faces_b.size());
  for (std::size_t f = 0; f < faces_b.size(); ++f)
    for (const Vec3& p : tri(faces_b[f], xb)) boxes[f].grow(p);
  const Bvh tree(boxes);
  int count = 0;
  for (const auto& fa : faces_a) {
    const auto t = tri(fa, xa);
    Aabb box;
    for (const Vec3& p : t) box.grow(p);
    tree.query(box, [&](int32_t g) { count += triangles_intersect(t, tri(faces_b[static_cast<std::size_t>(g)], xb)); });
  }
  return count;
}

}  // namespace vdc
