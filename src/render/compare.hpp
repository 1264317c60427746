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

// How one mesh shows in two renders (a garment in a view run and in its adaptive run): its
// pixels in each (where it is the nearest surface), those showing it in both and in either,
// and their intersection over union (1 when neither shows it).
struct MeshOverlap {
  int pixels_a = 0, pixels_b = 0;
  int both = 0, either = 0;
  double iou = 1;
};

// Mesh `mesh_a` of frame a against mesh `mesh_b` of frame b (-1: a mesh the frame lacks, no
// pixel). Same image sizes.
MeshOverlap compare_mesh(const RenderedFrame& a, int32_t mesh_a, const RenderedFrame& b, int32_t mesh_b);

// A, B and their difference (absolute, four times amplified) side by side.
RgbImage side_by_side(const RgbImage& a, const RgbImage& b);

}  // namespace vdc
