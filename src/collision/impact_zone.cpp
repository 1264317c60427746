// Inelastic impact-zone projection (Harmon et al. 2008, section 4), solved in the dual.
#include "collision/impact_zone.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>

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

ImpactZones::ImpactZones(int32_t num_nodes) : parent_(static_cast<std::size_t>(num_nodes)) {
  std::iota(parent_.begin(), parent_.end(), 0);
}

int32_t ImpactZones::root(int32_t i) {
  while (parent_[static_cast<std::size_t>(i)] != i)
    i = parent_[static_cast<std::size_t>(i)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(i)])];
  return i;
}

void ImpactZones::add(const std::vector<ImpactConstraint>& found) {
  for (const auto& c : found) {
    int32_t first = -1;
    for (int32_t n : c.nodes) {
      if (n < 0) continue;
      if (first < 0) first = n;
      else parent_[static_cast<std::size_t>(root(n))] = root(first);
    }
    if (first < 0) continue;  // nothing movable: an impact between fixed points
    constraints_.push_back(c);
    anchor_.push_back(first);
  }
}

void ImpactZones::project(Eigen::VectorXd& x, const std::vector<double>& mass, double min_separation, double tolerance,
                          std::vector<char>& moved) {
  std::fill(moved.begin(), moved.end(), 0);
  std::map<int32_t, std::vector<std::size_t>> zones;
  for (std::size_t i = 0; i < constraints_.size(); ++i) zones[root(anchor_[i])].push_back(i);
  for (const auto& [zone, members] : zones) {
    std::map<int32_t, int32_t> local;
    std::vector<Vec3> xz;
    std::vector<double> mz;
    std::vector<ImpactConstraint> cz;
    for (std::size_t i : members) {
      ImpactConstraint c = constraints_[i];
      for (int32_t& n : c.nodes) {
        if (n < 0) continue;
        auto it = local.find(n);
        if (it == local.end()) {
          it = local.emplace(n, static_cast<int32_t>(xz.size())).first;
          xz.push_back(x.segment<3>(3 * n));
          mz.push_back(mass[static_cast<std::size_t>(n)]);
        }
        n = it->second;
      }
      cz.push_back(c);
    }
    project_impact_zone(xz, mz, cz, min_separation, tolerance);
    for (const auto& [global, li] : local) {
      const Vec3& moved_to = xz[static_cast<std::size_t>(li)];
      if (moved_to != Vec3(x.segment<3>(3 * global))) moved[static_cast<std::size_t>(global)] = 1;
      x.segment<3>(3 * global) = moved_to;
    }
  }
}

int ImpactZones::fall_back(const Eigen::VectorXd& x_start, Eigen::VectorXd& x_end) {
  std::map<int32_t, std::vector<int32_t>> members;
  std::map<int32_t, std::pair<Vec3, int>> carried;
  for (std::size_t i = 0; i < constraints_.size(); ++i) {
    const int32_t zone = root(anchor_[i]);
    for (int32_t n : constraints_[i].nodes)
      if (n >= 0) members[zone].push_back(n);
    if (constraints_[i].has_fixed) {
      auto& [sum, count] = carried[zone];
      if (count == 0) sum = Vec3::Zero();
      sum += constraints_[i].fixed_motion;
      ++count;
    }
  }
  int zones = 0;
  for (const auto& [zone, nodes] : members) {
    const auto it = carried.find(zone);
    const Vec3 d = it == carried.end() ? Vec3::Zero() : Vec3(it->second.first / it->second.second);
    for (int32_t n : nodes) x_end.segment<3>(3 * n) = x_start.segment<3>(3 * n) + d;
    ++zones;
  }
  return zones;
}

}  // namespace vdc
