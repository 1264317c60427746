// Proximity pairs for repulsion inside the implicit step (Bridson, Fedkiw and Anderson 2002,
// section 7.2): vertex-face and edge-edge pairs, cloth-cloth and cloth-obstacle, closer than
// the repulsion thickness at the start of a step. Each cloth vertex keeps only its nearest face
// on each side, per mesh, so a vertex over a shared edge or vertex is not counted twice; edge-
// edge pairs count only when the closest points are inside both edges (the other cases are
// vertex-face pairs already).
#pragma once
#include <array>
#include <vector>

#include "core/math.hpp"

namespace vdc {

struct ProximityPair {
  std::array<int32_t, 4> nodes;           // cloth nodes; -1 for an obstacle point or a handle
  std::array<double, 4> weights;          // sum_j w_j x_j is the separation vector; sum_j w_j = 0
  std::array<Vec3, 4> obstacle_velocity;  // m/s, of the points with nodes[j] < 0
  Vec3 normal;                            // unit: the direction that separates the pair
  double distance = 0;                    // m: normal . sum_j w_j x_j (negative when crossed)
};

}  // namespace vdc
