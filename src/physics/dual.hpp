// Forward-mode dual numbers with N derivative directions: exact first derivatives of any
// expression built from + - * / sqrt. Used to differentiate analytic gradients into Hessians.
#pragma once
#include <cmath>

#include "core/math.hpp"

namespace vdc {

template <int N>
struct Dual {
  double v = 0;
  VecN<N> d = VecN<N>::Zero();
  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants promote implicitly
  Dual(double value, int direction) : v(value) { d[direction] = 1; }
  Dual(double value, const VecN<N>& deriv) : v(value), d(deriv) {}
};

template <int N> Dual<N> operator+(const Dual<N>& a, const Dual<N>& b) { return {a.v + b.v, a.d + b.d}; }
template <int N> Dual<N> operator-(const Dual<N>& a, const Dual<N>& b) { return {a.v - b.v, a.d - b.d}; }
template <int N> Dual<N> operator-(const Dual<N>& a) { return {-a.v, -a.d}; }
template <int N> Dual<N> operator*(const Dual<N>& a, const Dual<N>& b) { return {a.v * b.v, b.v * a.d + a.v * b.d}; }
template <int N> Dual<N> operator/(const Dual<N>& a, const Dual<N>& b) {
  return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)};
}
template <int N> Dual<N> operator*(double s, const Dual<N>& a) { return {s * a.v, s * a.d}; }
template <int N> Dual<N> sqrt(const Dual<N>& a) {
  double r = std::sqrt(a.v);
  return {r, a.d / (2 * r)};
}

inline double value_of(double x) { return x; }
template <int N> double value_of(const Dual<N>& x) { return x.v; }

// A 3-vector over any scalar (double or Dual), with the few operations geometry needs.
template <class T>
struct V3 {
  T x, y, z;
  V3 operator+(const V3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  V3 operator-(const V3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  V3 operator*(const T& s) const { return {x * s, y * s, z * s}; }
  V3 operator/(const T& s) const { return {x / s, y / s, z / s}; }
};
template <class T> T dot(const V3<T>& a, const V3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T> V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T> T norm(const V3<T>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}

}  // namespace vdc
