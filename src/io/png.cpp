// PNG writer (ISO/IEC 15948): signature, IHDR, one IDAT of the rows deflated by zlib, IEND.
#include "io/png.hpp"

#include <zlib.h>

#include <fstream>
#include <new>

namespace vdc {

namespace {

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<uint8_t>(v >> shift));
}

// Length, type, data and the CRC of type and data.
void put_chunk(std::vector<uint8_t>& out, const char* type, const std::vector<uint8_t>& data) {
  put_u32(out, static_cast<uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_u32(out, static_cast<uint32_t>(::crc32(0, out.data() + start, static_cast<uInt>(out.size() - start))));
}

}  // namespace

std::vector<uint8_t> encode_png(const RgbImage& image) {
  // Filter type 2 (up) before each row: each byte less the one above it (0 above the first
  // row), so the flat background and smooth shading become runs of zeros for deflate.
  const auto row = static_cast<std::size_t>(3 * image.width);
  std::vector<uint8_t> raw;
  raw.reserve(static_cast<std::size_t>(image.height) * (row + 1));
  for (int y = 0; y < image.height; ++y) {
    raw.push_back(2);
    const uint8_t* line = image.rgb.data() + static_cast<std::size_t>(y) * row;
    const uint8_t* above = y > 0 ? line - row : nullptr;
    for (std::size_t i = 0; i < row; ++i) raw.push_back(static_cast<uint8_t>(line[i] - (above != nullptr ? above[i] : 0)));
  }
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<uint8_t> z(size);
  if (compress2(z.data(), &size, raw.data(), static_cast<uLong>(raw.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
    throw std::bad_alloc();  // zlib's only failure with a large enough buffer is memory
  z.resize(size);

  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<uint8_t> header;
  put_u32(header, static_cast<uint32_t>(image.width));
  put_u32(header, static_cast<uint32_t>(image.height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, adaptive filters, no interlace
  put_chunk(png, "IHDR", header);
  put_chunk(png, "IDAT", z);
  put_chunk(png, "IEND", {});
  return png;
}

bool write_png(const RgbImage& image, const std::string& path) {
  const std::vector<uint8_t> bytes = encode_png(image);
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(file);
}

}  // namespace vdc
