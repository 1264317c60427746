// Byte buffers for the simulator's own binary files (checkpoints): plain values and arrays of
// them in the machine's byte order, read back with every length checked against what is left.
#pragma once
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace vdc {

// A buffer that ends before a read, or holds a length that cannot be right.
class BinaryFormatError : public std::runtime_error {
 public:
  BinaryFormatError(std::size_t offset, const std::string& problem)
      : std::runtime_error("byte " + std::to_string(offset) + ": " + problem), offset_(offset), problem_(problem) {}
  std::size_t offset() const { return offset_; }
  const std::string& problem() const { return problem_; }

 private:
  std::size_t offset_;
  std::string problem_;
};

// FNV-1a, 64 bits: the checksum that tells a damaged or cut-off file from a good one.
inline uint64_t fnv1a64(const char* data, std::size_t n, uint64_t h = 1469598103934665603ull) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

// Values are copied byte for byte: T must be a plain value (numbers, fixed-size Eigen
// matrices, mesh handles, arrays of those).
class BinaryWriter {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_destructible_v<T> && !std::is_pointer_v<T>, "plain values only");
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    value<uint64_t>(v.size());
    if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  template <class T>
  void nested(const std::vector<std::vector<T>>& v) {
    value<uint64_t>(v.size());
    for (const auto& inner : v) array(inner);
  }
  void string(const std::string& s) {
    value<uint64_t>(s.size());
    bytes_.append(s);
  }
  void raw(const char* data, std::size_t n) { bytes_.append(data, n); }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class BinaryReader {
 public:
  BinaryReader(const char* data, std::size_t size) : data_(data), size_(size) {}
  template <class T>
  T value() {
    need(sizeof(T), "a value");
    T v;
    std::memcpy(static_cast<void*>(&v), data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> array() {
    const std::size_t n = count(sizeof(T));
    std::vector<T> v(n);
    if (n > 0) std::memcpy(static_cast<void*>(v.data()), data_ + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return v;
  }
  template <class T>
  std::vector<std::vector<T>> nested() {
    const std::size_t n = count(sizeof(uint64_t));
    std::vector<std::vector<T>> v(n);
    for (auto& inner : v) inner = array<T>();
    return v;
  }
  std::string string() {
    const std::size_t n = count(1);
    std::string s(data_ + pos_, n);
    pos_ += n;
    return s;
  }
  void raw(char* out, std::size_t n) {
    need(n, "raw bytes");
    std::memcpy(out, data_ + pos_, n);
    pos_ += n;
  }
  std::size_t offset() const { return pos_; }
  bool at_end() const { return pos_ == size_; }
  [[noreturn]] void fail(const std::string& what) const { throw BinaryFormatError(pos_, what); }

 private:
  // A length prefix, checked against the bytes left at `element` bytes an element.
  std::size_t count(std::size_t element) {
    const auto n = value<uint64_t>();
    if (element > 0 && n > (size_ - pos_) / element) fail("a length of " + std::to_string(n) + " runs past the end");
    return static_cast<std::size_t>(n);
  }
  void need(std::size_t n, const char* what) {
    if (n > size_ - pos_) fail(std::string("the data ends before ") + what);
  }
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace vdc
