// A run's record and frames as the report page's scripts.
#include "app/report_data.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "core/error.hpp"
#include "io/input_file.hpp"
#include "io/json_reader.hpp"
#include "io/obj.hpp"
#include "io/ply.hpp"
#include "io/text_tokens.hpp"
#include "output/camera_export.hpp"

namespace vdc {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr std::uintmax_t kMaxTableBytes = std::uintmax_t{1} << 30;

bool is_file(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::vector<std::string> split(const std::string& line, char at) {
  std::vector<std::string> cells(1);
  for (const char c : line) {
    if (c == at) cells.emplace_back();
    else if (c != '\r') cells.back() += c;
  }
  return cells;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

// A stats.csv cell: a number, or null for "nan" and "inf" (a run that failed part-way may have
// written them in its last row, and its report is the one most wanted).
json stats_cell(const std::string& cell, const std::string& path, int line) {
  std::string lower;
  for (const char c : cell) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "nan" || lower == "-nan" || lower == "inf" || lower == "-inf" || lower == "+inf") return nullptr;
  return parse_text_number(cell, path, line);
}

// stats.csv as {column: [numbers]}: every row as wide as the header, every cell a number.
json read_stats_columns(const std::string& path) {
  const std::vector<std::string> lines = lines_of(read_input_text(path, kMaxTableBytes, "CSV"));
  if (lines.empty()) throw InputError(path, "line 1", "empty: no header");
  const std::vector<std::string> names = split(lines[0], ',');
  if (names.empty() || names[0] != "frame") throw InputError(path, "line 1", "the header does not start with frame");
  json columns = json::object();
  for (const std::string& name : names) columns[name] = json::array();
  for (std::size_t k = 1; k < lines.size(); ++k) {
    if (lines[k].empty()) continue;
    const int line = static_cast<int>(k + 1);
    const std::vector<std::string> cells = split(lines[k], ',');
    if (cells.size() != names.size())
      throw InputError(path, line_place(line), std::to_string(cells.size()) + " cells where the header names " + std::to_string(names.size()));
    for (std::size_t c = 0; c < cells.size(); ++c) columns[names[c]].push_back(stats_cell(cells[c], path, line));
  }
  return columns;
}

// vdcloth check's result in the run directory: its status line and its table of crossings.
json read_check(const std::string& dir) {
  const std::string status_path = dir + "/check_status.txt", csv_path = dir + "/check.csv";
  if (!is_file(status_path) || !is_file(csv_path)) return nullptr;
  std::istringstream status(read_input_text(status_path, 4096, "text"));
  int checked = 0, crossing = 0, every = 0;
  if (!(status >> checked >> crossing >> every)) throw InputError(status_path, "line 1", "expected three whole numbers (frames checked, with crossings, every)");
  json rows = json::array();
  const std::vector<std::string> lines = lines_of(read_input_text(csv_path, kMaxTableBytes, "CSV"));
  for (std::size_t k = 1; k < lines.size(); ++k) {
    if (lines[k].empty()) continue;
    const int line = static_cast<int>(k + 1);
    const std::vector<std::string> cells = split(lines[k], ',');
    if (cells.size() != 4) throw InputError(csv_path, line_place(line), "expected frame,mesh,other,face_pairs");
    rows.push_back({{"frame", parse_whole_number(cells[0], 1'000'000'000, "frame", csv_path, line)},
                    {"mesh", cells[1]},
                    {"other", cells[2]},
                    {"face_pairs", parse_whole_number(cells[3], int64_t{1} << 40, "face pairs", csv_path, line)}});
  }
  return {{"frames_checked", checked}, {"frames_with_crossings", crossing}, {"every", every}, {"rows", rows}};
}

void append_little_endian(std::string& bytes, const void* value, std::size_t size) {
  const auto* b = static_cast<const unsigned char*>(value);
  if constexpr (std::endian::native == std::endian::little) {
    bytes.append(reinterpret_cast<const char*>(b), size);
  } else {
    for (std::size_t k = size; k-- > 0;) bytes.push_back(static_cast<char>(b[k]));
  }
}

std::string float32_bytes(const std::vector<Vec3>& positions) {
  std::string bytes;
  bytes.reserve(12 * positions.size());
  for (const Vec3& p : positions)
    for (int k = 0; k < 3; ++k) {
      const auto f = static_cast<float>(p[k]);
      append_little_endian(bytes, &f, sizeof f);
    }
  return bytes;
}

std::string uint32_bytes(const std::vector<std::array<int32_t, 3>>& faces) {
  std::string bytes;
  bytes.reserve(12 * faces.size());
  for (const auto& face : faces)
    for (const int32_t v : face) {
      const auto u = static_cast<uint32_t>(v);
      append_little_endian(bytes, &u, sizeof u);
    }
  return bytes;
}

std::string float32_bytes(const std::vector<double>& values) {
  std::string bytes;
  bytes.reserve(4 * values.size());
  for (const double v : values) {
    const auto f = static_cast<float>(v);
    append_little_endian(bytes, &f, sizeof f);
  }
  return bytes;
}

}  // namespace

std::string base64(const std::string& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const uint32_t n = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
    for (int shift = 18; shift >= 0; shift -= 6) text.push_back(kDigits[(n >> shift) & 63]);
  }
  if (const std::size_t rest = bytes.size() - i; rest > 0) {
    uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
    if (rest == 2) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    text.push_back(kDigits[(n >> 18) & 63]);
    text.push_back(kDigits[(n >> 12) & 63]);
    text.push_back(rest == 2 ? kDigits[(n >> 6) & 63] : '=');
    text.push_back('=');
  }
  return text;
}

// The run's cameras: camera.json (its scene's one camera), or each camera_NAME.json of a scene
// with several, in the scene's order (their "index").
json read_cameras(const std::string& run_dir) {
  json cameras = json::array();
  for (const std::string& path : camera_files_in(run_dir, ".json")) cameras.push_back(JsonValue::load_file(path).raw());
  std::stable_sort(cameras.begin(), cameras.end(), [](const json& a, const json& b) { return a.value("index", 0) < b.value("index", 0); });
  return cameras;
}

json read_run_record(const std::string& run_dir) {
  const std::string summary_path = run_dir + "/summary.json", stats_path = run_dir + "/stats.csv";
  if (!is_file(summary_path)) throw InputError(summary_path, "", "missing: not the directory of a vdcloth run");
  if (!is_file(stats_path)) throw InputError(stats_path, "", "missing: not the directory of a vdcloth run");
  json record;
  record["label"] = run_dir;
  record["summary"] = JsonValue::load_file(summary_path).raw();
  if (!record["summary"].is_object()) throw InputError(summary_path, "", "not a JSON object");
  record["stats"] = read_stats_columns(stats_path);
  record["cameras"] = read_cameras(run_dir);
  record["camera"] = record["cameras"].empty() ? json(nullptr) : record["cameras"].front();
  record["check"] = read_check(run_dir);
  const std::string log_path = run_dir + "/" + kLogFile;
  record["log"] = is_file(log_path) ? json(lines_of(read_input_text(log_path, kMaxTableBytes, "text"))) : json(nullptr);
  return record;
}

void write_frame_script(std::ostream& out, int run_index, int frame, const FrameFiles& files, json& topology) {
  json meshes = json::array();
  for (const auto& [name, path] : files) {
    const bool cloth = name.rfind("cloth_", 0) == 0;
    // A cloth's PLY (view runs) holds its positions and triangles with a factor a face, as
    // `vdcloth render --colour view` draws it; otherwise the OBJ.
    const std::string factors = fs::path(path).replace_extension(".ply").string();
    json mesh = {{"name", name}, {"cloth", cloth}, {"view", nullptr}};
    std::string faces;
    if (cloth && is_file(factors)) {
      const PlyFaceValues ply = read_ply_with_face_values(factors);
      mesh["positions"] = base64(float32_bytes(ply.positions));
      faces = base64(uint32_bytes(ply.faces));
      mesh["view"] = base64(float32_bytes(ply.values));
      if (const auto reason = ply.more.find("reason"); reason != ply.more.end()) {
        std::string bytes;
        for (const double r : reason->second) bytes.push_back(static_cast<char>(std::clamp(r, 0.0, 255.0)));
        mesh["reason"] = base64(bytes);
      }
    } else {
      const MeshSource source = read_obj_source(path, false);
      mesh["positions"] = base64(float32_bytes(source.positions));
      faces = base64(uint32_bytes(position_triangles(source)));
    }
    mesh["faces"] = faces;
    if (!cloth) {
      if (!topology.contains(name)) topology[name] = faces;
      if (topology[name] == faces) mesh["faces"] = nullptr;
    }
    meshes.push_back(std::move(mesh));
  }
  out << "vdcloth.addFrame(" << run_index << ", " << frame << ", " << meshes.dump() << ");\n";
}

}  // namespace vdc
