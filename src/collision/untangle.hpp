// Untangling of interpenetrations that already exist (after remeshing, or in the initial pose),
// which continuous detection cannot see. Cloth-cloth: intersection contour minimisation (Volino
// and Magnenat-Thalmann 2006): the contour where two cloth surfaces cross is a chain of
// segments, one per intersecting triangle pair, whose ends are edge-face crossings; every
// crossing moves its edge against its face along the gradient of the contour length, so the
// contour shrinks until it vanishes. Cloth-obstacle: obstacles have an outside, so cloth that
// crosses one is moved out along the obstacle's normal (a contour-length step could push it
// further in). Iterates until no crossing is left or the iteration bound is reached, and ends
// at the iterate with the fewest crossing pairs.
#pragma once
#include <array>
#include <vector>

#include <Eigen/Core>

#include "collision/collider.hpp"

namespace vdc {

struct UntangleParams {
  double step = 0.002;      // m: the largest move of a vertex in one iteration
  double thickness = 0.002; // m: the clearance cloth is moved out of an obstacle by
  int max_iterations = 100;
  int threads = 1;          // for the crossing tests (the same moves on any number)
};

struct UntangleReport {
  int iterations = 0;       // detection passes that found crossings
  int moves = 0;            // vertex moves made
  int cloth_pairs = 0;      // intersecting cloth triangle pairs found by the first pass
  int obstacle_pairs = 0;   // intersecting cloth-obstacle triangle pairs found by the first pass
  int remaining = 0;        // intersecting pairs (of both kinds) left at the end
  int restored_pairs = 0;   // > 0: the last iterate had this many pairs, more than an earlier
                            // one, whose positions were restored
};

// Moves x (3n, cloth nodes) so that no two cloth faces that share no node intersect and no cloth
// face intersects an obstacle face. `fixed` nodes (handles) stay.
// `obstacle_trees` may give, per obstacle, a hierarchy whose boxes hold its faces at obstacle_x
// (the collider's, say); the others are built here, once for all passes.
UntangleReport untangle(const std::vector<std::array<int32_t, 3>>& cloth_faces, Eigen::VectorXd& x, const std::vector<char>& fixed,
                        const std::vector<CollisionMesh>& obstacles, const std::vector<std::vector<Vec3>>& obstacle_x,
                        const UntangleParams& params, const std::vector<const Bvh*>& obstacle_trees = {});

}  // namespace vdc
