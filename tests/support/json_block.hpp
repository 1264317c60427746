// A scene block given as text, read as the scene file `scene.json` would hold it at a key path,
// and the one-line error its parser throws.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "io/json_reader.hpp"

namespace vdc::test {

inline JsonValue json_block(const std::string& text, const std::string& path) {
  return JsonValue(nlohmann::json::parse(text), "scene.json", path);
}

// The message `parse` throws as InputError, or "" when it throws none.
template <class Parse>
std::string input_error(Parse&& parse) {
  try {
    parse();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace vdc::test
