// Preview rendering: the PNG encoding checked by decoding it with zlib; the rasterizer against
// the analytic size of a square's image, a z-buffer occlusion, a tilted plane's depth and
// normal, face colours and the wireframe's band; the comparison against a known overlap.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "io/png.hpp"
#include "render/compare.hpp"
#include "render/rasterizer.hpp"

namespace vdc {
namespace {

uint32_t read_u32(const std::vector<uint8_t>& b, std::size_t at) {
  return (uint32_t(b[at]) << 24) | (uint32_t(b[at + 1]) << 16) | (uint32_t(b[at + 2]) << 8) | uint32_t(b[at + 3]);
}

// Walks the chunks, checks each CRC, inflates IDAT and undoes each row's filter: the pixels
// come back exactly, in a fraction of their raw size for a picture with flat areas.
TEST(Png, ChunksCarryValidChecksumsAndTheDeflatedRowsHoldThePixels) {
  RgbImage image;
  image.width = 200;
  image.height = 120;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int k = 0; k < 3; ++k) image.rgb.push_back(static_cast<uint8_t>(x < 100 ? 200 + k : (x * 7 + y * 3 + k * 50) % 251));
  const std::vector<uint8_t> png = encode_png(image);
  const uint8_t signature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  ASSERT_EQ(std::memcmp(png.data(), signature, 8), 0);
  std::vector<uint8_t> idat;
  std::vector<std::string> types;
  for (std::size_t at = 8; at < png.size();) {
    const uint32_t length = read_u32(png, at);
    const std::string type(png.begin() + static_cast<std::ptrdiff_t>(at + 4), png.begin() + static_cast<std::ptrdiff_t>(at + 8));
    types.push_back(type);
    EXPECT_EQ(read_u32(png, at + 8 + length), ::crc32(0, png.data() + at + 4, 4 + length)) << type;
    if (type == "IHDR") {
      EXPECT_EQ(read_u32(png, at + 8), 200u);
      EXPECT_EQ(read_u32(png, at + 12), 120u);
      EXPECT_EQ(png[at + 16], 8);  // bit depth
      EXPECT_EQ(png[at + 17], 2);  // truecolour
    }
    if (type == "IDAT") idat.assign(png.begin() + static_cast<std::ptrdiff_t>(at + 8), png.begin() + static_cast<std::ptrdiff_t>(at + 8 + length));
    at += 12 + length;
  }
  EXPECT_EQ(types, (std::vector<std::string>{"IHDR", "IDAT", "IEND"}));
  const std::size_t row = 3 * 200;
  std::vector<uint8_t> raw(120 * (row + 1));
  uLongf size = raw.size();
  ASSERT_EQ(uncompress(raw.data(), &size, idat.data(), static_cast<uLong>(idat.size())), Z_OK);
  ASSERT_EQ(size, raw.size());
  EXPECT_LT(idat.size(), raw.size() / 2) << "half the picture is one colour";
  std::vector<uint8_t> pixels;
  for (std::size_t y = 0; y < 120; ++y) {
    const uint8_t filter = raw[y * (row + 1)];
    ASSERT_TRUE(filter == 0 || filter == 2) << "row " << y;
    for (std::size_t i = 0; i < row; ++i) {
      const uint8_t above = filter == 2 && y > 0 ? pixels[(y - 1) * row + i] : 0;
      pixels.push_back(static_cast<uint8_t>(raw[y * (row + 1) + 1 + i] + above));
    }
  }
  EXPECT_EQ(pixels, image.rgb);
}

// At (0, 0, 5) looking at the origin, 40 degrees, 320 x 240 pixels.
Camera test_camera() { return Camera{.position = Vec3(0, 0, 5), .target = Vec3::Zero(), .fov_y_degrees = 40, .width = 320, .height = 240}; }

// An axis-aligned square of half-width s at depth z in front of test_camera, as two triangles.
RenderMesh square(double s, double z, const Vec3& colour) {
  RenderMesh m;
  m.positions = {{-s, -s, z}, {s, -s, z}, {s, s, z}, {-s, s, z}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  m.colour = colour;
  return m;
}

int pixels_of(const RenderedFrame& f, int32_t mesh) { return static_cast<int>(std::count(f.mesh.begin(), f.mesh.end(), mesh)); }

TEST(Rasterizer, ASquareFacingTheCameraCoversItsProjectedArea) {
  const Camera camera = test_camera();
  const RenderedFrame f = render(camera, {square(0.5, 0, Vec3(1, 0, 0))});
  // Side in pixels: focal length times 1 m over 5 m.
  const double side = camera.focal_pixels() * 1.0 / 5.0;
  const int covered = pixels_of(f, 0);
  EXPECT_GE(covered, static_cast<int>(std::floor(side - 1) * std::floor(side - 1)));
  EXPECT_LE(covered, static_cast<int>(std::ceil(side + 1) * std::ceil(side + 1)));
  // Facing the light at the eye: full brightness, red; the background elsewhere.
  const std::size_t centre = 3 * (120 * 320 + 160);
  EXPECT_EQ(f.image.rgb[centre], 255);
  EXPECT_EQ(f.image.rgb[centre + 1], 0);
  EXPECT_EQ(f.mesh[0], -1);
}

TEST(Rasterizer, TheNearerSurfaceHidesTheFartherInEitherOrder) {
  const Camera camera = test_camera();
  const RenderMesh near = square(0.2, 1, Vec3(0, 1, 0)), far = square(0.5, 0, Vec3(1, 0, 0));
  for (const bool near_first : {true, false}) {
    const RenderedFrame f = render(camera, near_first ? std::vector<RenderMesh>{near, far} : std::vector<RenderMesh>{far, near});
    const int32_t near_index = near_first ? 0 : 1;
    EXPECT_EQ(f.mesh[120 * 320 + 160], near_index);
    const double near_side = camera.focal_pixels() * 0.4 / 4.0;
    EXPECT_NEAR(pixels_of(f, near_index), near_side * near_side, 2 * near_side + 2);
  }
}

TEST(Rasterizer, TrianglesBehindTheNearPlaneAreNotDrawnAndScaleSizesTheImage) {
  Camera camera = test_camera();
  const RenderedFrame behind = render(camera, {square(0.5, 6, Vec3(1, 1, 1))});
  EXPECT_EQ(pixels_of(behind, 0), 0);
  const RenderedFrame half = render(camera, {square(0.5, 0, Vec3(1, 1, 1))}, 0.5);
  EXPECT_EQ(half.image.width, 160);
  EXPECT_EQ(half.image.height, 120);
  const double side = 0.5 * camera.focal_pixels() / 5.0;
  EXPECT_NEAR(pixels_of(half, 0), side * side, 2 * side + 2);
}

std::size_t pixel_at(const Camera& camera, const Vec3& x) {
  const Vec2 p = camera.project(x);
  return static_cast<std::size_t>(std::floor(p.y())) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(std::floor(p.x()));
}

// Per-face colours replace the mesh's: each triangle of the square in its own, at full
// brightness where it faces the camera.
TEST(Rasterizer, FaceColoursColourTheirOwnFaces) {
  const Camera camera = test_camera();
  RenderMesh m = square(0.5, 0, Vec3(1, 1, 1));
  m.face_colours = {Vec3(1, 0, 0), Vec3(0, 0, 1)};  // (0, 1, 2) below the diagonal x = y, (0, 2, 3) above
  const RenderedFrame f = render(camera, {m});
  const std::size_t below = 3 * pixel_at(camera, Vec3(0.25, -0.1, 0)), above = 3 * pixel_at(camera, Vec3(-0.25, 0.1, 0));
  EXPECT_EQ(f.image.rgb[below], 255);
  EXPECT_EQ(f.image.rgb[below + 2], 0);
  EXPECT_EQ(f.image.rgb[above], 0);
  EXPECT_EQ(f.image.rgb[above + 2], 255);
}

// The wireframe darkens the pixels within kWireHalfWidth of an edge to 30%: on the diagonal
// (pixel (160, 119), whose centre lies on it), not 16 pixels away from every edge; their number
// is the band's area, the inner half of the outline plus both sides of the diagonal.
TEST(Rasterizer, WireframeDarkensABandAlongTheEdges) {
  const Camera camera = test_camera();
  RenderMesh m = square(0.5, 0, Vec3(1, 1, 1));
  const RenderedFrame plain = render(camera, {m});
  m.wireframe = true;
  const RenderedFrame wired = render(camera, {m});
  const std::size_t diagonal = 3 * (119 * 320 + 160), inside = 3 * pixel_at(camera, Vec3(0.25, -0.1, 0));
  EXPECT_EQ(plain.image.rgb[diagonal], 255);
  EXPECT_NEAR(wired.image.rgb[diagonal], 0.3 * 255, 1);
  EXPECT_EQ(wired.image.rgb[inside], 255);
  int dark = 0;
  for (std::size_t i = 0; i < wired.mesh.size(); ++i) dark += wired.mesh[i] == 0 && wired.image.rgb[3 * i] < 128;
  const double side = camera.focal_pixels() / 5.0;
  const double band = 4 * side * kWireHalfWidth + std::sqrt(2.0) * side * 2 * kWireHalfWidth;
  EXPECT_NEAR(dark, band, 0.25 * band);
  EXPECT_EQ(pixels_of(wired, 0), pixels_of(plain, 0));
}

// The view factor's colours: red at 1, green at 0.1, blue at 0.01 and below (also for 0 and NaN).
TEST(Rasterizer, ViewFactorColoursRunFromRedThroughGreenToBlue) {
  const Vec3 red(0.88, 0.28, 0.20), green(0.28, 0.72, 0.35), blue(0.20, 0.32, 0.85);
  const struct {
    double v;
    Vec3 colour;
  } cases[] = {{1.0, red}, {5.0, red}, {0.1, green}, {0.01, blue}, {0.0, blue}, {std::nan(""), blue},
               {std::sqrt(0.1), Vec3(0.58, 0.50, 0.275)}};  // halfway from green to red on the log scale
  for (const auto& c : cases) EXPECT_LT((view_factor_colour(c.v) - c.colour).norm(), 1e-12) << c.v;
}

// A sheet folded along x = 0: the left half faces the camera, the right half turns 60 degrees
// away. Smooth shading leaves no step in brightness at the fold (flat shading would step from
// full to 62%), and the face turned away is darker.
TEST(Rasterizer, ShadingIsSmoothAcrossAFold) {
  const Camera camera = test_camera();
  RenderMesh fold;
  const double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);
  fold.positions = {{-0.5, -0.5, 0}, {0, -0.5, 0}, {0, 0.5, 0}, {-0.5, 0.5, 0}, {0.5 * c, -0.5, -0.5 * s}, {0.5 * c, 0.5, -0.5 * s}};
  fold.faces = {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}};
  fold.colour = Vec3(1, 1, 1);
  const RenderedFrame f = render(camera, {fold});
  auto red = [&](int x) { return static_cast<int>(f.image.rgb[3 * static_cast<std::size_t>(120 * 320 + x)]); };
  ASSERT_EQ(f.mesh[static_cast<std::size_t>(120 * 320 + 159)], 0);
  ASSERT_EQ(f.mesh[static_cast<std::size_t>(120 * 320 + 160)], 0);
  EXPECT_LE(std::abs(red(159) - red(160)), 12) << "left of the fold " << red(159) << ", right " << red(160);
  EXPECT_GT(red(130), red(175)) << "the face turned away is darker";
}

