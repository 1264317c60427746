// Collision handling after a step (Bridson et al. 2002; Harmon et al. 2008): continuous
// detection of vertex-face and edge-edge impacts between cloth and cloth and between cloth and
// obstacles over the step's motion, grouped into impact zones, each projected inelastically;
// detection and projection repeat until no impact is left. Zones that do not converge within
// the bound fall back to their start-of-step positions (known collision-free), and say so.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/bvh.hpp"
#include "core/math.hpp"
#include "collision/candidates.hpp"
#include "collision/obstacle_trees.hpp"
#include "collision/proximity.hpp"

namespace vdc {

struct CollisionParams {
  double thickness = 0.002;  // m: the cloth's collision thickness (CCD tolerance 1e-3 of it)
  double impact_separation = 0.0002;   // m: impacts are projected to at least this separation
  double repulsion_thickness = 0.004;  // m: pairs closer than this are repelled in the implicit step
  double repulsion_stiffness = 3.0;    // k h^2 / m of a pair: the share of a gap a step closes is k h^2 / (m + k h^2)
  double friction = 0.3;               // Coulomb coefficient of proximity pairs
  int max_iterations = 20;   // detection-projection rounds before the fallback
  // Candidate pairs one detection round may test, per cloth primitive (node, edge): a step whose
  // motions sweep boxes that meet more (cloth driven far in one step) stops detecting and falls
  // back, rather than testing a number of pairs that grows as the square of the mesh.
  int max_candidates_per_primitive = 400;
  int untangle_iterations = 100;  // passes of untangling (collision/untangle.hpp) after a remesh
  int threads = 1;           // for the detection tests (set by the simulation, not the scene)
};

struct CollisionStats {
  int impacts = 0;     // impacts detected over all rounds
  int iterations = 0;  // detection rounds
  int fallbacks = 0;   // zones sent back to their start positions
  int64_t candidates = 0;  // most candidate pairs met in one detection round
  bool over_budget = false;  // a round met more than the bound: the step's cloth fell back whole
};

// A triangle soup that moves linearly over the step: cloth (global node indices into x) or an
// obstacle (its own vertex arrays, start and end).
struct CollisionMesh {
  std::vector<std::array<int32_t, 3>> faces;
};

// The faces around each vertex and each edge of an obstacle, for its outward normals at the few
// primitives a query finds (proximity.cpp), not at all of them every step. Item k's faces are
// faces[start[k], start[k + 1]).
struct FacesAround {
  std::vector<int32_t> start, faces;
};
struct ObstacleAdjacency {
  FacesAround vertex, edge;
};

// Each obstacle's face hierarchy at positions obstacle_x: given[o] where `given` has one (boxes
// holding the faces there, the collider's say), else one built into `built`, which owns it.
std::vector<const Bvh*> face_trees_at(const std::vector<CollisionMesh>& obstacles, const std::vector<std::vector<Vec3>>& obstacle_x,
                                      const std::vector<const Bvh*>& given, int threads, std::vector<std::unique_ptr<Bvh>>& built);

class Collider {
 public:
  // Cloth faces (global node ids) and obstacle meshes (faces into their own vertex arrays).
  Collider(const std::vector<std::array<int32_t, 3>>& cloth_faces, std::vector<CollisionMesh> obstacles, int32_t num_nodes);

  // New cloth faces after remeshing. The obstacles' edges and hierarchies stay: an obstacle's
  // topology never changes, and its hierarchies go on refitting as it moves.
  void set_cloth(const std::vector<std::array<int32_t, 3>>& cloth_faces, int32_t num_nodes);

  // Moves x_end (3n) so that no impact remains between x_start and x_end. `mass` per node;
  // `fixed` marks nodes whose end position must not change (handles). obstacle_start/end hold
  // each obstacle's vertices at the start and end of the step.
  CollisionStats resolve(const Eigen::VectorXd& x_start, Eigen::VectorXd& x_end, const std::vector<double>& mass,
                         const std::vector<char>& fixed, const std::vector<std::vector<Vec3>>& obstacle_start,
                         const std::vector<std::vector<Vec3>>& obstacle_end, const CollisionParams& params);

  // Proximity pairs closer than `band` at cloth positions x and velocities v (3n each) and the
  // obstacles' vertex positions and velocities at the same time (proximity.cpp). Nodes marked
  // `fixed` (handles) take part as points that do not move in the solve (node -1).
  std::vector<ProximityPair> proximities(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const std::vector<char>& fixed,
                                         const std::vector<std::vector<Vec3>>& obstacle_x,
                                         const std::vector<std::vector<Vec3>>& obstacle_v, double band, int threads);

  // Each obstacle's face hierarchy, its boxes holding the obstacle's faces at `obstacle_x`: kept
  // from the last detection when that ended there (the frame's start, after its last step), for
  // the searches between frames (obstacle-proximity sizing, untangling). Valid until the next
  // detection.
  std::vector<const Bvh*> obstacle_face_trees(const std::vector<std::vector<Vec3>>& obstacle_x, int threads);

 private:
  std::vector<std::array<int32_t, 3>> cloth_faces_;
  std::vector<std::array<int32_t, 2>> cloth_edges_;
  std::vector<std::array<int32_t, 3>> face_edges_;  // per cloth face, indices into cloth_edges_
  std::vector<CollisionMesh> obstacles_;
  std::vector<std::vector<std::array<int32_t, 2>>> obstacle_edges_;
  std::vector<std::vector<std::array<int32_t, 3>>> obstacle_face_edges_;
  std::vector<ObstacleAdjacency> obstacle_adjacency_;
  int32_t num_nodes_;
  // Hierarchies kept from step to step, refit to the boxes of each query (an obstacle's only
  // when it has moved since the last).
  RefitBvh cloth_face_tree_, cloth_edge_tree_;
  // The cloth-cloth pairs a proximity search listed, for the searches and first detection rounds
  // after it while the cloth stays near where they were listed.
  KeptClothPairs kept_pairs_;
  std::vector<ObstacleTrees> obstacle_trees_;
};

}  // namespace vdc
