#include "io/json_reader.hpp"

#include <cmath>
#include <limits>

#include "io/input_file.hpp"
#include "io/json_parse.hpp"

namespace vdc {

JsonValue JsonValue::load_file(const std::string& path) {
  const std::string text = read_input_text(path, kMaxJsonFileBytes, "JSON");
  JsonParse parsed = parse_json(text);
  if (!parsed.problem.empty()) throw InputError(path, json_failure_place(parsed), parsed.problem);
  return JsonValue(std::move(parsed.value), path, "");
}

JsonValue::JsonValue(nlohmann::json value, std::string file, std::string path)
    : value_(std::move(value)), file_(std::move(file)), path_(std::move(path)) {}

void JsonValue::fail(const std::string& problem) const { throw InputError(file_, path_.empty() ? "top level" : path_, problem); }

std::string JsonValue::type_name() const { return value_.type_name(); }

void JsonValue::expect_object() const {
  if (!value_.is_object()) fail("expected an object, found " + type_name());
}

bool JsonValue::has(const std::string& key) const { return value_.is_object() && value_.contains(key); }

JsonValue JsonValue::at(const std::string& key) const {
  expect_object();
  std::string child = path_.empty() ? key : path_ + "." + key;
  if (!value_.contains(key)) throw InputError(file_, child, "required key is missing");
  return JsonValue(value_.at(key), file_, child);
}

std::optional<JsonValue> JsonValue::find(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return at(key);
}

std::vector<JsonValue> JsonValue::items() const {
  if (!value_.is_array()) fail("expected an array, found " + type_name());
  std::vector<JsonValue> out;
  for (std::size_t i = 0; i < value_.size(); ++i)
    out.emplace_back(value_[i], file_, path_ + "[" + std::to_string(i) + "]");
  return out;
}

std::vector<std::pair<std::string, JsonValue>> JsonValue::members() const {
  expect_object();
  std::vector<std::pair<std::string, JsonValue>> out;
  for (const auto& [key, v] : value_.items()) out.emplace_back(key, JsonValue(v, file_, path_.empty() ? key : path_ + "." + key));
  return out;
}

void JsonValue::only_keys(std::initializer_list<const char*> allowed) const {
  expect_object();
  for (const auto& [key, v] : value_.items()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw InputError(file_, path_.empty() ? key : path_ + "." + key, "unknown key (expected one of: " + list + ")");
    }
  }
}

double JsonValue::number() const {
  if (!value_.is_number()) fail("expected a number, found " + type_name());
  double d = value_.get<double>();
  if (!std::isfinite(d)) fail("expected a finite number");
  return d;
}

double JsonValue::positive() const {
  double d = number();
  if (!(d > 0)) fail("must be greater than 0, found " + value_.dump());
  return d;
}

double JsonValue::non_negative() const {
  double d = number();
  if (d < 0) fail("must not be negative, found " + value_.dump());
  return d;
}

long long JsonValue::integer() const {
  if (!value_.is_number_integer()) fail("expected an integer, found " + (value_.is_number() ? value_.dump() : type_name()));
  if (value_.is_number_unsigned() && value_.get<unsigned long long>() > static_cast<unsigned long long>(std::numeric_limits<long long>::max()))
    fail("integer " + value_.dump() + " is out of range");
  return value_.get<long long>();
}

std::string JsonValue::string() const {
  if (!value_.is_string()) fail("expected a string, found " + type_name());
  return value_.get<std::string>();
}

bool JsonValue::boolean() const {
  if (!value_.is_boolean()) fail("expected true or false, found " + type_name());
  return value_.get<bool>();
}

Vec2 JsonValue::vec2() const {
  if (!value_.is_array() || value_.size() != 2) fail("expected an array of 2 numbers");
  auto it = items();
  return {it[0].number(), it[1].number()};
}

Vec3 JsonValue::vec3() const {
  if (!value_.is_array() || value_.size() != 3) fail("expected an array of 3 numbers");
  auto it = items();
  return {it[0].number(), it[1].number(), it[2].number()};
}

double JsonValue::number_or(const std::string& key, double fallback) const { return has(key) ? at(key).number() : fallback; }
double JsonValue::positive_or(const std::string& key, double fallback) const { return has(key) ? at(key).positive() : fallback; }
double JsonValue::non_negative_or(const std::string& key, double fallback) const {
  return has(key) ? at(key).non_negative() : fallback;
}
long long JsonValue::integer_or(const std::string& key, long long fallback) const { return has(key) ? at(key).integer() : fallback; }
std::string JsonValue::string_or(const std::string& key, const std::string& fallback) const {
  return has(key) ? at(key).string() : fallback;
}
bool JsonValue::boolean_or(const std::string& key, bool fallback) const { return has(key) ? at(key).boolean() : fallback; }
Vec3 JsonValue::vec3_or(const std::string& key, const Vec3& fallback) const { return has(key) ? at(key).vec3() : fallback; }

}  // namespace vdc