// A square turned 30 degrees about x (its normal tilted up towards +y), in either winding: at a
// pixel, the depth is where the pixel's ray meets the plane, and the normal is the plane's, turned
// to face the camera. The background has infinite depth and no normal.
TEST(Rasterizer, DepthAndNormalBuffersHoldThePlaneSeenAtEachPixel) {
  const Camera camera = test_camera();
  const double tilt = M_PI / 6;
  const Vec3 along_x(1, 0, 0), along_slope(0, std::cos(tilt), -std::sin(tilt)), plane_normal(0, std::sin(tilt), std::cos(tilt));
  RenderMesh plane;
  for (const Vec2& corner : {Vec2(-2, -2), Vec2(2, -2), Vec2(2, 2), Vec2(-2, 2)}) plane.positions.push_back(corner.x() * along_x + corner.y() * along_slope);
  for (const bool reversed : {false, true}) {
    plane.faces = reversed ? std::vector<std::array<int32_t, 3>>{{0, 2, 1}, {0, 3, 2}} : std::vector<std::array<int32_t, 3>>{{0, 1, 2}, {0, 2, 3}};
    const RenderedFrame f = render(camera, {plane});
    ASSERT_EQ(f.depth.size(), 320u * 240u);
    ASSERT_EQ(f.normal.size(), 320u * 240u);
    for (const auto& [x, y] : {std::pair{200, 80}, std::pair{100, 170}, std::pair{160, 120}}) {
      // The camera looks down -z from (0, 0, 5) with x to the right and y up: the ray through the
      // pixel's centre, scaled to advance 1 in depth.
      const Vec3 ray((x + 0.5 - 160) / camera.focal_pixels(), -(y + 0.5 - 120) / camera.focal_pixels(), -1);
      const double depth = -plane_normal.dot(camera.position) / plane_normal.dot(ray);
      const auto i = static_cast<std::size_t>(y * 320 + x);
      ASSERT_EQ(f.mesh[i], 0) << x << "," << y;
      EXPECT_NEAR(f.depth[i], depth, 1e-9) << x << "," << y;
      EXPECT_NEAR((f.normal[i] - plane_normal).norm(), 0, 1e-12) << x << "," << y << " reversed " << reversed;
    }
    EXPECT_EQ(f.mesh[0], -1);
    EXPECT_EQ(f.depth[0], std::numeric_limits<double>::infinity());
    EXPECT_EQ(f.normal[0], Vec3::Zero());
  }
}

