// Central differences for the derivative tests: along coordinate k, (f(x + eps e_k) -
// f(x - eps e_k)) / (2 eps), with error O(eps^2).
#pragma once
#include <type_traits>

#include <Eigen/Core>

namespace vdc::test {

// The central differences of f at x along every coordinate: the gradient (a vector) of a scalar
// f, the Jacobian (one column per coordinate) of a vector-valued one.
template <class F, class Vector>
auto central_differences(const F& f, const Vector& x, double eps) {
  using Value = std::decay_t<decltype(f(x))>;
  auto along = [&](Eigen::Index k) {
    Vector plus = x, minus = x;
    plus[k] += eps;
    minus[k] -= eps;
    const Value high = f(plus), low = f(minus);
    return Value((high - low) / (2 * eps));
  };
  if constexpr (std::is_arithmetic_v<Value>) {
    Eigen::VectorXd d(x.size());
    for (Eigen::Index k = 0; k < x.size(); ++k) d[k] = along(k);
    return d;
  } else {
    Eigen::MatrixXd d(f(x).size(), x.size());
    for (Eigen::Index k = 0; k < x.size(); ++k) d.col(k) = along(k);
    return d;
  }
}

}  // namespace vdc::test
