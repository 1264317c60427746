// Preview rendering of a frame through the scene's camera: z-buffered triangles, smooth-shaded
// (vertex normals) by a distant light at the eye, for looking at a shot and comparing two runs
// of it pixel by pixel (each pixel keeps its mesh, depth and shading normal for measuring). Not
// a production renderer: no clipping (a triangle with a corner behind the near plane is
// skipped), no antialiasing.
#pragma once
#include <array>
#include <vector>

#include "core/math.hpp"
#include "io/png.hpp"
#include "view/camera.hpp"

namespace vdc {

struct RenderMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<int32_t, 3>> faces;
  Vec3 colour = Vec3(0.7, 0.7, 0.7);  // base RGB in [0, 1]
  std::vector<Vec3> face_colours;     // per face, instead of `colour` when not empty
  bool wireframe = false;             // edges drawn dark over the shading, hidden where covered
};

// How far from a triangle's edge, in pixels, a wireframe's line reaches.
inline constexpr double kWireHalfWidth = 0.6;

// Per-pixel buffers in row-major order, `image.width` pixels a row.
struct RenderedFrame {
  RgbImage image;
  std::vector<int32_t> mesh;  // per pixel: the index of the nearest mesh, -1 for the background
  std::vector<double> depth;  // camera-space z of the nearest surface, +infinity for the background
  // The unit shading normal: the area-weighted vertex normals the shading interpolates,
  // interpolated the same way, normalised, and turned to face the camera (n . forward <= 0);
  // zero for the background.
  std::vector<Vec3> normal;
};

// The colour of a face with view factor v (Koh et al. 2014's coarsening factor): red at 1 (full resolution),
// through green to blue at 0.01 (the default out-of-frame factor) and below, on a log scale.
Vec3 view_factor_colour(double v);

// The image of `meshes` seen by `camera`, at `scale` times the camera's image size.
RenderedFrame render(const Camera& camera, const std::vector<RenderMesh>& meshes, double scale = 1.0);

}  // namespace vdc
