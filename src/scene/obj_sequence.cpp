// OBJ-sequence obstacles: one file a frame, linear interpolation between frames.
#include "scene/obj_sequence.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/mesh_build.hpp"
#include "io/obj.hpp"

namespace vdc {

std::vector<Vec3> interpolate_frames(const std::vector<std::vector<Vec3>>& frames, double frame_time, double t) {
  const double s = std::max(0.0, t / frame_time);
  const auto last = static_cast<double>(frames.size() - 1);
  if (s >= last) return frames.back();
  const auto i = static_cast<std::size_t>(std::floor(s));
  const double w = s - static_cast<double>(i);
  std::vector<Vec3> out(frames[i].size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = (1 - w) * frames[i][k] + w * frames[i + 1][k];
  return out;
}

std::vector<std::string> sequence_files(const std::string& pattern, int first, int count) {
  // Exactly one conversion: %d or %0Nd.
  const auto pct = pattern.find('%');
  if (pct == std::string::npos) throw InputError(pattern, "", "the file pattern needs one %d field (for example body.%04d.obj)");
  auto end = pct + 1;
  while (end < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[end]))) ++end;
  if (end >= pattern.size() || pattern[end] != 'd' || pattern.find('%', end) != std::string::npos)
    throw InputError(pattern, "", "the file pattern needs exactly one %d field (for example body.%04d.obj)");
  const std::string spec = pattern.substr(pct, end + 1 - pct);
  std::vector<std::string> files;
  for (int i = first; i < first + count; ++i) {
    char number[64];
    std::snprintf(number, sizeof number, spec.c_str(), i);
    files.push_back(pattern.substr(0, pct) + number + pattern.substr(end + 1));
  }
  return files;
}

ObjSequence load_obj_sequence(const std::vector<std::string>& files, double frame_time) {
  ObjSequence seq;
  seq.frame_time = frame_time;
  MeshSource first = read_obj_source(files.front(), false);
  ObstacleSurface surface = [&] {
    try {
      return build_obstacle_mesh(first);
    } catch (const MeshBuildError& e) {
      throw InputError(files.front(), "", std::string("cannot be a collision surface: ") + e.what());
    }
  }();
  seq.mesh = std::move(surface.mesh);
  seq.repairs = surface.repairs.summary();
  for (const std::string& file : files) {
    MeshSource s = file == files.front() ? first : read_obj_source(file, false);
    if (s.positions.size() != first.positions.size() || s.faces.size() != first.faces.size())
      throw InputError(file, "", "has " + std::to_string(s.positions.size()) + " vertices and " + std::to_string(s.faces.size()) +
                                     " faces; the sequence's first file " + files.front() + " has " +
                                     std::to_string(first.positions.size()) + " and " + std::to_string(first.faces.size()));
    for (std::size_t f = 0; f < s.faces.size(); ++f)
      for (std::size_t c = 0; c < 3; ++c)
        if (s.faces[f][c].node != first.faces[f][c].node)
          throw InputError(file, "face " + std::to_string(f + 1), "lists other vertices than the same face of " + files.front());
    std::vector<Vec3> x;  // by node: each the file's position the repaired surface copies
    for (int32_t i : surface.source) {
      const Vec3& p = s.positions[static_cast<std::size_t>(i)];
      if (!p.allFinite()) throw InputError(file, "", "position " + std::to_string(i + 1) + " is not finite");
      x.push_back(p);
    }
    seq.frames.push_back(std::move(x));
  }
  return seq;
}

}  // namespace vdc
