// An obstacle's surface as artists' characters come: several meshes, loose parts, open borders,
// edges shared by three faces or more, vertices where separate sheets touch, faces wound against
// their neighbours. Collisions need none of it closed (repulsion and untangling work by face
// normals, continuous collision by triangles), only each edge between two faces at most, wound
// the same way, which build_mesh checks. The repair makes that so without moving a point:
// faces with no area dropped, faces turned to agree with their neighbours, edges of three faces
// or more cut open, and a vertex copied for each separate fan of faces around it.
#pragma once
#include <string>
#include <vector>

#include "core/mesh_build.hpp"

namespace vdc {

// What a repair found and did.
struct SurfaceRepairs {
  int dropped_faces = 0;      // no area, a repeated corner, or a copy of another face
  int turned_faces = 0;       // wound against their neighbours (or a closed part inside out)
  int cut_edges = 0;          // shared by three faces or more, or where a part cannot agree (a Moebius strip)
  int copied_vertices = 0;    // extra copies for vertices with separate fans
  int open_edges = 0;         // on a border once repaired
  int parts = 0;              // connected pieces once repaired
  // "" when the surface needed nothing and is one closed piece; else one sentence of findings.
  std::string summary() const;
};

struct RepairedSurface {
  MeshSource mesh;              // the faces kept, some turned over, indexing `positions` below
  std::vector<int32_t> source;  // per position of mesh: the input position it copies
  SurfaceRepairs repairs;
};

// Throws MeshBuildError for a surface with no face left or a position that is not finite.
RepairedSurface repair_surface(const MeshSource& surface);

// An obstacle's mesh from its surface as given: repaired, with the canonical material triangles
// an obstacle has (it has no pattern); its node i copies the surface's position source[i].
struct ObstacleSurface {
  Mesh mesh;
  std::vector<int32_t> source;
  SurfaceRepairs repairs;
};
ObstacleSurface build_obstacle_mesh(const MeshSource& surface);

}  // namespace vdc
