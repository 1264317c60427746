// Wavefront OBJ for garments: `v` world position, `vt` material-space position in metres, `f v/vt`.
// A position used with several `vt` is a seam.
#pragma once
#include <string>
#include <vector>

#include "core/mesh.hpp"
#include "core/mesh_build.hpp"

namespace vdc {

// Reads the arrays of an OBJ file. Throws InputError naming the file and line.
// When `require_uv` is false (obstacles), `vt` is optional and ignored: every face gets the same
// canonical material triangle. Garments must have `vt`.
MeshSource read_obj_source(const std::string& path, bool require_uv, std::vector<int>* face_lines = nullptr);

// Reads and validates a garment mesh. Throws InputError naming the file, the line and the problem.
Mesh read_obj(const std::string& path, bool require_uv = true);

// How write_obj writes a mesh: with material-space `vt` (garments) or without (obstacles, whose
// material triangles mean nothing), and its coordinates exact (the shortest form that reads back
// to the same double) or rounded to `decimals` places after the point.
struct ObjWriting {
  bool material = true;
  int decimals = -1;  // -1: exact
  // Pattern pieces (the parts of material space that faces connect) whose bounding boxes
  // overlap are written side by side instead, each moved as a whole (its shape, in metres,
  // unchanged): a texture can then be painted on `vt`. Off: `vt` is material space as it is.
  bool separate_pieces = false;
};

// Per material-space vert of `source`, how far separate_pieces moves it: zero everywhere when
// no two pieces' bounding boxes overlap; otherwise the pieces in a row along u, ordered by their
// boxes rounded out to 10 cm, each box so rounded starting 2 cm after the last, at v = 0. The
// rounding keeps the offsets from frame to frame though remeshing moves a box by millimetres.
std::vector<Vec2> piece_offsets(const MeshSource& source);

// Writes v, vt and f v/vt (v and f v without material) so that read_obj gives back the same mesh,
// to the rounding asked for. Returns false on I/O failure.
bool write_obj(const Mesh& mesh, const std::string& path, const ObjWriting& how = {});

}  // namespace vdc
