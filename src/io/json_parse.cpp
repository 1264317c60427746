#include "io/json_parse.hpp"

#include <vector>

#include "core/error.hpp"
#include "io/input_file.hpp"

namespace vdc {

namespace {

using Json = nlohmann::json;

// "line L, column C" of byte `offset` of `text` (both counted from 1).
std::string line_column(const std::string& text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// The byte at which arrays and objects first nest `depth` deep (the text's size if they never
// do), strings skipped.
std::size_t offset_of_depth(const std::string& text, int depth) {
  int open = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++open >= depth) return i;
    } else if (c == ']' || c == '}') {
      --open;
    }
  }
  return text.size();
}

// nlohmann's SAX events built into a value, as its own DOM parser does, keeping the key path of
// the value being read and refusing to open a container past kMaxJsonDepth.
class PathTrackingBuilder {
 public:
  bool null() { return put(nullptr); }
  bool boolean(bool v) { return put(v); }
  bool number_integer(Json::number_integer_t v) { return put(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return put(v); }
  bool number_float(Json::number_float_t v, const std::string&) { return put(v); }
  bool string(std::string& v) { return put(v); }
  bool binary(Json::binary_t& v) { return put(v); }
  bool start_object(std::size_t) { return open(Json::object()); }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool key(std::string& k) {
    levels_.back().key = k;
    return true;
  }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool parse_error(std::size_t position, const std::string&, const Json::exception& e) {
    failure_ = e.what();
    failure_id_ = e.id;
    failure_end_ = position;
    return false;
  }

  Json take() { return std::move(root_); }
  bool too_deep() const { return too_deep_; }
  const std::string& failure() const { return failure_; }
  int failure_id() const { return failure_id_; }
  std::size_t failure_end() const { return failure_end_; }  // the byte after the failing token
  // The key path of the value being read when parsing stopped: "" at the top level.
  std::string path() const {
    std::string p;
    for (std::size_t i = 0; i < levels_.size(); ++i) {
      const Json& v = *levels_[i].value;
      // An array's last element is the container above when one is open; else the next comes.
      if (v.is_array()) p += "[" + std::to_string(i + 1 < levels_.size() ? v.size() - 1 : v.size()) + "]";
      else if (!levels_[i].key.empty()) p += (p.empty() ? "" : ".") + levels_[i].key;
    }
    return p;
  }

 private:
  struct Level {
    Json* value;
    std::string key;  // an object's key whose value comes next
  };

  Json* slot() {
    if (levels_.empty()) return &root_;
    Level& top = levels_.back();
    if (top.value->is_array()) {
      top.value->push_back(nullptr);
      return &top.value->back();
    }
    return &(*top.value)[top.key];
  }
  template <class V>
  bool put(V&& v) {
    *slot() = Json(std::forward<V>(v));
    value_read();
    return true;
  }
  // An object's key is spent once its value is read: a failure before the next key is placed
  // by the object alone.
  void value_read() {
    if (!levels_.empty() && levels_.back().value->is_object()) levels_.back().key.clear();
  }
  bool open(Json empty) {
    if (static_cast<int>(levels_.size()) >= kMaxJsonDepth) {
      too_deep_ = true;
      return false;
    }
    Json* at = slot();
    *at = std::move(empty);
    levels_.push_back({at, ""});
    return true;
  }
  bool close() {
    levels_.pop_back();
    value_read();
    return true;
  }

  Json root_;
  std::vector<Level> levels_;
  bool too_deep_ = false;
  std::string failure_;
  int failure_id_ = 0;
  std::size_t failure_end_ = 0;
};

}  // namespace

JsonParse parse_json(const std::string& text) {
  PathTrackingBuilder builder;
  JsonParse out;
  if (Json::sax_parse(text, &builder)) {
    out.value = builder.take();
    return out;
  }
  out.place = shortened(builder.path(), 120);
  if (builder.too_deep()) {
    out.at = line_column(text, offset_of_depth(text, kMaxJsonDepth + 1));
    out.problem = "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth);
    return out;
  }
  const std::string& msg = builder.failure();
  if (builder.failure_id() == 406) {
    // "[json.exception.out_of_range.406] number overflow parsing '1e400'": the token, placed
    // by the key it was given for and where it starts, the parser having stopped just past it.
    const std::size_t open = msg.find("parsing '"), close = msg.rfind('\'');
    const std::string token = open == std::string::npos || close <= open + 9 ? "" : msg.substr(open + 9, close - open - 9);
    if (!token.empty() && builder.failure_end() >= token.size()) out.at = line_column(text, builder.failure_end() - token.size());
    out.problem = "number out of range" + (token.empty() ? std::string() : ": " + shortened(token));
    return out;
  }
  // nlohmann's message: "[json.exception.parse_error.101] parse error at line 3, column 5: ...".
  const std::size_t at = msg.find(" at line ");
  const std::size_t colon = at == std::string::npos ? std::string::npos : msg.find(": ", at);
  if (colon != std::string::npos) {
    out.at = msg.substr(at + 4, colon - at - 4);
    out.problem = "JSON syntax error: " + shortened(msg.substr(colon + 2));
  } else {
    out.problem = "JSON syntax error: " + shortened(msg);
  }
  return out;
}

std::string json_failure_place(const JsonParse& parsed) {
  if (parsed.place.empty()) return parsed.at;
  return parsed.at.empty() ? parsed.place : parsed.place + " (" + parsed.at + ")";
}

nlohmann::json read_json_or_null(const std::string& path) {
  try {
    JsonParse parsed = parse_json(read_input_text(path, kMaxJsonFileBytes, "JSON"));
    return parsed.problem.empty() ? std::move(parsed.value) : Json(nullptr);
  } catch (const InputError&) {
    return nullptr;
  }
}

}  // namespace vdc
