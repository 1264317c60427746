// What stands in front of cloth seen from the camera: a depth image (z-buffer) of the scene's
// opaque triangles, bodies and garments, at a fraction of the camera's resolution. The view
// factor asks it whether a face is hidden: behind a body, another garment or another layer, or,
// turned away from the camera, really hidden (Koh et al. 2014's back-face rule, section 3.1,
// assumes it is: the inside of a hakama lifted by a kick or of a flared skirt faces away from the
// camera and is in plain view).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/math.hpp"
#include "view/camera.hpp"

namespace vdc {

// Walks the pixels whose centres lie in the screen triangle (a, b, c) (pixel coordinates, z the
// corners' camera depths), clipped to a width x height image, and calls visit(x, y, wa, wb, wc,
// depth): the pixel, its barycentric weights and its depth interpolated as 1/z (linear in screen
// space). Degenerate triangles visit nothing.
template <class Visit>
void rasterize_triangle(const Vec2& a, const Vec2& b, const Vec2& c, const std::array<double, 3>& z, int width, int height, Visit&& visit) {
  const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (!(std::abs(area) > 1e-12)) return;
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
      visit(x, y, wa, wb, wc, 1.0 / (wa / z[0] + wb / z[1] + wc / z[2]));
    }
}

class DepthImage {
 public:
  // Nothing seen yet by `camera` at `scale` times its image size (every pixel hides nothing).
  DepthImage(const Camera& camera, double scale);
  // The nearest surface of `triangles` seen by `camera`, eroded by `erosion` pixels: draw, then
  // erode.
  DepthImage(const Camera& camera, const std::vector<Triangle>& triangles, double scale, int erosion);
  // Adds `triangles` to the nearest surface, each pixel at the farthest depth of its nearest
  // triangle over the pixel's square (conservative); a triangle with a corner in front of the
  // near plane is left out (it hides nothing then). Only before erode().
  void draw(const std::vector<Triangle>& triangles);
  // Keeps the image at every erosion from 0 to `erosion` pixels (levels): at erosion r each
  // pixel holds the farthest of the nearest depths within r pixels, so an occluder's edge hides
  // nothing within r pixels of it. Once.
  void erode(int erosion);
  // x lies behind that surface, eroded by `erosion` pixels, by more than `margin` metres (false
  // outside the image).
  bool hidden(const Vec3& x, double margin) const { return hidden_levels(x, margin) == levels(); }
  // How deep inside an occluder x lies: the number of erosions 0, 1, ..., `erosion` at which it
  // is hidden (0: in plain view; levels(): hidden at the full erosion). Hidden at one erosion, a
  // point is hidden at every smaller one.
  int hidden_levels(const Vec3& x, double margin) const;
  int levels() const { return static_cast<int>(depth_.size()); }
  int width() const { return width_; }
  int height() const { return height_; }
  const Camera& camera() const { return camera_; }

 private:
  Camera camera_;
  Projection projection_;  // the camera's
  double scale_;
  int width_, height_;
  // depth_[r]: eroded by r pixels, row-major, +infinity where nothing is near enough to hide
  std::vector<std::vector<double>> depth_;
  bool eroded_ = false;
};

}  // namespace vdc
