// Silhouette overlap (intersection over union) and mean pixel difference of two renders.
#include "render/compare.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace vdc {

RenderComparison compare_renders(const RenderedFrame& a, const std::vector<char>& cloth_a, const RenderedFrame& b,
                                 const std::vector<char>& cloth_b) {
  if (a.image.width != b.image.width || a.image.height != b.image.height) throw std::invalid_argument("compare_renders: image sizes differ");
  auto is_cloth = [](const RenderedFrame& f, const std::vector<char>& cloth, std::size_t i) {
    const int32_t m = f.mesh[i];
    return m >= 0 && static_cast<std::size_t>(m) < cloth.size() && cloth[static_cast<std::size_t>(m)];
  };
  RenderComparison c;
  int both = 0, either = 0;
  double diff = 0;
  for (std::size_t i = 0; i < a.mesh.size(); ++i) {
    const bool in_a = is_cloth(a, cloth_a, i), in_b = is_cloth(b, cloth_b, i);
    c.cloth_pixels_a += in_a;
    c.cloth_pixels_b += in_b;
    both += in_a && in_b;
    if (!in_a && !in_b) continue;
    ++either;
    for (std::size_t k = 0; k < 3; ++k) diff += std::abs(int(a.image.rgb[3 * i + k]) - int(b.image.rgb[3 * i + k])) / 3.0;
  }
  if (either > 0) {
    c.cloth_iou = static_cast<double>(both) / either;
    c.mean_abs_diff = diff / either;
  }
  return c;
}

MeshOverlap compare_mesh(const RenderedFrame& a, int32_t mesh_a, const RenderedFrame& b, int32_t mesh_b) {
  if (a.mesh.size() != b.mesh.size()) throw std::invalid_argument("compare_mesh: image sizes differ");
  MeshOverlap o;
  for (std::size_t i = 0; i < a.mesh.size(); ++i) {
    const bool in_a = mesh_a >= 0 && a.mesh[i] == mesh_a, in_b = mesh_b >= 0 && b.mesh[i] == mesh_b;
    o.pixels_a += in_a;
    o.pixels_b += in_b;
    o.both += in_a && in_b;
    o.either += in_a || in_b;
  }
  if (o.either > 0) o.iou = static_cast<double>(o.both) / o.either;
  return o;
}

RgbImage side_by_side(const RgbImage& a, const RgbImage& b) {
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument("side_by_side: image sizes differ");
  const int gap = 4;
  RgbImage out;
  out.width = 3 * a.width + 2 * gap;
  out.height = a.height;
  out.rgb.assign(3 * static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), 255);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const std::size_t src = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(a.width) + static_cast<std::size_t>(x));
      const std::size_t row = 3 * static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width);
      for (std::size_t k = 0; k < 3; ++k) {
        out.rgb[row + 3 * static_cast<std::size_t>(x) + k] = a.rgb[src + k];
        out.rgb[row + 3 * static_cast<std::size_t>(x + a.width + gap) + k] = b.rgb[src + k];
        const int d = std::min(255, 4 * std::abs(int(a.rgb[src + k]) - int(b.rgb[src + k])));
        out.rgb[row + 3 * static_cast<std::size_t>(x + 2 * (a.width + gap)) + k] = static_cast<uint8_t>(255 - d);
      }
    }
  return out;
}

}  // namespace vdc