TEST(RenderComparison, IdenticalRendersMatchAndAShiftedSquareOverlapsAsExpected) {
  const Camera camera = test_camera();
  const RenderedFrame a = render(camera, {square(0.5, 0, Vec3(0.8, 0.3, 0.2))});
  const RenderComparison same = compare_renders(a, {1}, a, {1});
  EXPECT_EQ(same.cloth_iou, 1.0);
  EXPECT_EQ(same.mean_abs_diff, 0.0);
  EXPECT_EQ(same.cloth_pixels_a, pixels_of(a, 0));
  // The same square moved sideways by a quarter of its side: overlap 3/4 over union 5/4.
  RenderMesh moved = square(0.5, 0, Vec3(0.8, 0.3, 0.2));
  for (Vec3& p : moved.positions) p.x() += 0.25;
  const RenderedFrame b = render(camera, {moved});
  const RenderComparison shifted = compare_renders(a, {1}, b, {1});
  EXPECT_NEAR(shifted.cloth_iou, 0.6, 0.02);
  // Not cloth (a body, say): no cloth pixels, nothing to compare.
  const RenderComparison body = compare_renders(a, {0}, b, {0});
  EXPECT_EQ(body.cloth_pixels_a, 0);
  EXPECT_EQ(body.cloth_iou, 1.0);
  // One mesh at a time: mesh 0 of a against mesh 0 of b is the square and its shifted copy,
  // pixel counts those of each; a mesh a frame lacks (-1) shows nowhere.
  const MeshOverlap square_moved = compare_mesh(a, 0, b, 0);
  EXPECT_EQ(square_moved.pixels_a, pixels_of(a, 0));
  EXPECT_EQ(square_moved.pixels_b, pixels_of(b, 0));
  EXPECT_EQ(square_moved.pixels_a + square_moved.pixels_b, square_moved.both + square_moved.either);
  EXPECT_EQ(square_moved.iou, shifted.cloth_iou);
  const MeshOverlap missing = compare_mesh(a, 0, b, -1);
  EXPECT_EQ(missing.pixels_b, 0);
  EXPECT_EQ(missing.both, 0);
  EXPECT_EQ(missing.either, pixels_of(a, 0));
  EXPECT_EQ(missing.iou, 0.0);
  EXPECT_EQ(compare_mesh(a, -1, b, -1).iou, 1.0) << "shown by neither: alike";
  const RgbImage panels = side_by_side(a.image, b.image);
  EXPECT_EQ(panels.width, 3 * 320 + 8);
  EXPECT_EQ(panels.height, 240);
}

}  // namespace
}  // namespace vdc
