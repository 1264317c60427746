// Penalty repulsion with lagged Coulomb friction for proximity pairs (Bridson, Fedkiw and
// Anderson 2002, sections 7.2 and 7.3), linearised for one backward-Euler step.
#include "physics/contact.hpp"

#include <algorithm>

namespace vdc {

std::vector<ContactTerm> contact_terms(const std::vector<ProximityPair>& pairs, const Eigen::VectorXd& v,
                                       const std::vector<double>& mass, double h, const ContactParams& params) {
  std::vector<ContactTerm> terms;
  terms.reserve(pairs.size());
  for (const ProximityPair& p : pairs) {
    double inv_mass = 0;
    Vec3 v_rel = Vec3::Zero();
    for (std::size_t j = 0; j < 4; ++j) {
      const int32_t n = p.nodes[j];
      if (n >= 0) {
        inv_mass += p.weights[j] * p.weights[j] / mass[static_cast<std::size_t>(n)];
        v_rel += p.weights[j] * v.segment<3>(3 * n);
      } else {
        v_rel += p.weights[j] * p.obstacle_velocity[j];
      }
    }
    if (!(inv_mass > 0)) continue;
    const double m_eff = 1 / inv_mass;
    const double k = params.stiffness * m_eff / (h * h);
    const double fn = k * std::max(0.0, params.band - p.distance);
    if (fn <= 0) continue;
    const Vec3& n = p.normal;
    const double vn = n.dot(v_rel);
    const Vec3 vt = v_rel - vn * n;
    const double vt_norm = vt.norm();
    const double cap = m_eff / h;
    const double c = vt_norm > 0 ? std::min(params.friction * fn / vt_norm, cap) : (params.friction > 0 ? cap : 0.0);
    const Mat3 nn = n * n.transpose();
    ContactTerm t;
    t.nodes = p.nodes;
    t.weights = p.weights;
    t.block = h * h * k * nn + h * c * (Mat3::Identity() - nn);
    t.rhs = h * (fn * n - c * vt) - h * h * k * vn * n;
    t.normal_force = fn;
    terms.push_back(t);
  }
  return terms;
}

}  // namespace vdc
