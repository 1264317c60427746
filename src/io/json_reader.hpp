// Strict reading of JSON input files: every value knows its file and key path
// (e.g. garments[0].material), unknown keys and wrong types are errors that name them.
#pragma once
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/math.hpp"

namespace vdc {

class JsonValue {
 public:
  // Parses a file (parse_json); syntax errors, numbers out of range and nesting too deep become
  // InputError with the key path and "line L, column C". Only regular files of at most
  // kMaxJsonFileBytes are read.
  static JsonValue load_file(const std::string& path);
  JsonValue(nlohmann::json value, std::string file, std::string path);

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  const nlohmann::json& raw() const { return value_; }

  bool is_object() const { return value_.is_object(); }
  bool is_string() const { return value_.is_string(); }
  bool is_array() const { return value_.is_array(); }
  bool has(const std::string& key) const;
  JsonValue at(const std::string& key) const;  // required key
  std::optional<JsonValue> find(const std::string& key) const;
  std::vector<JsonValue> items() const;  // array elements
  std::vector<std::pair<std::string, JsonValue>> members() const;  // object members, in key order
  // Fails on any key of this object not in `allowed`.
  void only_keys(std::initializer_list<const char*> allowed) const;
  void expect_object() const;

  double number() const;
  double positive() const;      // > 0
  double non_negative() const;  // >= 0
  long long integer() const;
  std::string string() const;
  bool boolean() const;
  Vec2 vec2() const;
  Vec3 vec3() const;

  // Optional members with defaults.
  double number_or(const std::string& key, double fallback) const;
  double positive_or(const std::string& key, double fallback) const;
  double non_negative_or(const std::string& key, double fallback) const;
  long long integer_or(const std::string& key, long long fallback) const;
  std::string string_or(const std::string& key, const std::string& fallback) const;
  bool boolean_or(const std::string& key, bool fallback) const;
  Vec3 vec3_or(const std::string& key, const Vec3& fallback) const;

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  std::string type_name() const;
  nlohmann::json value_;
  std::string file_, path_;
};

}  // namespace vdc
