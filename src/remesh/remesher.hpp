// The remeshing loop of Narain et al. 2012 (section 4) for a given sizing field: split every
// invalid edge (s^2 > 1, eq. 1 of Koh et al. 2014), largest first; flip to an anisotropically
// Delaunay mesh; collapse every edge whose removal leaves no edge above 1 - margin.
#pragma once
#include "core/mesh.hpp"
#include "remesh/crossing_guard.hpp"
#include "remesh/operations.hpp"

namespace vdc {

// Vert attribute holding the sizing tensor M (symmetric 2x2, material space, 1/m^2).
inline constexpr const char* kSizingAttr = "sizing";

struct RemeshOptions {
  double collapse_margin = 0.2;   // a collapse may not create an edge with s^2 > 1 - margin
  double flip_threshold = 1e-3;   // flip only when the Delaunay test fails by more than this
  int max_passes = 20;            // bound on split and flip sweeps
  // A node on a curved border (hem, neckline, a seam along an arc) may be collapsed when it lies
  // within this fraction of the chord that replaces it (can_collapse): 0.025 lets a border
  // coarsen to chords of a fifth of its radius of curvature, moving it by at most 2.5% of a chord
  // (0.5% of that radius).
  double border_sag = 0.025;
};

struct RemeshStats {
  int splits = 0, flips = 0, collapses = 0;
  int refused = 0;  // flips and collapses refused because they would have made cloth cross cloth
};

// s^2 of an edge: u_ij^T ((M_i + M_j) / 2) u_ij, the largest over the two sides of a seam.
double edge_size2(const Mesh& mesh, EdgeId e);

// True when edge e (interior, not a seam) fails the anisotropic Delaunay test by more than
// `threshold` (relative): the other diagonal is the better one in the metric.
bool should_flip(const Mesh& mesh, EdgeId e, double threshold);

// True when flipping e would give a diagonal with s^2 <= 1 (a flip never makes an invalid edge).
bool flip_keeps_valid(const Mesh& mesh, EdgeId e);

// Remeshes to the sizing field in the vert attribute kSizingAttr (Mat2). Split verts get the
// mean of the two ends' tensors. Node positions and velocities of new nodes are interpolated by
// the split. The mesh is left compact. Given `standing` (what the garments and obstacles were at
// the frame's start, the mesh being garment `self` of it), no flip or collapse adds a crossing
// (CrossingGuard); without, the remesher looks at the material space and the sizing only.
RemeshStats remesh(Mesh& mesh, const RemeshOptions& options = {}, const StandingSurfaces* standing = nullptr, int self = -1);

}  // namespace vdc
