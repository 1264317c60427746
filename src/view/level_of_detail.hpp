// Physics level of detail for cloth no camera resolves (an extension of Koh, Narain and O'Brien
// 2014, section 3.2's screen-space floor): where a garment's folds stay finer than the floor
// for every camera over the coming frames, the view would only keep its faces at the floor, so
// its sizing and remeshing may wait a few frames (ViewParams::far_remesh_every).
#pragma once
#include <vector>

#include "core/math.hpp"
#include "view/view_factor.hpp"

namespace vdc {

// Where a garment can be: a ball around its nodes now, and its fastest node's speed.
struct GarmentReach {
  Vec3 centre = Vec3::Zero();
  double radius = 0;  // m
  double speed = 0;   // m/s
};

// The ball around `x` (the garment's node positions) and the fastest of `v` (their velocities).
GarmentReach garment_reach(const std::vector<Vec3>& x, const std::vector<Vec3>& v);

// The most pixels a metre of anything in the ball (centre, radius) spans on `camera`'s image
// where it is in frame: f sqrt(1 + tx^2 + ty^2) / z, the pinhole's largest stretch at the image's
// corner (tx, ty the half-angles' tangents) at the ball's nearest depth z (not nearer than the
// near plane); 0 when the ball lies wholly outside the frustum.
double most_pixels_per_metre(const Camera& camera, const Frustum& frustum, const Vec3& centre, double radius);

// Whether cloth within `reach` is beyond what every camera of `windows` (each camera's eq. 4
// window from now, the garment moving at most at its speed) resolves: folds of p.fold_length span less
// than half of p.l_min on screen wherever it can be in frame (fold_weight 1 there, view_sizing.hpp),
// and, with a ceiling p.l_max, an edge as long as `size_max` would stay under it. Never so
// without a floor or a fold length. The lens's blur floors are left out (they only make more
// cloth unresolved).
bool beyond_resolution(const std::vector<AnticipationWindow>& windows, const ViewParams& p, const GarmentReach& reach, double size_max);

}  // namespace vdc
