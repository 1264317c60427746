// Local topology operations of adaptive remeshing (Narain et al. 2012, section 4): edge split,
// edge flip and edge collapse. Each has a can_* check; each returns what it added and removed,
// keeps handle nodes and the pattern's corners, moves border nodes (boundary or seam) only
// along their border, carries attributes over and never inverts a face in material or world
// space.
#pragma once
#include <array>
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

// Removes node edge_node(e, remove) by moving it onto the other end; on a seam, each of its
// verts merges into the other end's vert in the same panel. Refused when the removed node is a
// handle; when it is on the pattern's border (a boundary or a seam) but e is not a border edge,
// or it is a corner there (other than two border edges of one kind, or more than two panels), or
// the border bends through it: its distance from the chord between its border neighbours above
// `border_sag` times that chord, in any of its panels (0: straight to round-off); when the
// link condition fails (the ends share a neighbour other than the opposite nodes of e); or when a
// new face would be inverted or degenerate in material space or flip its world normal.
bool can_collapse(const Mesh& mesh, EdgeId e, int remove, double border_sag = 0);
OpRecord collapse_edge(Mesh& mesh, EdgeId e, int remove, double border_sag = 0);

// What a flip or a collapse would do, found before it is done: the faces it would remove and the
// faces it would make, as node triples (their world positions are the nodes', which neither
// operation moves). Call only where can_flip or can_collapse holds.
struct OpPreview {
  std::vector<FaceId> removed;
  std::vector<std::array<NodeId, 3>> made;
};
OpPreview preview_flip(const Mesh& mesh, EdgeId e);
OpPreview preview_collapse(const Mesh& mesh, EdgeId e, int remove);

// The vert of node n that shares a face with vert v (n's vert in v's panel), or invalid.
VertId vert_beside(const Mesh& mesh, VertId v, NodeId n);
// The vert that vert vr of the removed node merges into when e collapses.
VertId collapse_target(const Mesh& mesh, EdgeId e, int remove, VertId vr);

}  // namespace vdc
