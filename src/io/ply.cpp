// ASCII PLY with a per-face value: the writer and its reader.
#include "io/ply.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "io/input_file.hpp"
#include "io/text_file.hpp"
#include "io/text_tokens.hpp"

namespace vdc {

bool write_ply_with_face_values(const Mesh& mesh, const std::string& path, const std::vector<PlyFaceProperty>& properties, int decimals) {
  TextFile out(path);
  if (!out.ok()) return false;
  std::vector<const Attribute<FaceTag, double>*> values;
  for (const PlyFaceProperty& p : properties) values.push_back(&mesh.face_attrs().get<double>(p.attribute));
  std::vector<int32_t> index(static_cast<std::size_t>(mesh.node_capacity()), -1);
  int32_t n = 0;
  for (NodeId v : mesh.nodes()) index[static_cast<std::size_t>(v.idx)] = n++;
  out.text("ply\nformat ascii 1.0\nelement vertex ").integer(n).text("\nproperty double x\nproperty double y\nproperty double z\n");
  out.text("element face ").integer(mesh.num_faces()).text("\nproperty list uchar int vertex_indices\n");
  for (const PlyFaceProperty& p : properties) out.text(p.whole ? "property uchar " : "property float ").text(p.name).text("\n");
  out.text("end_header\n");
  for (NodeId v : mesh.nodes()) {
    const Vec3& x = mesh.x(v);
    out.fixed(x.x(), decimals).text(" ").fixed(x.y(), decimals).text(" ").fixed(x.z(), decimals).text("\n");
  }
  for (FaceId f : mesh.faces()) {
    out.text("3");
    for (int k = 0; k < 3; ++k) out.text(" ").integer(index[static_cast<std::size_t>(mesh.face_node(f, k).idx)]);
    for (std::size_t p = 0; p < properties.size(); ++p) {
      const double v = (*values[p])[f];
      if (properties[p].whole) out.text(" ").integer(static_cast<int64_t>(std::clamp(std::round(v), 0.0, 255.0)));
      else out.text(" ").number(v, 6);
    }
    out.text("\n");
  }
  return out.close();
}

namespace {

// The largest PLY read: a mesh of some 20 million faces.
constexpr std::uintmax_t kMaxPlyBytes = std::uintmax_t{1} << 30;
constexpr int64_t kMaxElements = int64_t{1} << 28;
constexpr std::size_t kMaxFaceProperties = 8;

std::vector<std::string> tokens_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> tokens;
  for (std::string t; in >> t;) tokens.push_back(t);
  return tokens;
}

}  // namespace

PlyFaceValues read_ply_with_face_values(const std::string& path) {
  const std::string text = read_input_text(path, kMaxPlyBytes, "PLY");
  std::istringstream in(text);
  PlyFaceValues ply;
  std::string raw;
  int line = 0;
  auto next = [&]() -> std::vector<std::string> {  // the next line's tokens, comments skipped in the header
    while (std::getline(in, raw)) {
      ++line;
      std::vector<std::string> t = tokens_of(raw);
      if (t.empty() || t[0] != "comment") return t;
    }
    throw InputError(path, line_place(line), "the file ends early");
  };
  auto fail = [&](const std::string& problem) { throw InputError(path, line_place(line), problem); };
  if (next() != std::vector<std::string>{"ply"}) fail("not a PLY file (its first line is not 'ply')");
  if (next() != std::vector<std::string>{"format", "ascii", "1.0"}) fail("only 'format ascii 1.0' is read");
  std::vector<std::string> t = next();
  if (t.size() != 3 || t[0] != "element" || t[1] != "vertex") fail("expected 'element vertex N'");
  const int64_t vertices = parse_whole_number(t[2], kMaxElements, "vertex count", path, line);
  for (const char* axis : {"x", "y", "z"}) {
    t = next();
    if (t.size() != 3 || t[0] != "property" || t[2] != axis) fail(std::string("expected the vertex property ") + axis);
  }
  t = next();
  if (t.size() != 3 || t[0] != "element" || t[1] != "face") fail("expected 'element face N' after the vertex's x, y and z");
  const int64_t faces = parse_whole_number(t[2], kMaxElements, "face count", path, line);
  t = next();
  if (t.size() != 5 || t[0] != "property" || t[1] != "list" || t[4] != "vertex_indices") fail("expected 'property list uchar int vertex_indices'");
  std::vector<std::string> names;
  for (t = next(); t != std::vector<std::string>{"end_header"}; t = next()) {
    if (t.size() != 3 || t[0] != "property" || t[1] == "list") fail("expected a scalar face property or 'end_header'");
    if (std::find(names.begin(), names.end(), t[2]) != names.end()) fail("the face property '" + t[2] + "' twice");
    if (names.size() == kMaxFaceProperties) fail("more than " + std::to_string(kMaxFaceProperties) + " face properties");
    names.push_back(t[2]);
  }
  if (names.empty()) fail("expected a scalar face property after vertex_indices");
  ply.name = names.front();
  // Reserved as far as the file can hold them (a vertex line has at least 6 bytes, a face line
  // 10), not as far as a header may claim.
  ply.positions.reserve(std::min(static_cast<std::size_t>(vertices), text.size() / 6));
  for (int64_t i = 0; i < vertices; ++i) {
    t = next();
    if (t.size() != 3) fail("a vertex needs 3 coordinates");
    ply.positions.emplace_back(parse_coordinate(t[0], path, line), parse_coordinate(t[1], path, line), parse_coordinate(t[2], path, line));
  }
  ply.faces.reserve(std::min(static_cast<std::size_t>(faces), text.size() / 10));
  ply.values.reserve(ply.faces.capacity());
  for (int64_t i = 0; i < faces; ++i) {
    t = next();
    if (t.size() != 4 + names.size() || t[0] != "3")
      fail("a face needs '3', three vertex indices and its " + std::to_string(names.size()) + " value(s)");
    std::array<int32_t, 3> face{};
    for (int k = 0; k < 3; ++k)
      face[static_cast<std::size_t>(k)] = static_cast<int32_t>(parse_whole_number(t[static_cast<std::size_t>(k) + 1], vertices - 1, "vertex index", path, line));
    ply.faces.push_back(face);
    ply.values.push_back(parse_text_number(t[4], path, line));
    for (std::size_t p = 1; p < names.size(); ++p) ply.more[names[p]].push_back(parse_text_number(t[4 + p], path, line));
  }
  while (std::getline(in, raw)) {
    ++line;
    if (!tokens_of(raw).empty()) fail("more than the header's " + std::to_string(vertices) + " vertices and " + std::to_string(faces) + " faces");
  }
  if (faces == 0) throw InputError(path, "", "no faces");
  return ply;
}

}  // namespace vdc
