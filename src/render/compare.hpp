// Pixel comparison of two renders of the same shot (a view-dependent run against its adaptive
// run, say): how much of the image the cloth covers in each, how well the two cloth silhouettes
// overlap, and how different the pixels are where either shows cloth.
#pragma once
#include <vector>

#include "render/rasterizer.hpp"

namespace vdc {

struct RenderComparison {
  int cloth_pixels_a = 0, cloth_pixels_b = 0;
  double cloth_iou = 1;       // |A and B| / |A or B| of the cloth pixels (1 when neither has any)
  double mean_abs_diff = 0;   // mean over the pixels where either shows cloth, of the mean
                              // absolute channel difference, 0 to 255
};

// `cloth_a[m]` says whether mesh m of frame a is cloth (likewise b). Same image sizes.
RenderComparison compare_renders(const RenderedFrame& a, const std::vector<char>& cloth_a, const RenderedFrame& b,
                                 const std::vector<char>& cloth_b);

// A, B and their difference (absolute, four times amplified) side by side.
RgbImage side_by_side(const RgbImage& a, const RgbImage& b);

}  // namespace vdc
