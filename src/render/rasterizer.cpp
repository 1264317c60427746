// Scanline-free rasterization: each triangle's pixel box is walked with edge functions, depth is
// interpolated as 1/z (linear in screen space) and kept in a z-buffer; Gouraud shading, and the
// shading normal interpolated alongside it.
#include "render/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vdc {

namespace {

const Vec3 kBackground(0.86, 0.88, 0.91);

uint8_t to_byte(double c) { return static_cast<uint8_t>(std::lround(255.0 * std::clamp(c, 0.0, 1.0))); }

}  // namespace

RenderedFrame render(const Camera& camera, const std::vector<RenderMesh>& meshes, double scale) {
  const int width = std::max(1, static_cast<int>(std::lround(camera.width * scale)));
  const int height = std::max(1, static_cast<int>(std::lround(camera.height * scale)));
  const auto pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  RenderedFrame frame;
  frame.image.width = width;
  frame.image.height = height;
  frame.image.rgb.resize(3 * pixels);
  frame.mesh.assign(pixels, -1);
  frame.depth.assign(pixels, std::numeric_limits<double>::infinity());
  frame.normal.assign(pixels, Vec3::Zero());
  for (std::size_t i = 0; i < pixels; ++i)
    for (int k = 0; k < 3; ++k) frame.image.rgb[3 * i + static_cast<std::size_t>(k)] = to_byte(kBackground[k]);
  std::vector<double>& depth = frame.depth;

  const Vec3 forward = camera.basis()[2];
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const RenderMesh& mesh = meshes[m];
    std::vector<Vec2> screen(mesh.positions.size());
    std::vector<double> z(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) screen[i] = scale * camera.project(mesh.positions[i], &z[i]);
    // Gouraud shading: brightness at each vertex from its area-weighted normal against the
    // view direction (a distant light at the eye, both sides lit), interpolated across faces.
    std::vector<Vec3> vertex_normal(mesh.positions.size(), Vec3::Zero());
    for (const auto& f : mesh.faces) {
      const Vec3 n = (mesh.positions[static_cast<std::size_t>(f[1])] - mesh.positions[static_cast<std::size_t>(f[0])])
                         .cross(mesh.positions[static_cast<std::size_t>(f[2])] - mesh.positions[static_cast<std::size_t>(f[0])]);
      for (int32_t v : f) vertex_normal[static_cast<std::size_t>(v)] += n;
    }
    std::vector<double> brightness(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const double len = vertex_normal[i].norm();
      brightness[i] = 0.25 + 0.75 * (len > 0 ? std::abs(vertex_normal[i].dot(forward)) / len : 1.0);
      // A vertex without a normal is lit as if facing the camera, and its normal says so.
      vertex_normal[i] = len > 0 ? Vec3(vertex_normal[i] / len) : Vec3(-forward);
    }
    for (const auto& f : mesh.faces) {
      const std::array<std::size_t, 3> v = {static_cast<std::size_t>(f[0]), static_cast<std::size_t>(f[1]), static_cast<std::size_t>(f[2])};
      if (z[v[0]] < camera.near || z[v[1]] < camera.near || z[v[2]] < camera.near) continue;
      const Vec2 &a = screen[v[0]], &b = screen[v[1]], &c = screen[v[2]];
      const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (!(std::abs(area) > 1e-12)) continue;
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
      const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
      const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const Vec2 p(x + 0.5, y + 0.5);
          // Barycentric weights from the signed areas of the sub-triangles opposite each corner.
          const double wa = ((b - p).x() * (c - p).y() - (b - p).y() * (c - p).x()) / area;
          const double wb = ((c - p).x() * (a - p).y() - (c - p).y() * (a - p).x()) / area;
          const double wc = 1 - wa - wb;
          if (wa < 0 || wb < 0 || wc < 0) continue;
          const double d = 1.0 / (wa / z[v[0]] + wb / z[v[1]] + wc / z[v[2]]);
          const auto i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
          if (d >= depth[i]) continue;
          depth[i] = d;
          frame.mesh[i] = static_cast<int32_t>(m);
          const Vec3 colour = mesh.colour * (wa * brightness[v[0]] + wb * brightness[v[1]] + wc * brightness[v[2]]);
          for (int k = 0; k < 3; ++k) frame.image.rgb[3 * i + static_cast<std::size_t>(k)] = to_byte(colour[k]);
          Vec3 n = wa * vertex_normal[v[0]] + wb * vertex_normal[v[1]] + wc * vertex_normal[v[2]];
          const double len = n.norm();
          n = len > 0 ? Vec3(n / len) : Vec3(-forward);
          frame.normal[i] = n.dot(forward) > 0 ? Vec3(-n) : n;
        }
    }
  }
  return frame;
}

}  // namespace vdc
