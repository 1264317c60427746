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

namespace vdc {

struct CollisionParams {
  double thickness = 0.002;  // m: impacts are projected to at least this separation
  int max_iterations = 20;   // detection-projection rounds before the fallback
  int threads = 1;           // for the detection tests (set by the simulation, not the scene)
};

struct CollisionStats {
  int impacts = 0;     // impacts detected over all rounds
  int iterations = 0;  // detection rounds
  int fallbacks = 0;   // zones sent back to their start positions
};

// A triangle soup that moves linearly over the step: cloth (global node indices into x) or an
// obstacle (its own vertex arrays, start and end).
struct CollisionMesh {
  std::vector<std::array<int32_t, 3>> faces;
};

class Collider {
 public:
  // Cloth faces (global node ids) and obstacle meshes (faces into their own vertex arrays).
  Collider(const std::vector<std::array<int32_t, 3>>& cloth_faces, std::vector<CollisionMesh> obstacles, int32_t num_nodes);

  // Moves x_end (3n) so that no impact remains between x_start and x_end. `mass` per node;
  // `fixed` marks nodes whose end position must not change (handles). obstacle_start/end hold
  // each obstacle's vertices at the start and end of the step.
  CollisionStats resolve(const Eigen::VectorXd& x_start, Eigen::VectorXd& x_end, const std::vector<double>& mass,
                         const std::vector<char>& fixed, const std::vector<std::vector<Vec3>>& obstacle_start,
                         const std::vector<std::vector<Vec3>>& obstacle_end, const CollisionParams& params);

 private:
  std::vector<std::array<int32_t, 3>> cloth_faces_;
  std::vector<std::array<int32_t, 2>> cloth_edges_;
  std::vector<std::array<int32_t, 3>> face_edges_;  // per cloth face, indices into cloth_edges_
  std::vector<CollisionMesh> obstacles_;
  std::vector<std::vector<std::array<int32_t, 2>>> obstacle_edges_;
  std::vector<std::vector<std::array<int32_t, 3>>> obstacle_face_edges_;
  int32_t num_nodes_;
};

}  // namespace vdc
