// PNG output of 8-bit RGB images (PNG specification, ISO/IEC 15948), rows filtered by their
// difference from the row above and deflated by zlib.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace vdc {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // row by row from the top, 3 bytes a pixel
};

// The PNG file of `image` as bytes.
std::vector<uint8_t> encode_png(const RgbImage& image);
// Writes it to `path`; false when the file cannot be written.
bool write_png(const RgbImage& image, const std::string& path);

}  // namespace vdc
