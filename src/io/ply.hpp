// ASCII PLY of a mesh's world positions and faces with one float property per face, for
// previews that colour faces by a value (the view factor in view mode).
#pragma once
#include <string>

#include "core/mesh.hpp"

namespace vdc {

// Writes `path` with vertex x, y, z (node order) and faces with vertex_indices and the float
// property `name` taken from the face attribute `attribute` (double); positions exact, or rounded
// to `decimals` places after the point. False on I/O failure.
bool write_ply_with_face_values(const Mesh& mesh, const std::string& path, const std::string& name, const std::string& attribute,
                                int decimals = -1);

}  // namespace vdc
