#include "io/obj.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

#include "core/error.hpp"
#include "io/input_file.hpp"
#include "io/text_file.hpp"
#include "io/text_tokens.hpp"

namespace vdc {

namespace {

// The largest OBJ read: a mesh of some 20 million faces.
constexpr std::uintmax_t kMaxObjBytes = std::uintmax_t{1} << 30;

// OBJ indices are 1-based; negative ones count back from the last element read so far.
int32_t parse_index(const std::string& tok, std::size_t count, const std::string& what, const std::string& path, int line) {
  long long value = 0;
  auto res = std::from_chars(tok.data(), tok.data() + tok.size(), value);
  if (res.ec != std::errc() || res.ptr != tok.data() + tok.size() || value == 0)
    throw InputError(path, line_place(line), "bad " + what + " index '" + tok + "'");
  long long idx = value > 0 ? value - 1 : static_cast<long long>(count) + value;
  if (idx < 0 || idx >= static_cast<long long>(count))
    throw InputError(path, line_place(line), what + " index " + tok + " out of range (" + std::to_string(count) + " defined so far)");
  return static_cast<int32_t>(idx);
}

}  // namespace

MeshSource read_obj_source(const std::string& path, bool require_uv, std::vector<int>* face_lines) {
  std::istringstream in(read_input_text(path, kMaxObjBytes, "OBJ"));
  MeshSource src;
  std::vector<int> lines;
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    if (auto hash = raw.find('#'); hash != std::string::npos) raw.resize(hash);
    std::istringstream ss(raw);
    std::string tag;
    if (!(ss >> tag)) continue;
    std::vector<std::string> toks;
    for (std::string t; ss >> t;) toks.push_back(t);
    if (tag == "v") {
      if (toks.size() < 3) throw InputError(path, line_place(line), "'v' needs 3 coordinates");
      src.positions.emplace_back(parse_coordinate(toks[0], path, line), parse_coordinate(toks[1], path, line),
                                 parse_coordinate(toks[2], path, line));
    } else if (tag == "vt") {
      if (toks.size() < 2) throw InputError(path, line_place(line), "'vt' needs 2 coordinates");
      src.uvs.emplace_back(parse_coordinate(toks[0], path, line), parse_coordinate(toks[1], path, line));
    } else if (tag == "f") {
      if (toks.size() < 3) throw InputError(path, line_place(line), "a face needs at least 3 corners");
      std::vector<Corner> corners;
      for (const auto& t : toks) {
        auto slash = t.find('/');
        Corner c{parse_index(t.substr(0, slash), src.positions.size(), "position", path, line), -1};
        if (slash != std::string::npos) {
          auto rest = t.substr(slash + 1);
          auto slash2 = rest.find('/');
          auto uvtok = rest.substr(0, slash2);
          if (!uvtok.empty()) c.uv = parse_index(uvtok, src.uvs.size(), "texture", path, line);
        }
        if (c.uv < 0 && require_uv) throw InputError(path, line_place(line), "face corner '" + t + "' has no material-space (vt) index");
        corners.push_back(c);
      }
      // Polygons are split into a fan of triangles.
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
        src.faces.push_back({corners[0], corners[k], corners[k + 1]});
        lines.push_back(line);
      }
    }
    // Other statements (vn, o, g, s, usemtl, mtllib, l, p) carry nothing a garment needs.
  }
  if (in.bad()) throw InputError(path, "", "read error");
  if (src.faces.empty()) throw InputError(path, "", "no faces");
  if (!require_uv) with_canonical_uvs(src);  // obstacles have no pattern: vt, if any, is ignored
  if (face_lines) *face_lines = std::move(lines);
  return src;
}

Mesh read_obj(const std::string& path, bool require_uv) {
  std::vector<int> lines;
  MeshSource src = read_obj_source(path, require_uv, &lines);
  try {
    return build_mesh(src);
  } catch (const MeshBuildError& e) {
    std::string place = e.face >= 0 ? line_place(lines[static_cast<std::size_t>(e.face)]) : "";
    throw InputError(path, place, e.what());
  }
}

