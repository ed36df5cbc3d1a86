#pragma once
/// Forward-mode dual numbers, nestable: Dual<T, N> = v + sum_k d_k eps_k with
/// eps_j eps_k = 0, T = double or another Dual (nesting gives second derivatives). The one
/// dual type of the library: the beam element differentiates the SO(3) coefficients with
/// it (common/lie_series.hpp), the planar shooting right-hand side its state.
///
/// No default member initializers: `Dual<T, N> x;` leaves v and d uninitialized (work arrays
/// filled before use cost nothing), while `Dual<T, N>()` (value-initialization) is zero and
/// `Dual<T, N>(c)` is the constant c (zero derivatives).
#include <array>
#include <cmath>

namespace tcasim::ad {

template <class T, int N>
struct Dual {
  T v;
  std::array<T, N> d;
  Dual() = default;
  Dual(double x) : v(x), d{} {}  // NOLINT: constants promote implicitly
};

/// The value part (of the innermost level for nested duals).
inline double value(double x) { return x; }
template <class T, int N>
double value(const Dual<T, N>& x) {
  return value(x.v);
}

template <class T, int N>
Dual<T, N> operator+(const Dual<T, N>& a, const Dual<T, N>& b) {
  Dual<T, N> r;
  r.v = a.v + b.v;
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] + b.d[k];
  return r;
}
template <class T, int N>
Dual<T, N> operator-(const Dual<T, N>& a, const Dual<T, N>& b) {
  Dual<T, N> r;
  r.v = a.v - b.v;
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] - b.d[k];
  return r;
}
template <class T, int N>
Dual<T, N> operator-(const Dual<T, N>& a) {
  Dual<T, N> r;
  r.v = -a.v;
  for (int k = 0; k < N; ++k) r.d[k] = -a.d[k];
  return r;
}
template <class T, int N>
Dual<T, N> operator*(const Dual<T, N>& a, const Dual<T, N>& b) {
  Dual<T, N> r;
  r.v = a.v * b.v;
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] * b.v + a.v * b.d[k];
  return r;
}
/// (a/b)' = (a' - (a/b) b') / b.
template <class T, int N>
Dual<T, N> operator/(const Dual<T, N>& a, const Dual<T, N>& b) {
  Dual<T, N> r;
  r.v = a.v / b.v;
  const T inv = 1.0 / b.v;
  for (int k = 0; k < N; ++k) r.d[k] = (a.d[k] - r.v * b.d[k]) * inv;
  return r;
}
template <class T, int N>
Dual<T, N> operator+(const Dual<T, N>& a, double b) {
  Dual<T, N> r = a;
  r.v = r.v + b;
  return r;
}
template <class T, int N>
Dual<T, N> operator+(double a, const Dual<T, N>& b) {
  return b + a;
}
template <class T, int N>
Dual<T, N> operator-(const Dual<T, N>& a, double b) {
  Dual<T, N> r = a;
  r.v = r.v - b;
  return r;
}
template <class T, int N>
Dual<T, N> operator-(double b, const Dual<T, N>& a) {
  return (-a) + b;
}
template <class T, int N>
Dual<T, N> operator*(double a, const Dual<T, N>& b) {
  Dual<T, N> r;
  r.v = a * b.v;
  for (int k = 0; k < N; ++k) r.d[k] = a * b.d[k];
  return r;
}
template <class T, int N>
Dual<T, N> operator*(const Dual<T, N>& a, double b) {
  return b * a;
}
/// (a/b)' = -(a/b) b' / b.
template <class T, int N>
Dual<T, N> operator/(double a, const Dual<T, N>& b) {
  Dual<T, N> r;
  r.v = a / b.v;
  const T s = -r.v / b.v;
  for (int k = 0; k < N; ++k) r.d[k] = s * b.d[k];
  return r;
}
template <class T, int N>
Dual<T, N> operator/(const Dual<T, N>& a, double b) {
  return (1.0 / b) * a;
}
/// 1/a.
inline double inverse(double a) { return 1.0 / a; }
template <class T, int N>
Dual<T, N> inverse(const Dual<T, N>& a) {
  return 1.0 / a;
}

using std::cos;
using std::sin;
using std::sqrt;
template <class T, int N>
Dual<T, N> sin(const Dual<T, N>& a) {
  Dual<T, N> r;
  r.v = sin(a.v);
  const T c = cos(a.v);
  for (int k = 0; k < N; ++k) r.d[k] = c * a.d[k];
  return r;
}
template <class T, int N>
Dual<T, N> cos(const Dual<T, N>& a) {
  Dual<T, N> r;
  r.v = cos(a.v);
  const T ms = -sin(a.v);
  for (int k = 0; k < N; ++k) r.d[k] = ms * a.d[k];
  return r;
}
template <class T, int N>
Dual<T, N> sqrt(const Dual<T, N>& a) {
  Dual<T, N> r;
  r.v = sqrt(a.v);
  const T s = 0.5 / r.v;
  for (int k = 0; k < N; ++k) r.d[k] = s * a.d[k];
  return r;
}

}  // namespace tcasim::ad
