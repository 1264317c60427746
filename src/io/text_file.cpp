// Buffered text output with std::to_chars.
#include "io/text_file.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

namespace vdc {

namespace {
constexpr std::size_t kBufferBytes = 1 << 16;
constexpr std::size_t kLongestNumber = 40;  // a double (shortest, %.17g, or below 1e15 with 17 decimals), or an int64, fits
}  // namespace

TextFile::TextFile(const std::string& path) : file_(std::fopen(path.c_str(), "w")), buffer_(kBufferBytes) {}

TextFile::~TextFile() {
  if (file_) std::fclose(file_);
}

void TextFile::flush() {
  if (file_ && used_ > 0 && std::fwrite(buffer_.data(), 1, used_, file_) != used_) failed_ = true;
  used_ = 0;
}

void TextFile::make_room(std::size_t n) {
  if (used_ + n <= buffer_.size()) return;
  flush();
  if (n > buffer_.size()) buffer_.resize(n);
}

TextFile& TextFile::text(std::string_view s) {
  make_room(s.size());
  std::memcpy(buffer_.data() + used_, s.data(), s.size());
  used_ += s.size();
  return *this;
}

template <class... Args>
TextFile& TextFile::append(Args... args) {
  make_room(kLongestNumber);
  used_ = static_cast<std::size_t>(std::to_chars(buffer_.data() + used_, buffer_.data() + buffer_.size(), args...).ptr - buffer_.data());
  return *this;
}

TextFile& TextFile::number(double value) { return append(value); }

TextFile& TextFile::number(double value, int precision) { return append(value, std::chars_format::general, precision); }

TextFile& TextFile::fixed(double value, int decimals) {
  if (decimals < 0 || !(std::abs(value) < 1e15)) return append(value);
  make_room(kLongestNumber);
  char* const begin = buffer_.data() + used_;
  char* end = std::to_chars(begin, buffer_.data() + buffer_.size(), value, std::chars_format::fixed, decimals).ptr;
  if (decimals > 0) {
    while (end[-1] == '0') --end;
    if (end[-1] == '.') --end;
  }
  if (end - begin == 2 && begin[0] == '-' && begin[1] == '0') *begin = '0', end = begin + 1;
  used_ = static_cast<std::size_t>(end - buffer_.data());
  return *this;
}

TextFile& TextFile::integer(int64_t value) { return append(value); }

bool TextFile::close() {
  if (!file_) return false;
  flush();
  const bool ok = !failed_ && std::ferror(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  return ok && closed;
}

}  // namespace vdc
