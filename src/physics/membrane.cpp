// Orthotropic StVK constant-strain triangle (Narain et al. 2012 section 3; Green strain).
#include "physics/membrane.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace vdc {

namespace {

// F = sum_a x_a g_a^T with g_1, g_2 the rows of Du^-1 and g_0 = -(g_1 + g_2).
std::array<Vec2, 3> shape_gradients(const MembraneElement& m) {
  Vec2 g1 = m.du_inv.row(0).transpose(), g2 = m.du_inv.row(1).transpose();
  return {Vec2(-(g1 + g2)), g1, g2};
}

double energy_density(const Mat2& e, const MembraneStiffness& k) {
  double g12 = 2.0 * e(0, 1);
  return 0.5 * (k.c11 * e(0, 0) * e(0, 0) + 2.0 * k.c12 * e(0, 0) * e(1, 1) + k.c22 * e(1, 1) * e(1, 1) + k.c33 * g12 * g12);
}

Mat2 clamp_negative(const Mat2& s) {
  Eigen::SelfAdjointEigenSolver<Mat2> eig;
  eig.computeDirect(s);
  Vec2 l = eig.eigenvalues().cwiseMax(0.0);
  return eig.eigenvectors() * l.asDiagonal() * eig.eigenvectors().transpose();
}

// Hessian of A psi: for each direction dx = e_k at corner a, dP = dF S_geo + F dS, column
// entries dP g_b. `s_geo` is the stress used in the geometric term (exact or clamped).
MatN<9> hessian_with(const Mat32& f, const Mat2& s_geo, const MembraneElement& m) {
  auto g = shape_gradients(m);
  MatN<9> h;
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 3; ++k) {
      Mat32 df = Mat32::Zero();
      df.row(k) = g[static_cast<std::size_t>(a)].transpose();
      Mat2 de = 0.5 * (f.transpose() * df + df.transpose() * f);
      Mat32 dp = df * s_geo + f * membrane_stress(de, m.k);
      for (int b = 0; b < 3; ++b) h.block<3, 1>(3 * b, 3 * a + k) = m.area * dp * g[static_cast<std::size_t>(b)];
    }
  return 0.5 * (h + h.transpose());
}

}  // namespace

double coarse_compression_factor(double coarsening) {
  if (!(coarsening > 1)) return 1;
  return std::max(1e-6, 1 / (coarsening * coarsening));
}

double eased_compression(double current, double target, double dt, double settle) {
  if (!(settle > 0) || !(target < current)) return target;
  return std::max(target, current * std::pow(target, dt / settle));
}

MembraneElement make_membrane_element(const Vec2& u0, const Vec2& u1, const Vec2& u2, const MembraneStiffness& k,
                                      double compression) {
  MembraneElement m;
  m.compression = compression;
  Mat2 du;
  du.col(0) = u1 - u0;
  du.col(1) = u2 - u0;
  m.du_inv = du.inverse();
  m.area = 0.5 * std::abs(du.determinant());
  m.k = k;
  return m;
}

Mat32 deformation_gradient(const TriStencil& x, const MembraneElement& m) {
  Mat32 dx;
  dx.col(0) = x[1] - x[0];
  dx.col(1) = x[2] - x[0];
  return dx * m.du_inv;
}

Mat2 green_strain(const Mat32& f) { return 0.5 * (f.transpose() * f - Mat2::Identity()); }

Mat2 membrane_stress(const Mat2& e, const MembraneStiffness& k) {
  Mat2 s;
  s(0, 0) = k.c11 * e(0, 0) + k.c12 * e(1, 1);
  s(1, 1) = k.c12 * e(0, 0) + k.c22 * e(1, 1);
  s(0, 1) = s(1, 0) = 2.0 * k.c33 * e(0, 1);
  return s;
}

namespace {

// The strain psi sees: compressive warp and weft strains scaled by the element's `compression`,
// and beyond its `gathered` strain by `gathering` (piecewise linear and continuous, so within
// each piece psi is the plain energy of the scaled strain), with the slopes of that scaling on
// E11 and E22.
struct SeenStrain {
  Mat2 e;
  Vec2 slope;
};

SeenStrain seen_strain(const Mat2& e, const MembraneElement& m) {
  SeenStrain s{e, Vec2(1, 1)};
  if (!(m.compression < 1)) return s;
  for (int i = 0; i < 2; ++i) {
    const double strain = e(i, i);
    if (!(strain < 0)) continue;
    if (m.gathering > 0 && strain < m.gathered[i]) {
      s.e(i, i) = m.compression * m.gathered[i] + m.gathering * (strain - m.gathered[i]);
      s.slope[i] = m.gathering;
    } else {
      s.e(i, i) = m.compression * strain;
      s.slope[i] = m.compression;
    }
  }
  return s;
}

// dpsi/dE: the plain stress of the seen strain, its warp and weft rows scaled by their slopes.
Mat2 seen_stress(const SeenStrain& s, const MembraneStiffness& k) {
  Mat2 out = membrane_stress(s.e, k);
  out(0, 0) *= s.slope[0];
  out(1, 1) *= s.slope[1];
  return out;
}

// The element whose plain stress increments are those of the scaled energy: dS = C' dE with
// c11' = a1^2 c11, c12' = a1 a2 c12, c22' = a2^2 c22 (a the slopes).
MembraneElement tangent_element(const MembraneElement& m, const Vec2& slope) {
  MembraneElement t = m;
  t.k.c11 *= slope[0] * slope[0];
  t.k.c12 *= slope[0] * slope[1];
  t.k.c22 *= slope[1] * slope[1];
  return t;
}

// Gradient of A psi: node a gets A P g_a with P = F S the first Piola-Kirchhoff stress.
VecN<9> nodal_gradient(const Mat32& f, const Mat2& s, const MembraneElement& m) {
  const Mat32 p = f * s;
  const auto g = shape_gradients(m);
  VecN<9> out;
  for (int a = 0; a < 3; ++a) out.segment<3>(3 * a) = m.area * p * g[static_cast<std::size_t>(a)];
  return out;
}

}  // namespace

double membrane_energy(const TriStencil& x, const MembraneElement& m) {
  return m.area * energy_density(seen_strain(green_strain(deformation_gradient(x, m)), m).e, m.k);
}

VecN<9> membrane_gradient(const TriStencil& x, const MembraneElement& m) {
  const Mat32 f = deformation_gradient(x, m);
  return nodal_gradient(f, seen_stress(seen_strain(green_strain(f), m), m.k), m);
}

MatN<9> membrane_hessian(const TriStencil& x, const MembraneElement& m) {
  const Mat32 f = deformation_gradient(x, m);
  const SeenStrain e = seen_strain(green_strain(f), m);
  return hessian_with(f, seen_stress(e, m.k), tangent_element(m, e.slope));
}

MatN<9> membrane_hessian_psd(const TriStencil& x, const MembraneElement& m) {
  const Mat32 f = deformation_gradient(x, m);
  const SeenStrain e = seen_strain(green_strain(f), m);
  return hessian_with(f, clamp_negative(seen_stress(e, m.k)), tangent_element(m, e.slope));
}

MembraneEval membrane_eval(const TriStencil& x, const MembraneElement& m) {
  const Mat32 f = deformation_gradient(x, m);
  const SeenStrain e = seen_strain(green_strain(f), m);
  const Mat2 s = seen_stress(e, m.k);
  MembraneEval r;
  r.energy = m.area * energy_density(e.e, m.k);
  r.gradient = nodal_gradient(f, s, m);
  r.hessian = hessian_with(f, clamp_negative(s), tangent_element(m, e.slope));
  return r;
}

}  // namespace vdc
