// JSON text to a value: nesting bounded, and a failure placed by line, column and key path.
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace vdc {

// Arrays and objects inside one another, at most. Copying or destroying a value recurses as deep
// as it nests, so a deeper text is refused rather than read (a scene of 200,000 nested arrays
// under one key overflowed the stack); no input of the project's nests past a dozen.
constexpr int kMaxJsonDepth = 100;
// The largest JSON file read.
constexpr std::uintmax_t kMaxJsonFileBytes = std::uintmax_t{256} << 20;

struct JsonParse {
  nlohmann::json value;  // the text's value when `problem` is empty, null otherwise
  std::string place;     // where it fails: the key path when known ("solver.tolerance"), else ""
  std::string at;        // and the text's "line L, column C"
  std::string problem;   // why; empty when the text is read
};

JsonParse parse_json(const std::string& text);

// The strict readers' failure as one place: "key path (line L, column C)", or the line and
// column alone where no key is known.
std::string json_failure_place(const JsonParse& parsed);

// A file the project wrote itself (a run's summary.json) as a value, for readers that can do
// without it: null where it is missing, unreadable, over 256 MiB or not JSON as parse_json takes it.
nlohmann::json read_json_or_null(const std::string& path);

}  // namespace vdc
