#include "io/text_tokens.hpp"

#include <charconv>
#include <cmath>

#include "core/error.hpp"

namespace vdc {

std::string line_place(int line) { return "line " + std::to_string(line); }

double parse_text_number(const std::string& token, const std::string& path, int line) {
  double value = 0;
  const char* begin = token.data() + (token.size() > 1 && token[0] == '+' ? 1 : 0);  // from_chars refuses a leading '+'
  auto res = std::from_chars(begin, token.data() + token.size(), value);
  if (res.ec != std::errc() || res.ptr != token.data() + token.size() || !std::isfinite(value))
    throw InputError(path, line_place(line), "expected a number, found '" + token + "'");
  return value;
}

double parse_coordinate(const std::string& token, const std::string& path, int line) {
  constexpr double kFarthest = 1e5;
  const double value = parse_text_number(token, path, line);
  if (std::abs(value) > kFarthest) throw InputError(path, line_place(line), "coordinate " + token + " is beyond 100 km (coordinates are metres)");
  return value;
}

int64_t parse_whole_number(const std::string& token, int64_t largest, const std::string& what, const std::string& path, int line) {
  int64_t value = -1;
  auto res = std::from_chars(token.data(), token.data() + token.size(), value);
  if (res.ec != std::errc() || res.ptr != token.data() + token.size() || value < 0 || value > largest)
    throw InputError(path, line_place(line), "bad " + what + " '" + token + "' (0 to " + std::to_string(largest) + ")");
  return value;
}

}  // namespace vdc
