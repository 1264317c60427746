// Builds a Mesh from indexed arrays (what an OBJ file holds) and checks that it is a valid garment:
// manifold edges and vertices, consistent orientation, no degenerate face in either space.
#pragma once
#include <array>
#include <vector>

#include "core/error.hpp"
#include "core/mesh.hpp"

namespace vdc {

struct Corner {
  int32_t node;  // index into positions
  int32_t uv;    // index into uvs
  friend bool operator==(const Corner&, const Corner&) = default;
};

struct MeshSource {
  std::vector<Vec3> positions;  // world space
  std::vector<Vec2> uvs;        // material space, metres
  std::vector<std::array<Corner, 3>> faces;
};

// Raised by build_mesh for a face it cannot accept; `face` indexes MeshSource::faces.
class MeshBuildError : public TopologyError {
 public:
  MeshBuildError(int32_t face_index, const std::string& what) : TopologyError(what), face(face_index) {}
  int32_t face;
};

// Positions that no face uses are dropped. A vert is a distinct (node, uv) pair, in order of first
// use; nodes keep the order of `positions`.
Mesh build_mesh(const MeshSource& src);

// The arrays of a mesh in its own order: the same faces, nodes and uvs (uvs numbered in the mesh's
// vert order, i.e. first use, which may differ from the arrays that built it).
MeshSource mesh_source(const Mesh& mesh);

// A size_x by size_y metre sheet split into nx by ny cells of two triangles each (diagonals
// alternate to avoid a directional bias). Material space is (x, y) in [0, size]; world space is
// (u, 0, -v), so the outer side faces +y.
MeshSource make_grid(double size_x, double size_y, int nx, int ny);

// The faces of a source as triples of position indices (its world-space triangles), for the
// checks and drawings that need no material space.
std::vector<std::array<int32_t, 3>> position_triangles(const MeshSource& source);

// A closed sphere of the given radius centred at the origin: an icosahedron subdivided
// `subdivisions` times, outward-facing. Obstacles have no pattern: every face gets the same
// canonical material triangle (see with_canonical_uvs).
MeshSource make_icosphere(double radius, int subdivisions);

// Volume enclosed by a closed triangle mesh with positions x (by position index): positive when
// its faces are counter-clockwise seen from outside (divergence theorem over the faces).
double enclosed_volume(const MeshSource& mesh, const std::vector<Vec3>& x);

// Replaces the uvs of a mesh that has no material space (an obstacle) by one canonical
// counter-clockwise triangle per face, which every check of build_mesh accepts.
void with_canonical_uvs(MeshSource& src);

}  // namespace vdc
