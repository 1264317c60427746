// Projection of a symmetric matrix onto the positive semi-definite cone (negative eigenvalues
// clamped to zero), the reference against which the cheap analytic projections are tested.
#pragma once
#include <Eigen/Eigenvalues>

#include "core/math.hpp"

namespace vdc {

template <int N>
MatN<N> project_psd(const MatN<N>& h) {
  Eigen::SelfAdjointEigenSolver<MatN<N>> eig(0.5 * (h + h.transpose()));
  VecN<N> lambda = eig.eigenvalues().cwiseMax(0.0);
  return eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
}

template <int N>
double min_eigenvalue(const MatN<N>& h) {
  return Eigen::SelfAdjointEigenSolver<MatN<N>>(0.5 * (h + h.transpose()), Eigen::EigenvaluesOnly).eigenvalues()[0];
}

}  // namespace vdc
