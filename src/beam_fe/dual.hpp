#pragma once
/// Forward-mode dual numbers (nestable) and the rotation formulas exp, Jr and Jr^-1 as
/// functions of a rotation vector. The element kernel differentiates only the scalar
/// coefficients a, b, c, d of t^2 with them (nested scalar duals give their first and second
/// t^2-derivatives); the matrix formulas are kept for tests. Internal to beam_fe. The double-valued versions are src/common/so3 (tests
/// compare these against it); here the coefficients are functions of t^2 = |phi|^2, so
/// they stay smooth (and differentiable twice) through phi = 0.
#include <array>
#include <cmath>

namespace tcasim::beam_fe::ad {

/// v + sum_k d_k eps_k with eps_j eps_k = 0. T is double or another Dual (nesting gives
/// second derivatives).
template <class T, int N>
struct Dual {
  T v{};
  std::array<T, N> d{};
  Dual() = default;
  Dual(double x) : v(x) {}  // NOLINT: constants promote implicitly
};

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
template <class T, int N>
Dual<T, N> operator*(double a, const Dual<T, N>& b) {
  Dual<T, N> r;
  r.v = a * b.v;
  for (int k = 0; k < N; ++k) r.d[k] = a * b.d[k];
  return r;
}
template <class T, int N>
Dual<T, N> operator*(const Dual<T, N>& b, double a) {
  return a * b;
}
template <class T, int N>
Dual<T, N> operator+(const Dual<T, N>& a, double b) {
  Dual<T, N> r = a;
  r.v = r.v + b;
  return r;
}
template <class T, int N>
Dual<T, N> operator+(double b, const Dual<T, N>& a) {
  return a + b;
}
template <class T, int N>
Dual<T, N> operator-(const Dual<T, N>& a, double b) {
  return a + (-b);
}
template <class T, int N>
Dual<T, N> operator-(double b, const Dual<T, N>& a) {
  return (-a) + b;
}
template <class T, int N>
Dual<T, N> inverse(const Dual<T, N>& a) {
  Dual<T, N> r;
  r.v = 1.0 / a.v;
  const T minus_r2 = -(r.v * r.v);
  for (int k = 0; k < N; ++k) r.d[k] = minus_r2 * a.d[k];
  return r;
}
inline double inverse(double a) { return 1.0 / a; }
template <class T, int N>
Dual<T, N> operator/(const Dual<T, N>& a, const Dual<T, N>& b) {
  return a * inverse(b);
}
template <class T, int N>
Dual<T, N> operator/(double a, const Dual<T, N>& b) {
  return a * inverse(b);
}
template <class T, int N>
Dual<T, N> operator/(const Dual<T, N>& a, double b) {
  return (1.0 / b) * a;
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
  const T half_inv = 0.5 * inverse(r.v);
  for (int k = 0; k < N; ++k) r.d[k] = half_inv * a.d[k];
  return r;
}

/// Small fixed-size vector and matrix (row-major) over any scalar.
template <class S>
using V3 = std::array<S, 3>;
template <class S>
using M3 = std::array<S, 9>;

template <class S>
M3<S> hat(const V3<S>& v) {
  return {S(0.0), -v[2], v[1], v[2], S(0.0), -v[0], -v[1], v[0], S(0.0)};
}
template <class S>
M3<S> mul(const M3<S>& a, const M3<S>& b) {
  M3<S> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  return r;
}
/// alpha I + beta K + gamma K^2 for K = hat(phi).
template <class S>
M3<S> combine(const S& alpha, const S& beta, const S& gamma, const V3<S>& phi) {
  const M3<S> K = hat(phi);
  const M3<S> K2 = mul(K, K);
  M3<S> r;
  for (int i = 0; i < 9; ++i) r[i] = beta * K[i] + gamma * K2[i];
  for (int i = 0; i < 3; ++i) r[4 * i] = r[4 * i] + alpha;
  return r;
}

/// Below this t^2 = |phi|^2 the coefficients use their Taylor series in t^2 (through
/// t^8): the first dropped term is < 1e-18 and its second derivatives < 1e-15, while the
/// closed forms at t = 0.1 lose at most ~1e-11 relative in second derivatives.
inline constexpr double kSeriesBelowAngleSquared = 1e-2;

/// Coefficients a = sin t/t, b = (1 - cos t)/t^2, c = (t - sin t)/t^3,
/// d = 1/t^2 - cot(t/2)/(2 t) of t^2.
template <class S>
struct Coefficients {
  S a, b, c, d;
};
template <class S>
Coefficients<S> coefficients(const S& t2) {
  if (value(t2) < kSeriesBelowAngleSquared) {
    const S x = t2;
    const S x2 = x * x, x3 = x2 * x, x4 = x3 * x;
    return {1.0 - x / 6.0 + x2 / 120.0 - x3 / 5040.0 + x4 / 362880.0,
            0.5 - x / 24.0 + x2 / 720.0 - x3 / 40320.0 + x4 / 3628800.0,
            1.0 / 6.0 - x / 120.0 + x2 / 5040.0 - x3 / 362880.0 + x4 / 39916800.0,
            1.0 / 12.0 + x / 720.0 + x2 / 30240.0 + x3 / 1209600.0 + x4 / 47900160.0};
  }
  const S t = sqrt(t2);
  const S s = sin(t);
  const S sh = sin(0.5 * t);
  const S ch = cos(0.5 * t);
  const S inv_t2 = inverse(t2);
  return {s / t, 2.0 * sh * sh * inv_t2, (t - s) * inv_t2 / t, inv_t2 - ch / (2.0 * t * sh)};
}

template <class S>
S dot(const V3<S>& a, const V3<S>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// exp(hat(phi)) = I + a K + b K^2.
template <class S>
M3<S> exp_matrix(const V3<S>& phi) {
  const Coefficients<S> k = coefficients(dot(phi, phi));
  return combine(S(1.0), k.a, k.b, phi);
}
/// Jr(phi) = I - b K + c K^2.
template <class S>
M3<S> right_jacobian(const V3<S>& phi) {
  const Coefficients<S> k = coefficients(dot(phi, phi));
  return combine(S(1.0), -k.b, k.c, phi);
}
/// Jr^-1(phi) = I + K/2 + d K^2.
template <class S>
M3<S> right_jacobian_inverse(const V3<S>& phi) {
  const Coefficients<S> k = coefficients(dot(phi, phi));
  return combine(S(1.0), S(0.5), k.d, phi);
}

}  // namespace tcasim::beam_fe::ad