std::vector<Vec2> piece_offsets(const MeshSource& source) {
  const std::size_t n = source.uvs.size();
  std::vector<std::size_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& face : source.faces)
    for (int k = 1; k < 3; ++k) parent[root(static_cast<std::size_t>(face[static_cast<std::size_t>(k)].uv))] = root(static_cast<std::size_t>(face[0].uv));
  struct Piece {
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -Vec2::Constant(std::numeric_limits<double>::infinity());
    Vec2 offset = Vec2::Zero();
  };
  std::map<std::size_t, Piece> pieces;
  for (std::size_t i = 0; i < n; ++i) {
    Piece& piece = pieces[root(i)];
    piece.lo = piece.lo.cwiseMin(source.uvs[i]);
    piece.hi = piece.hi.cwiseMax(source.uvs[i]);
  }
  std::vector<Piece*> order;
  for (auto& [r, piece] : pieces) order.push_back(&piece);
  bool overlap = false;
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a + 1; b < order.size(); ++b)
      overlap = overlap || ((order[a]->lo.array() < order[b]->hi.array()).all() && (order[b]->lo.array() < order[a]->hi.array()).all());
  std::vector<Vec2> offsets(n, Vec2::Zero());
  if (!overlap) return offsets;
  // The layout reads the boxes rounded out to a 10 cm grid: remeshing moves a piece's box by a
  // few millimetres at most (a collapse on a curved outline), which leaves the rounded box, and
  // so every offset, as it was unless an edge of the box crosses a grid line.
  constexpr double kGrid = 0.1, kGap = 0.02;  // m
  for (Piece* piece : order) {
    for (int k = 0; k < 2; ++k) {
      piece->lo[k] = std::floor(piece->lo[k] / kGrid + 1e-9) * kGrid;
      piece->hi[k] = std::ceil(piece->hi[k] / kGrid - 1e-9) * kGrid;
    }
  }
  std::stable_sort(order.begin(), order.end(), [](const Piece* a, const Piece* b) {
    return std::tie(a->lo.x(), a->lo.y(), a->hi.x(), a->hi.y()) < std::tie(b->lo.x(), b->lo.y(), b->hi.x(), b->hi.y());
  });
  double cursor = 0;
  for (Piece* piece : order) {
    piece->offset = Vec2(cursor - piece->lo.x(), -piece->lo.y());
    cursor += piece->hi.x() - piece->lo.x() + kGap;
  }
  for (std::size_t i = 0; i < n; ++i) offsets[i] = pieces[root(i)].offset;
  return offsets;
}

bool write_obj(const Mesh& mesh, const std::string& path, const ObjWriting& how) {
  MeshSource src = mesh_source(mesh);
  if (how.material && how.separate_pieces) {
    const std::vector<Vec2> offsets = piece_offsets(src);
    for (std::size_t i = 0; i < src.uvs.size(); ++i) src.uvs[i] += offsets[i];
  }
  TextFile f(path);
  if (!f.ok()) return false;
  f.text(how.material ? "# vdcloth mesh: v world position, vt material position (m)\n" : "# vdcloth mesh: v world position (m)\n");
  for (const Vec3& p : src.positions)
    f.text("v ").fixed(p.x(), how.decimals).text(" ").fixed(p.y(), how.decimals).text(" ").fixed(p.z(), how.decimals).text("\n");
  if (how.material)
    for (const Vec2& u : src.uvs) f.text("vt ").fixed(u.x(), how.decimals).text(" ").fixed(u.y(), how.decimals).text("\n");
  for (const auto& face : src.faces) {
    f.text("f");
    for (const auto& corner : face) {
      f.text(" ").integer(corner.node + 1);
      if (how.material) f.text("/").integer(corner.uv + 1);
    }
    f.text("\n");
  }
  return f.close();
}

}  // namespace vdc
