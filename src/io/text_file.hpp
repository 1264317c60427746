// Buffered writing of text files made of numbers (OBJ, PLY): doubles in their shortest form that
// reads back to the same value (std::to_chars), about four times faster than printf's %.17g.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace vdc {

class TextFile {
 public:
  // Opens `path` for writing; ok() is false if it could not be opened.
  explicit TextFile(const std::string& path);
  ~TextFile();
  TextFile(const TextFile&) = delete;
  TextFile& operator=(const TextFile&) = delete;

  TextFile& text(std::string_view s);
  TextFile& number(double value);                 // shortest exact form
  TextFile& number(double value, int precision);  // as printf's %.<precision>g, precision 1 to 17
  // Rounded to `decimals` (0 to 17) places after the point, without trailing zeros or a
  // negative zero; magnitudes of 1e15 and more, infinities and NaN in their shortest form.
  // decimals < 0: the shortest exact form, as number(value).
  TextFile& fixed(double value, int decimals);
  TextFile& integer(int64_t value);
  // Writes what is buffered and closes the file: false if anything failed since it was opened.
  bool close();
  bool ok() const { return file_ != nullptr && !failed_; }

 private:
  void flush();
  void make_room(std::size_t n);
  // Appends std::to_chars(…, args...) of one number.
  template <class... Args>
  TextFile& append(Args... args);
  std::FILE* file_ = nullptr;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
  bool failed_ = false;
};

}  // namespace vdc
