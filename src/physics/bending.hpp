// Discrete-shell bending (Grinspun et al. 2003, "Discrete Shells"; gradient as in Bridson et al.
// 2003): E = k (theta - theta0)^2 |e|^2 / (2 (A0 + A1)) with rest edge length and areas. The
// factor 1/2 makes a regular equilateral mesh bent to curvature kappa store the continuum
// plate energy 1/2 k kappa^2 per unit area, whatever the bending direction.
// Stencil: x0, x1 the edge; x2 opposite in the face running x0 -> x1; x3 opposite in the other.
#pragma once
#include <array>

#include "core/math.hpp"

namespace vdc {

using BendStencil = std::array<Vec3, 4>;

// Signed dihedral angle atan2(e.(nA x nB), nA.nB) in (-pi, pi]: zero when flat, negative when the
// opposite vertices rise along the face normals (the outer side becomes concave).
double dihedral_angle(const BendStencil& x);
VecN<12> dihedral_angle_gradient(const BendStencil& x);
MatN<12> dihedral_angle_hessian(const BendStencil& x);  // exact, by forward differentiation

struct BendingElement {
  double theta0 = 0;  // rest angle
  double coeff = 0;   // k |e|^2 / (2 (A0 + A1)), so E = coeff (theta - theta0)^2
};

// Coefficient for bending stiffness k (N m), rest edge length and the rest areas of the two faces.
double bending_coefficient(double stiffness, double rest_length, double rest_area0, double rest_area1);

double bending_energy(const BendStencil& x, const BendingElement& b);
VecN<12> bending_gradient(const BendStencil& x, const BendingElement& b);
MatN<12> bending_hessian(const BendStencil& x, const BendingElement& b);  // exact
// Positive semi-definite: the Gauss-Newton part 2 coeff grad(theta) grad(theta)^T, i.e. the exact
// Hessian without the (theta - theta0) curvature term, which is what makes it indefinite.
MatN<12> bending_hessian_psd(const BendStencil& x, const BendingElement& b);

// Energy, gradient and PSD Hessian in one pass (what assembly uses).
struct BendingEval {
  double energy;
  VecN<12> gradient;
  MatN<12> hessian;
};
BendingEval bending_eval(const BendStencil& x, const BendingElement& b);

}  // namespace vdc
