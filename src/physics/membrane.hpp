// Constant-strain triangle membrane on Green strain with an orthotropic (warp, weft, shear)
// St. Venant-Kirchhoff energy: psi = 1/2 (c11 E11^2 + 2 c12 E11 E22 + c22 E22^2 + c33 (2 E12)^2),
// W = A psi, F = Dx Du^-1 (Narain et al. 2012 section 3; Volino et al. 2009 for the strain model).
//
// An element coarser than the wrinkles its cloth would form cannot buckle into them: along warp
// and weft it would resist compression with the full stretch stiffness, where the fine cloth
// folds at almost no cost, and a coarse region would hold its shape like a stiff shell (membrane
// locking). `compression` < 1 models those unresolved buckles: a compressive warp or weft
// strain E counts as compression * E in psi, so the element keeps its full response in tension
// and shear and carries compression^2 of the stiffness against compression. 1 is the plain
// material.
//
// A coarse element also stands for the folds it was made over: its chords were shorter than its
// material by the gathering those folds held. With `gathering` > 0 it remembers that strain
// (`gathered`, warp and weft, <= 0): up to it, compression stays as soft as `compression` says
// (folds open and close freely), and beyond it the element resists with the steeper factor
// `gathering` (fine cloth gathers further only by bending its folds tighter), so coarse cloth
// keeps the gathering it had instead of collapsing further at no cost (an extension of Koh et
// al. 2014's coarsening, bench/RESULTS.md "Coarse cloth keeps its gathering").
#pragma once
#include <array>

#include "core/math.hpp"

namespace vdc {

// Stiffness in N/m: warp (material u axis), weft (material v axis), their coupling, in-plane shear.
struct MembraneStiffness {
  double c11 = 0, c12 = 0, c22 = 0, c33 = 0;
};

struct MembraneElement {
  Mat2 du_inv = Mat2::Identity();  // inverse of [u1 - u0, u2 - u0]
  double area = 0;                  // rest (material-space) area
  MembraneStiffness k;
  double compression = 1;           // in (0, 1]: see above
  Vec2 gathered = Vec2::Zero();     // warp and weft Green strain (<= 0) the element was made with
  double gathering = 0;             // strain factor beyond `gathered`; 0: `compression` throughout
};

using TriStencil = std::array<Vec3, 3>;

// The compression factor of an element `coarsening` times coarser than its sizing asks (the
// squared ratio of edge lengths): 1 up to 1, then coarsening^-2, not below 1e-6. Buckled cloth
// carries almost no compression (pi^2 B / lambda^2: 0.25 N/m for cotton's 2 cm wrinkles, where
// 1% of strain takes 50 N/m), so the factor falls steeply; it starts at 1 so that a face at its
// own resolution is the plain material, and the exponent is the one that kept view runs closest
// to the adaptive shot (bench/RESULTS.md, "The compression law").
double coarse_compression_factor(double coarsening);

// A face's compression factor one step of `dt` seconds on (an extension of the law above): cloth
// that gathers into folds does so over time, as it buckles, so a factor that softens moves from
// `current` towards `target` geometrically, reaching it after `settle` seconds at most
// (current * target^(dt / settle), never below target); one that stiffens, or any with settle 0,
// is `target` at once.
double eased_compression(double current, double target, double dt, double settle);

MembraneElement make_membrane_element(const Vec2& u0, const Vec2& u1, const Vec2& u2, const MembraneStiffness& k,
                                      double compression = 1);

Mat32 deformation_gradient(const TriStencil& x, const MembraneElement& m);
Mat2 green_strain(const Mat32& f);
// Second Piola-Kirchhoff stress dpsi/dE (symmetric 2x2).
Mat2 membrane_stress(const Mat2& strain, const MembraneStiffness& k);

double membrane_energy(const TriStencil& x, const MembraneElement& m);
VecN<9> membrane_gradient(const TriStencil& x, const MembraneElement& m);
MatN<9> membrane_hessian(const TriStencil& x, const MembraneElement& m);  // exact
// Positive semi-definite: the geometric-stiffness term uses the stress with negative principal
// values clamped to zero; the material term J^T C J is PSD already. Equal to the exact Hessian
// whenever the element is not in compression.
MatN<9> membrane_hessian_psd(const TriStencil& x, const MembraneElement& m);

struct MembraneEval {
  double energy;
  VecN<9> gradient;
  MatN<9> hessian;  // PSD
};
MembraneEval membrane_eval(const TriStencil& x, const MembraneElement& m);

}  // namespace vdc
