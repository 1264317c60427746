// Drawing a run's written frames for render and fidelity, finding the frames runs share, and
// writing tables under a temporary name.
#include "app/run_frames.hpp"

#include <filesystem>
#include <iterator>

#include "core/error.hpp"
#include "io/obj.hpp"
#include "io/ply.hpp"

namespace vdc {

namespace fs = std::filesystem;

namespace {

const Vec3 kClothPalette[] = {{0.80, 0.25, 0.22}, {0.93, 0.72, 0.20}, {0.22, 0.42, 0.78}, {0.30, 0.65, 0.38},
                              {0.60, 0.35, 0.70}, {0.90, 0.50, 0.25}, {0.25, 0.70, 0.75}, {0.85, 0.40, 0.60}};

}  // namespace

DrawnFrame draw_frame(const Camera& camera, const FrameFiles& files, double scale, const DrawStyle& style) {
  std::vector<RenderMesh> meshes;
  DrawnFrame drawn;
  std::size_t garments = 0;
  for (const auto& [key, path] : files) {  // in name order
    const bool cloth = key.rfind("cloth_", 0) == 0;
    RenderMesh mesh;
    const fs::path factors = fs::path(path).replace_extension(".ply");
    std::error_code ec;
    if (cloth && style.view_colours && fs::exists(factors, ec)) {
      const PlyFaceValues ply = read_ply_with_face_values(factors.string());
      mesh.positions = ply.positions;
      mesh.faces = ply.faces;
      for (double v : ply.values) mesh.face_colours.push_back(view_factor_colour(v));
    } else {
      const MeshSource source = read_obj_source(path, false);
      mesh.positions = source.positions;
      mesh.faces = position_triangles(source);
    }
    mesh.colour = !cloth ? Vec3(0.78, 0.74, 0.70) : style.view_colours ? view_factor_colour(1.0) : kClothPalette[garments % std::size(kClothPalette)];
    garments += cloth ? 1 : 0;
    mesh.wireframe = cloth && style.wireframe;
    meshes.push_back(std::move(mesh));
    drawn.cloth.push_back(cloth);
    drawn.names.push_back(key);
  }
  drawn.pixels = render(camera, meshes, scale);
  return drawn;
}

std::vector<int> frames_in_common(const std::vector<const std::map<int, FrameFiles>*>& runs) {
  std::vector<int> common;
  if (runs.empty()) return common;
  for (const auto& [frame, files] : *runs.front()) {
    bool everywhere = true;
    for (const auto* run : runs) everywhere = everywhere && run->count(frame) > 0;
    if (everywhere) common.push_back(frame);
  }
  return common;
}

std::vector<fs::path> create_output_directory(const std::string& dir) {
  std::vector<fs::path> made;
  std::error_code ec;
  for (fs::path p = fs::path(dir).lexically_normal(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    made.push_back(p);
    if (p == p.parent_path()) break;
  }
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "", "cannot create output directory: " + ec.message());
  return made;
}

PartialTable::PartialTable(std::string path) : path_(std::move(path)) {
  std::error_code ec;
  fs::remove(path_, ec);
  stream_.open(path_ + ".partial");
  if (!stream_) throw OutputError(path_ + ".partial", "cannot write");
}

void PartialTable::finish() {
  stream_.close();
  if (stream_.fail()) throw OutputError(path_ + ".partial", "cannot write");
  std::error_code ec;
  fs::rename(path_ + ".partial", path_, ec);
  if (ec) throw OutputError(path_, "cannot write: " + ec.message());
}

void PartialTable::discard() {
  stream_.close();
  std::error_code ec;
  fs::remove(path_ + ".partial", ec);
}

}  // namespace vdc
