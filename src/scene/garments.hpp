// Procedural garments for the project's figure (figure_skeleton, rest pose): pattern pieces in
// material space (metres), sewn along seams (a seam is a world node shared by pieces with
// their own material coordinates), placed around the body in its rest pose.
#pragma once
#include "core/mesh_build.hpp"

namespace vdc {

// A tube around the figure's vertical axis between two rings, a cylinder or a cone, cut from its
// developed pattern and sewn at the back: a skirt, a hakama, a belt. Outer side outwards.
struct TubeParams {
  int around = 48;             // segments around
  double top_height = 1.0;     // m
  double top_radius = 0.2;     // m
  double bottom_height = 0.1;  // m, below the top
  double bottom_radius = 0.4;  // m
  double cell = 0.03;          // m, target edge length down the pattern
  int rows = 0;                // rows down the pattern; 0: from cell
};
MeshSource make_tube(const TubeParams& p);

// A dress: a bodice (a tube from the waist to under the arms, sewn at the back), a flared skirt
// (a cone cut from an annular sector, sewn at the back and to the bodice at the waist) and two
// shoulder straps sewn to the bodice's top edge front and back. Outer side outwards.
struct DressParams {
  int around = 48;                // segments around the body (bodice and skirt)
  double bodice_radius = 0.19;    // m
  double waist_height = 1.05;     // m, where bodice and skirt meet
  double top_height = 1.32;       // m, the bodice's top edge, under the arms
  double hem_height = 0.45;       // m
  double hem_radius = 0.42;       // m, the skirt's flare
  double strap_rise = 0.20;       // m, how far the straps arc above the top edge
  double strap_x = 0.13;          // m, strap centre from the body's midline
  double cell = 0.03;             // m, target edge length along the straps and down the panels
  int bodice_rows = 0, skirt_rows = 0, strap_rows = 0;  // rows down each piece; 0: from cell
};
MeshSource make_dress(const DressParams& p = {});

// The same parameters with every row count that was 0 set from the cell size: the pieces
// make_tube and make_dress cut. A garment built from other sizes but these counts has the same
// nodes in the same order (so a handle chosen on one is the same node of the other).
TubeParams with_rows(TubeParams p);
DressParams with_rows(DressParams p);

inline MeshSource make_garment(const TubeParams& p) { return make_tube(p); }
inline MeshSource make_garment(const DressParams& p) { return make_dress(p); }

}  // namespace vdc
