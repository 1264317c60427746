// Narrow phase of continuous collision handling (Bridson, Fedkiw and Anderson 2002, section 7.4;
// Harmon et al. 2008, section 4): one vertex-face or edge-edge pair's motion over a step tested
// for contact, and the impact constraint the contact gives.
#pragma once
#include <cstdint>
#include <optional>

#include "collision/impact_zone.hpp"
#include "core/math.hpp"

namespace vdc {

// One point's motion over a step.
struct PointPath {
  Vec3 start, end;    // positions at the step's start and end
  int32_t node = -1;  // the node the projection may move; -1 for an obstacle or fixed point
};

// Vertex p against triangle (a, b, c): the constraint of their first contact within eta, its
// normal on the side the vertex came from; nothing when they do not meet or the triangle is
// degenerate.
std::optional<ImpactConstraint> vertex_face_impact(const PointPath& p, const PointPath& a, const PointPath& b, const PointPath& c,
                                                   double eta);

// Edge (a, b) against edge (c, d): the constraint of their first contact within eta, its normal
// from (c, d) towards (a, b) as they were at the step's start.
std::optional<ImpactConstraint> edge_edge_impact(const PointPath& a, const PointPath& b, const PointPath& c, const PointPath& d,
                                                 double eta);

}  // namespace vdc
