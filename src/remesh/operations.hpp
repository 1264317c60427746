// Local topology operations of adaptive remeshing (Narain et al. 2012, section 4): edge split,
// edge flip and edge collapse. Each has a can_* check; each returns what it added and removed,
// keeps boundaries, seams and handle nodes, carries attributes over and never inverts a face
// in material or world space.
#pragma once
#include <vector>

#include "core/mesh.hpp"

namespace vdc {

struct OpRecord {
  std::vector<NodeId> added_nodes, removed_nodes;
  std::vector<VertId> added_verts, removed_verts;
  std::vector<FaceId> added_faces, removed_faces;
  std::vector<EdgeId> added_edges, removed_edges;
};

// Splits edge e at parameter t from node 0 (0 < t < 1). The new node interpolates position and
// velocity; on a seam each side gets its own new vert. New faces copy the attributes of the
// face they came from, the two halves those of the old edge; the node attributes of the new node
// are the defaults. Always possible for a live edge.
bool can_split(const Mesh& mesh, EdgeId e);
OpRecord split_edge(Mesh& mesh, EdgeId e, double t = 0.5);

// Replaces interior edge e by the other diagonal of its two faces. Refused on boundaries and
// seams, when the other diagonal exists already, or when a new face would be inverted or
// degenerate in material space or flip its world normal against the old faces.
bool can_flip(const Mesh& mesh, EdgeId e);
OpRecord flip_edge(Mesh& mesh, EdgeId e);

// Removes node edge_node(e, remove) by moving it onto the other end. Refused when the removed
// node is a handle, lies on a seam or is a boundary corner, when it is on the boundary but e is
// not, when the link condition fails (the ends share a neighbour other than the opposite
// nodes of e), or when a new face would be inverted or degenerate in material space or flip
// its world normal.
bool can_collapse(const Mesh& mesh, EdgeId e, int remove);
OpRecord collapse_edge(Mesh& mesh, EdgeId e, int remove);

}  // namespace vdc
