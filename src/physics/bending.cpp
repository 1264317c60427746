// Discrete-shell bending: Grinspun et al. 2003 energy, Bridson et al. 2003 angle gradient.
#include "physics/bending.hpp"

#include <cmath>

#include "physics/dual.hpp"

namespace vdc {

namespace {

template <class T>
V3<T> lift(const Vec3& p) {
  return {T(p.x()), T(p.y()), T(p.z())};
}

// d theta / d (x0, x1, x2, x3): opposite vertices move along -n/h, edge vertices balance them by
// the barycentric position of the opposite vertex's foot on the edge.
template <class T>
std::array<V3<T>, 4> angle_gradient(const std::array<V3<T>, 4>& x) {
  using std::sqrt;
  V3<T> e = x[1] - x[0];
  T le2 = dot(e, e);
  T le = sqrt(le2);
  V3<T> na = cross(x[1] - x[0], x[2] - x[0]);
  V3<T> nb = cross(x[0] - x[1], x[3] - x[1]);
  T la = norm(na), lb = norm(nb);
  // n/h = (N/|N|) / (|N|/|e|) = N |e| / |N|^2
  V3<T> ga = na * (le / (la * la));
  V3<T> gb = nb * (le / (lb * lb));
  T ta = dot(x[2] - x[0], e) / le2;
  T tb = dot(x[3] - x[0], e) / le2;
  T one(1.0);
  return {ga * (one - ta) + gb * (one - tb), ga * ta + gb * tb, ga * T(-1.0), gb * T(-1.0)};
}

}  // namespace

double dihedral_angle(const BendStencil& x) {
  Vec3 e = (x[1] - x[0]).normalized();
  Vec3 na = (x[1] - x[0]).cross(x[2] - x[0]);
  Vec3 nb = (x[0] - x[1]).cross(x[3] - x[1]);
  return std::atan2(e.dot(na.cross(nb)), na.dot(nb));
}

VecN<12> dihedral_angle_gradient(const BendStencil& x) {
  std::array<V3<double>, 4> p;
  for (int i = 0; i < 4; ++i) p[static_cast<std::size_t>(i)] = lift<double>(x[static_cast<std::size_t>(i)]);
  auto g = angle_gradient(p);
  VecN<12> out;
  for (int i = 0; i < 4; ++i) out.segment<3>(3 * i) << g[static_cast<std::size_t>(i)].x, g[static_cast<std::size_t>(i)].y, g[static_cast<std::size_t>(i)].z;
  return out;
}

MatN<12> dihedral_angle_hessian(const BendStencil& x) {
  using D = Dual<12>;
  std::array<V3<D>, 4> p;
  for (int i = 0; i < 4; ++i) {
    const Vec3& xi = x[static_cast<std::size_t>(i)];
    p[static_cast<std::size_t>(i)] = {D(xi.x(), 3 * i), D(xi.y(), 3 * i + 1), D(xi.z(), 3 * i + 2)};
  }
  auto g = angle_gradient(p);
  MatN<12> h;
  for (int i = 0; i < 4; ++i) {
    const auto& gi = g[static_cast<std::size_t>(i)];
    h.row(3 * i) = gi.x.d.transpose();
    h.row(3 * i + 1) = gi.y.d.transpose();
    h.row(3 * i + 2) = gi.z.d.transpose();
  }
  return 0.5 * (h + h.transpose());
}

double bending_coefficient(double stiffness, double rest_length, double rest_area0, double rest_area1) {
  return stiffness * rest_length * rest_length / (2.0 * (rest_area0 + rest_area1));
}

double bending_energy(const BendStencil& x, const BendingElement& b) {
  double d = dihedral_angle(x) - b.theta0;
  return b.coeff * d * d;
}

VecN<12> bending_gradient(const BendStencil& x, const BendingElement& b) {
  return 2.0 * b.coeff * (dihedral_angle(x) - b.theta0) * dihedral_angle_gradient(x);
}

MatN<12> bending_hessian(const BendStencil& x, const BendingElement& b) {
  VecN<12> g = dihedral_angle_gradient(x);
  return 2.0 * b.coeff * (g * g.transpose() + (dihedral_angle(x) - b.theta0) * dihedral_angle_hessian(x));
}

MatN<12> bending_hessian_psd(const BendStencil& x, const BendingElement& b) {
  VecN<12> g = dihedral_angle_gradient(x);
  return 2.0 * b.coeff * g * g.transpose();
}

BendingEval bending_eval(const BendStencil& x, const BendingElement& b) {
  VecN<12> g = dihedral_angle_gradient(x);
  double d = dihedral_angle(x) - b.theta0;
  return {b.coeff * d * d, 2.0 * b.coeff * d * g, 2.0 * b.coeff * g * g.transpose()};
}

}  // namespace vdc
