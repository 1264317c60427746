// ASCII PLY of a mesh's world positions and faces with one float property per face, for
// previews that colour faces by a value (the view factor in view mode): written by a run, read
// back by `vdcloth render`.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/mesh.hpp"

namespace vdc {

// Writes `path` with vertex x, y, z (node order) and faces with vertex_indices and the float
// property `name` taken from the face attribute `attribute` (double); positions exact, or rounded
// to `decimals` places after the point. False on I/O failure.
bool write_ply_with_face_values(const Mesh& mesh, const std::string& path, const std::string& name, const std::string& attribute,
                                int decimals = -1);

// A triangle mesh with one value per face, as write_ply_with_face_values writes it.
struct PlyFaceValues {
  std::string name;  // the face property's name
  std::vector<Vec3> positions;
  std::vector<std::array<int32_t, 3>> faces;
  std::vector<double> values;
};

// Reads an ASCII PLY whose vertices are x, y, z and whose faces are triangles (a vertex_indices
// list) with one scalar property each; comments allowed. Throws InputError naming the file, the
// line and the problem.
PlyFaceValues read_ply_with_face_values(const std::string& path);

}  // namespace vdc
