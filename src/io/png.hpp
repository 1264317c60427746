// PNG output of 8-bit RGB images (PNG specification, ISO/IEC 15948): the pixels go into zlib
// "stored" blocks, uncompressed, so no compression library is needed.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace vdc {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // row by row from the top, 3 bytes a pixel
};

// CRC-32 of the PNG chunks (ISO 3309 polynomial, reflected) and zlib's Adler-32 (RFC 1950).
uint32_t crc32(const uint8_t* data, std::size_t size, uint32_t crc = 0);
uint32_t adler32(const uint8_t* data, std::size_t size);

// The PNG file of `image` as bytes.
std::vector<uint8_t> encode_png(const RgbImage& image);
// Writes it to `path`; false when the file cannot be written.
bool write_png(const RgbImage& image, const std::string& path);

}  // namespace vdc
