// Marching tetrahedra on the Kuhn subdivision of a regular grid.
#include "core/isosurface.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace vdc {

MeshSource polygonize(const std::function<double(const Vec3&)>& f, const Aabb& box, double h) {
  const Vec3 size = box.hi - box.lo;
  const int nx = std::max(1, static_cast<int>(std::ceil(size.x() / h))), ny = std::max(1, static_cast<int>(std::ceil(size.y() / h))),
            nz = std::max(1, static_cast<int>(std::ceil(size.z() / h)));
  auto index = [&](int i, int j, int k) { return (static_cast<int64_t>(k) * (ny + 1) + j) * (nx + 1) + i; };
  auto point = [&](int64_t id) {
    const int64_t i = id % (nx + 1), j = (id / (nx + 1)) % (ny + 1), k = id / (static_cast<int64_t>(nx + 1) * (ny + 1));
    return Vec3(box.lo.x() + h * static_cast<double>(i), box.lo.y() + h * static_cast<double>(j), box.lo.z() + h * static_cast<double>(k));
  };
  // Field at the grid points; exact zeros count as outside.
  std::vector<double> value(static_cast<std::size_t>(index(nx, ny, nz) + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) value[static_cast<std::size_t>(index(i, j, k))] = f(point(index(i, j, k)));
  auto inside = [&](int64_t id) { return value[static_cast<std::size_t>(id)] < 0; };

  MeshSource out;
  std::unordered_map<int64_t, int32_t> edge_vertex;  // key: lower id * stride + higher id
  const int64_t stride = index(nx, ny, nz) + 1;
  auto vertex_on = [&](int64_t a, int64_t b) {
    if (a > b) std::swap(a, b);
    const int64_t key = a * stride + b;
    auto it = edge_vertex.find(key);
    if (it != edge_vertex.end()) return it->second;
    const double fa = value[static_cast<std::size_t>(a)], fb = value[static_cast<std::size_t>(b)];
    const double t = std::clamp(fa / (fa - fb), 0.05, 0.95);
    const auto v = static_cast<int32_t>(out.positions.size());
    out.positions.push_back((1 - t) * point(a) + t * point(b));
    edge_vertex.emplace(key, v);
    return v;
  };
  // Adds triangle (a, b, c), turned to face away from the inside point `in`.
  auto triangle = [&](int32_t a, int32_t b, int32_t c, const Vec3& in) {
    const Vec3 &pa = out.positions[static_cast<std::size_t>(a)], &pb = out.positions[static_cast<std::size_t>(b)],
               &pc = out.positions[static_cast<std::size_t>(c)];
    if ((pb - pa).cross(pc - pa).dot(pa - in) < 0) std::swap(b, c);
    out.faces.push_back({Corner{a, 0}, Corner{b, 0}, Corner{c, 0}});
  };
  // The six Kuhn tetrahedra: corners 0 = (0,0,0) and 7 = (1,1,1) with a path through the axes.
  static constexpr int kAxisOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& order : kAxisOrders) {
          std::array<int64_t, 4> t;
          int c[3] = {i, j, k};
          t[0] = index(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[order[s]];
            t[static_cast<std::size_t>(s + 1)] = index(c[0], c[1], c[2]);
          }
          std::array<int64_t, 4> in, ex;
          int n_in = 0, n_ex = 0;
          for (int64_t v : t) (inside(v) ? in[static_cast<std::size_t>(n_in++)] : ex[static_cast<std::size_t>(n_ex++)]) = v;
          if (n_in == 0 || n_in == 4) continue;
          if (n_in == 1 || n_in == 3) {
            // One corner apart: a triangle across its three edges.
            const int64_t apart = n_in == 1 ? in[0] : ex[0];
            const auto& others = n_in == 1 ? ex : in;
            const Vec3 in_point = n_in == 1 ? point(in[0]) : (point(in[0]) + point(in[1]) + point(in[2])) / 3.0;
            triangle(vertex_on(apart, others[0]), vertex_on(apart, others[1]), vertex_on(apart, others[2]), in_point);
          } else {
            // Two and two: a quad across four edges, split into two triangles.
            const int32_t a = vertex_on(in[0], ex[0]), b = vertex_on(in[0], ex[1]), c2 = vertex_on(in[1], ex[1]), d = vertex_on(in[1], ex[0]);
            const Vec3 in_point = 0.5 * (point(in[0]) + point(in[1]));
            triangle(a, b, c2, in_point);
            triangle(a, c2, d, in_point);
          }
        }
  return out;
}

}  // namespace vdc
