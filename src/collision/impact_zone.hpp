// Inelastic projection of impact zones (Harmon, Vouga, Tamstorf and Grinspun 2008, section 4):
// the end-of-step positions of a zone's nodes move as little as possible, in the mass metric,
// so that every impact's separation along its normal is at least the thickness. Each
// constraint's weights sum to zero, so the correction conserves the zone's linear momentum
// exactly, whatever the solver's accuracy; nodes of obstacles have infinite mass and stay put.
#pragma once
#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/math.hpp"

namespace vdc {

// One impact: four points (vertex-face: the vertex, then the face's corners; edge-edge: the
// two ends of each edge) with weights such that sum_j w_j x_j is the separation vector, and
// the normal it must point along. `nodes` index the zone's positions; -1 for an obstacle point,
// whose position is fixed and given in `fixed`.
struct ImpactConstraint {
  std::array<int32_t, 4> nodes;
  std::array<double, 4> weights;
  std::array<Vec3, 4> fixed{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  // used where nodes[j] < 0
  Vec3 normal;                // unit
  // Displacement over the step of the fixed points (obstacle or handle), weighted by |w_j|;
  // zero when all points are movable. The fallback moves a stuck zone with it.
  Vec3 fixed_motion = Vec3::Zero();
  bool has_fixed = false;
};

struct ProjectionReport {
  bool converged = false;
  int iterations = 0;
  double worst_violation = 0;  // m: thickness minus the smallest separation, after projection
};

// Separation of constraint c at positions x: normal . sum_j w_j x_j.
double separation(const ImpactConstraint& c, const std::vector<Vec3>& x);

// Projects positions x (masses m, all > 0) onto {separation >= min_separation for every
// constraint} by projected Gauss-Seidel on the dual variables, up to `tolerance` metres of
// violation.
ProjectionReport project_impact_zone(std::vector<Vec3>& x, const std::vector<double>& mass,
                                     const std::vector<ImpactConstraint>& constraints, double min_separation, double tolerance,
                                     int max_iterations = 200);

// The impact zones of one step (Bridson, Fedkiw and Anderson 2002, section 7.4; Harmon et al.
// 2008, section 4): the movable nodes of every impact found so far merged into zones, each zone
// projected with every constraint gathered for it, and the fallback for zones that do not
// separate.
class ImpactZones {
 public:
  explicit ImpactZones(int32_t num_nodes);
  // Merges each impact's movable nodes into one zone and keeps its constraint; an impact between
  // fixed points only is dropped.
  void add(const std::vector<ImpactConstraint>& found);
  // Projects each zone (project_impact_zone) on the end positions x (3 per node, masses by
  // node); moved[n] becomes 1 for the nodes the projection moved, 0 for the others.
  void project(Eigen::VectorXd& x, const std::vector<double>& mass, double min_separation, double tolerance,
               std::vector<char>& moved);
  // Sends every zone back to where it started the step, moved with the obstacles it touches (the
  // mean displacement of its constraints' fixed points), so that a zone caught on a moving body
  // rides along rather than being swallowed by it. Returns the number of zones.
  int fall_back(const Eigen::VectorXd& x_start, Eigen::VectorXd& x_end);

 private:
  int32_t root(int32_t node);  // union-find with path halving
  std::vector<int32_t> parent_;
  std::vector<ImpactConstraint> constraints_;
  std::vector<int32_t> anchor_;  // a movable node of each constraint
};

}  // namespace vdc
