// Depth images for the view factor's back-face rule (Koh et al. 2014, sec. 3.1, made to look).
#include "view/depth_image.hpp"

#include <limits>

namespace vdc {

DepthImage::DepthImage(const Camera& camera, const std::vector<Triangle>& triangles, double scale, int erosion)
    : camera_(camera),
      scale_(scale),
      width_(std::max(1, static_cast<int>(std::lround(camera.width * scale)))),
      height_(std::max(1, static_cast<int>(std::lround(camera.height * scale)))) {
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<double> nearest(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), infinity);
  for (const Triangle& t : triangles) {
    std::array<Vec2, 3> screen;
    std::array<double, 3> z{};
    for (int k = 0; k < 3; ++k) screen[static_cast<std::size_t>(k)] = scale * camera.project(t[static_cast<std::size_t>(k)], &z[static_cast<std::size_t>(k)]);
    if (z[0] < camera.near || z[1] < camera.near || z[2] < camera.near) continue;
    rasterize_triangle(screen[0], screen[1], screen[2], z, width_, height_, [&](int x, int y, double, double, double, double d) {
      double& here = nearest[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)];
      here = std::min(here, d);
    });
  }
  if (erosion <= 0) {
    depth_ = std::move(nearest);
    return;
  }
  // The farthest within the square of radius `erosion`, rows then columns (a separable max).
  std::vector<double> rows(nearest.size());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      double far = 0;
      for (int dx = std::max(0, x - erosion); dx <= std::min(width_ - 1, x + erosion); ++dx)
        far = std::max(far, nearest[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(dx)]);
      rows[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] = far;
    }
  depth_.assign(nearest.size(), 0.0);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      double far = 0;
      for (int dy = std::max(0, y - erosion); dy <= std::min(height_ - 1, y + erosion); ++dy)
        far = std::max(far, rows[static_cast<std::size_t>(dy) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)]);
      depth_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] = far;
    }
}

bool DepthImage::hidden(const Vec3& x, double margin) const {
  double z = 0;
  const Vec2 p = scale_ * camera_.project(x, &z);
  if (!(z >= camera_.near) || !std::isfinite(p.x()) || !std::isfinite(p.y())) return false;
  const auto px = static_cast<int>(std::floor(p.x())), py = static_cast<int>(std::floor(p.y()));
  if (px < 0 || py < 0 || px >= width_ || py >= height_) return false;
  return z > depth_[static_cast<std::size_t>(py) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(px)] + margin;
}

}  // namespace vdc
