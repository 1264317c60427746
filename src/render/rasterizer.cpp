// Scanline-free rasterization (view/depth_image.hpp's rasterize_triangle: each triangle's pixel
// box walked with edge functions, depth interpolated as 1/z) into a z-buffer; Gouraud shading,
// and the shading normal interpolated alongside it.
#include "render/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "view/depth_image.hpp"

namespace vdc {

namespace {

const Vec3 kBackground(0.86, 0.88, 0.91);

uint8_t to_byte(double c) { return static_cast<uint8_t>(std::lround(255.0 * std::clamp(c, 0.0, 1.0))); }

}  // namespace

Vec3 view_factor_colour(double v) {
  const Vec3 low(0.20, 0.32, 0.85), middle(0.28, 0.72, 0.35), high(0.88, 0.28, 0.20);
  const double t = std::isfinite(v) && v > 0 ? std::clamp((std::log10(v) + 2.0) / 2.0, 0.0, 1.0) : 0.0;
  return t < 0.5 ? Vec3(low + (middle - low) * (2 * t)) : Vec3(middle + (high - middle) * (2 * t - 1));
}

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
    for (std::size_t fi = 0; fi < mesh.faces.size(); ++fi) {
      const auto& f = mesh.faces[fi];
      const std::array<std::size_t, 3> v = {static_cast<std::size_t>(f[0]), static_cast<std::size_t>(f[1]), static_cast<std::size_t>(f[2])};
      if (z[v[0]] < camera.near || z[v[1]] < camera.near || z[v[2]] < camera.near) continue;
      const std::array<double, 3> zs = {z[v[0]], z[v[1]], z[v[2]]};
      const Vec3& base = mesh.face_colours.empty() ? mesh.colour : mesh.face_colours[fi];
      // Wireframe: a barycentric weight times the corner's height over the opposite edge is the
      // pixel's distance from that edge in screen pixels.
      std::array<double, 3> height_over = {0, 0, 0};
      if (mesh.wireframe) {
        const Vec2 &a = screen[v[0]], &b = screen[v[1]], &c = screen[v[2]];
        const double twice_area = std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
        height_over = {twice_area / std::max((c - b).norm(), 1e-12), twice_area / std::max((a - c).norm(), 1e-12),
                       twice_area / std::max((b - a).norm(), 1e-12)};
      }
      rasterize_triangle(screen[v[0]], screen[v[1]], screen[v[2]], zs, width, height, [&](int x, int y, double wa, double wb, double wc, double d) {
        const auto i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        if (d >= depth[i]) return;
        depth[i] = d;
        frame.mesh[i] = static_cast<int32_t>(m);
        const bool on_edge = mesh.wireframe && std::min({wa * height_over[0], wb * height_over[1], wc * height_over[2]}) < kWireHalfWidth;
        const Vec3 colour = base * ((on_edge ? 0.3 : 1.0) * (wa * brightness[v[0]] + wb * brightness[v[1]] + wc * brightness[v[2]]));
        for (int k = 0; k < 3; ++k) frame.image.rgb[3 * i + static_cast<std::size_t>(k)] = to_byte(colour[k]);
        Vec3 n = wa * vertex_normal[v[0]] + wb * vertex_normal[v[1]] + wc * vertex_normal[v[2]];
        const double len = n.norm();
        n = len > 0 ? Vec3(n / len) : Vec3(-forward);
        frame.normal[i] = n.dot(forward) > 0 ? Vec3(-n) : n;
      });
    }
  }
  return frame;
}

}  // namespace vdc
