// Repulsion and friction of proximity pairs inside the implicit step. Repulsion is the penalty
// E = k (band - d)^2 / 2 on a pair's separation d (Bridson, Fedkiw and Anderson 2002, section
// 7.2), with k = stiffness m_eff / h^2 so that one step closes the share stiffness / (1 +
// stiffness) of the gap whatever the pair's mass; m_eff = 1 / sum_j (w_j^2 / m_j). Friction is
// Coulomb's law as a damping lagged over the step: coefficient min(mu f_n / |v_t|, m_eff / h),
// sliding at mu f_n, and stopping a slow relative tangential motion instead of reversing it.
#pragma once
#include <array>
#include <vector>

#include <Eigen/Core>

#include "collision/proximity.hpp"

namespace vdc {

struct ContactParams {
  double band = 0.004;    // m: the repulsion thickness
  double stiffness = 3;   // k h^2 / m_eff
  double friction = 0.3;  // Coulomb coefficient
};

// What one pair adds to the step's system (M + h D + h^2 K) dv = rhs: the block w_i w_j A at
// nodes (i, j) and w_i b to node i's right-hand side, for its movable nodes.
struct ContactTerm {
  std::array<int32_t, 4> nodes;  // -1: not a node of the system
  std::array<double, 4> weights;
  Mat3 block;  // h^2 k n n^T + h c (I - n n^T)
  Vec3 rhs;    // h (f_n n - c v_t) - h^2 k n (n . v_rel)
  double normal_force = 0;  // N: k (band - d)
};

// Terms of every pair at velocities v (3n), masses per node, step h.
std::vector<ContactTerm> contact_terms(const std::vector<ProximityPair>& pairs, const Eigen::VectorXd& v,
                                       const std::vector<double>& mass, double h, const ContactParams& params);

}  // namespace vdc
