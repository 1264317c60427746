#include "io/input_file.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.hpp"

namespace vdc {

std::string read_input_text(const std::string& path, std::uintmax_t max_bytes, const std::string& kind) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "", fs::exists(path, ec) ? "not a regular file" : "file not found");
  if (fs::file_size(path, ec) > max_bytes)
    throw InputError(path, "", kind + " files are read up to " + std::to_string(max_bytes >> 20) + " MiB: this one is larger");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open file");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, "", "cannot read file");
  if (const void* nul = std::memchr(text.data(), '\0', text.size()); nul != nullptr)
    throw InputError(path, "byte " + std::to_string(static_cast<const char*>(nul) - text.data() + 1),
                     "a NUL byte: " + kind + " files are text");
  return text;
}

}  // namespace vdc
