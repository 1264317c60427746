// ASCII PLY of a mesh's world positions and faces with values per face, for previews that
// colour faces by a value (in view mode the view factor, and what set it): written by a run,
// read back by `vdcloth render` and `vdcloth report`.
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "core/mesh.hpp"

namespace vdc {

// A face property written from a face attribute (double): a float, or a whole number (uchar).
struct PlyFaceProperty {
  std::string name, attribute;
  bool whole = false;
};

// Writes `path` with vertex x, y, z (node order) and faces with vertex_indices and each of
// `properties` taken from its face attribute; positions exact, or rounded to `decimals` places
// after the point. False on I/O failure.
bool write_ply_with_face_values(const Mesh& mesh, const std::string& path, const std::vector<PlyFaceProperty>& properties, int decimals = -1);

// A triangle mesh with values per face, as write_ply_with_face_values writes it: `name` and
// `values` the first face property, `more` the others by name.
struct PlyFaceValues {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<std::array<int32_t, 3>> faces;
  std::vector<double> values;
  std::map<std::string, std::vector<double>> more;
};

// Reads an ASCII PLY whose vertices are x, y, z and whose faces are triangles (a vertex_indices
// list) with one to eight scalar properties each; comments allowed. Throws InputError naming the
// file, the line and the problem.
PlyFaceValues read_ply_with_face_values(const std::string& path);

}  // namespace vdc
