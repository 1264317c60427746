// Inelastic impact-zone projection (Harmon et al. 2008, section 4), solved in the dual.
#include "collision/impact_zone.hpp"

#include <algorithm>
#include <limits>

namespace vdc {

double separation(const ImpactConstraint& c, const std::vector<Vec3>& x) {
  Vec3 s = Vec3::Zero();
  for (int j = 0; j < 4; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    s += c.weights[ju] * (c.nodes[ju] >= 0 ? x[static_cast<std::size_t>(c.nodes[ju])] : c.fixed[ju]);
  }
  return c.normal.dot(s);
}

ProjectionReport project_impact_zone(std::vector<Vec3>& x, const std::vector<double>& mass,
                                     const std::vector<ImpactConstraint>& constraints, double min_separation, double tolerance,
                                     int max_iterations) {
  // min 1/2 sum m |x - x0|^2 subject to g_i(x) = n_i . sum_j w_ij x_j - h >= 0. With multipliers
  // lambda_i >= 0, x = x0 + M^-1 sum_i lambda_i grad g_i; Gauss-Seidel raises or lowers one
  // lambda at a time to satisfy its constraint exactly, never below zero.
  ProjectionReport rep;
  std::vector<double> lambda(constraints.size(), 0.0), inv_k(constraints.size(), 0.0);
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    double k = 0;
    for (int j = 0; j < 4; ++j) {
      const auto ju = static_cast<std::size_t>(j);
      if (constraints[i].nodes[ju] >= 0) k += constraints[i].weights[ju] * constraints[i].weights[ju] / mass[static_cast<std::size_t>(constraints[i].nodes[ju])];
    }
    inv_k[i] = k > 0 ? 1.0 / k : 0.0;
  }
  for (rep.iterations = 0; rep.iterations < max_iterations; ++rep.iterations) {
    double worst = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < constraints.size(); ++i) {
      const ImpactConstraint& c = constraints[i];
      const double violation = min_separation - separation(c, x);
      worst = std::max(worst, violation);
      const double delta = std::max(violation * inv_k[i], -lambda[i]);
      if (delta == 0) continue;
      lambda[i] += delta;
      for (int j = 0; j < 4; ++j) {
        const auto ju = static_cast<std::size_t>(j);
        if (c.nodes[ju] >= 0) x[static_cast<std::size_t>(c.nodes[ju])] += delta * c.weights[ju] / mass[static_cast<std::size_t>(c.nodes[ju])] * c.normal;
      }
    }
    rep.worst_violation = worst;
    if (worst <= tolerance) {
      rep.converged = true;
      break;
    }
  }
  // The last sweep changed x: measure the final state.
  rep.worst_violation = -std::numeric_limits<double>::infinity();
  for (const auto& c : constraints) rep.worst_violation = std::max(rep.worst_violation, min_separation - separation(c, x));
  rep.converged = rep.worst_violation <= tolerance;
  return rep;
}

}  // namespace vdc
