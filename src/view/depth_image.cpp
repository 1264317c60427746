// Depth images for the view factor's back-face rule (Koh et al. 2014, sec. 3.1, made to look).
#include "view/depth_image.hpp"

#include <limits>
#include <stdexcept>

namespace vdc {

DepthImage::DepthImage(const Camera& camera, double scale)
    : camera_(camera),
      projection_(camera),
      scale_(scale),
      width_(std::max(1, static_cast<int>(std::lround(camera.width * scale)))),
      height_(std::max(1, static_cast<int>(std::lround(camera.height * scale)))) {
  depth_.emplace_back(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), std::numeric_limits<double>::infinity());
}

DepthImage::DepthImage(const Camera& camera, const std::vector<Triangle>& triangles, double scale, int erosion) : DepthImage(camera, scale) {
  draw(triangles);
  erode(erosion);
}

void DepthImage::draw(const std::vector<Triangle>& triangles) {
  if (eroded_) throw std::logic_error("DepthImage::draw after erode");
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<double>& nearest = depth_.front();
  for (const Triangle& t : triangles) {
    std::array<Vec2, 3> screen;
    std::array<double, 3> z{};
    for (int k = 0; k < 3; ++k) screen[static_cast<std::size_t>(k)] = scale_ * projection_(t[static_cast<std::size_t>(k)], &z[static_cast<std::size_t>(k)]);
    if (z[0] < camera_.near || z[1] < camera_.near || z[2] < camera_.near) continue;
    // 1/z is linear on the screen: its gradient, so that each pixel keeps the triangle's farthest
    // depth over the pixel's square rather than at its centre. A surface then never hides its own
    // points (at a grazing angle its depth changes by more than occlusion_depth across a pixel).
    const Vec2 ab = screen[1] - screen[0], ac = screen[2] - screen[0];
    const double area = ab.x() * ac.y() - ab.y() * ac.x();
    if (!(std::abs(area) > 1e-12)) continue;
    const double q1 = 1 / z[1] - 1 / z[0], q2 = 1 / z[2] - 1 / z[0];
    const double spread = 0.5 * (std::abs((ac.y() * q1 - ab.y() * q2) / area) + std::abs((ab.x() * q2 - ac.x() * q1) / area));
    rasterize_triangle(screen[0], screen[1], screen[2], z, width_, height_, [&](int x, int y, double, double, double, double d) {
      const double q = 1 / d - spread;  // the least 1/z over the pixel
      double& here = nearest[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)];
      here = std::min(here, q > 0 ? 1 / q : infinity);
    });
  }
}

void DepthImage::erode(int erosion) {
  if (eroded_) throw std::logic_error("DepthImage::erode twice");
  eroded_ = true;
  // Each erosion is the last one's farthest within one pixel (a square of radius r + 1 is the
  // union of the squares of radius r around its 3x3 pixels), rows then columns.
  for (int r = 1; r <= erosion; ++r) {
    const std::vector<double>& last = depth_.back();
    std::vector<double> rows(last.size()), next(last.size());
    auto at = [&](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x); };
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        double far = 0;
        for (int dx = std::max(0, x - 1); dx <= std::min(width_ - 1, x + 1); ++dx) far = std::max(far, last[at(dx, y)]);
        rows[at(x, y)] = far;
      }
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        double far = 0;
        for (int dy = std::max(0, y - 1); dy <= std::min(height_ - 1, y + 1); ++dy) far = std::max(far, rows[at(x, dy)]);
        next[at(x, y)] = far;
      }
    depth_.push_back(std::move(next));
  }
}

int DepthImage::hidden_levels(const Vec3& x, double margin) const {
  double z = 0;
  const Vec2 p = scale_ * projection_(x, &z);
  if (!(z >= camera_.near) || !std::isfinite(p.x()) || !std::isfinite(p.y())) return 0;
  const auto px = static_cast<int>(std::floor(p.x())), py = static_cast<int>(std::floor(p.y()));
  if (px < 0 || py < 0 || px >= width_ || py >= height_) return 0;
  const std::size_t at = static_cast<std::size_t>(py) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(px);
  int hidden = 0;
  while (hidden < levels() && z > depth_[static_cast<std::size_t>(hidden)][at] + margin) ++hidden;
  return hidden;
}

}  // namespace vdc
