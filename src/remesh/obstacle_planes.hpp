// The obstacle point nearest to each cloth node, for the obstacle-proximity sizing criterion
// (Narain et al. 2012, section 5): searched within a radius, with the direction from that point
// to the node (the obstacle's face normal when the node lies on it), and whether the node is held
// between that obstacle and another surface, both within `hold_distance` (0: never held). Branch
// and bound over each obstacle's hierarchy, the nodes on `threads` threads.
#pragma once
#include <vector>

#include "collision/collider.hpp"
#include "remesh/sizing.hpp"

namespace vdc {

// `obstacle_trees` may give, per obstacle, a hierarchy whose boxes hold its faces at obstacle_x
// (the collider's, say); the others are built here.
std::vector<ObstaclePlane> nearest_obstacle_planes(const std::vector<Vec3>& points, const std::vector<CollisionMesh>& obstacles,
                                                   const std::vector<std::vector<Vec3>>& obstacle_x, double radius, double hold_distance, int threads,
                                                   const std::vector<const Bvh*>& obstacle_trees = {});

}  // namespace vdc
