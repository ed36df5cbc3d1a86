#pragma once
/// The scalar coefficient functions shared by every SO(3)/SE(3) formula of the library, and
/// hat, once, templated on the scalar (double or ad::Dual of any nesting):
///   a = sin t / t,  b = (1 - cos t) / t^2,  c = (t - sin t) / t^3,
///   d = 1/t^2 - (1 + cos t) / (2 t sin t) = 1/t^2 - cot(t/2) / (2 t),
/// as functions of t^2 = |phi|^2, so they are smooth (and differentiable twice by nested
/// duals) through phi = 0. With K = hat(phi) [Sola2018]:
///   Exp(phi) = I + a K + b K^2,  Jr(phi) = I - b K + c K^2,  Jr^-1(phi) = I + K/2 + d K^2,
///   Jl(phi) = Jr(-phi),  and the SE(3) translation t = Jl(phi) rho.
/// Users: common/so3 (double rotations), cosserat/lie_rkmk4 (SE(3) exponential and its
/// derivative, one dual direction in t^2), beam_fe/element (first and second
/// t^2-derivatives by a nested dual).
#include <Eigen/Core>

#include "common/dual.hpp"

namespace tcasim::so3 {

/// Below this t^2 = |phi|^2 (angle 0.1 rad) the coefficients use their Taylor series in
/// t^2 through t^8: the first dropped term is < 1e-18 and its second t^2-derivative
/// < 1e-15, while the closed forms at t = 0.1 lose at most ~eps/t^2 ~ 1e-14 relative
/// (~1e-11 in second derivatives).
inline constexpr double kSeriesBelowAngleSquared = 1e-2;

/// The coefficients a, b, c, d of one rotation vector.
template <class S>
struct Coefficients {
  S a, b, c, d;
};

/// a, b, c, d at t2 = |phi|^2 >= 0.
template <class S>
Coefficients<S> coefficients(const S& t2) {
  using ad::inverse;
  using ad::value;
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (value(t2) < kSeriesBelowAngleSquared) {
    // a = sum (-x)^k/(2k+1)!, b = sum (-x)^k/(2k+2)!, c = sum (-x)^k/(2k+3)!,
    // d = 1/12 + x/720 + x^2/30240 + x^3/1209600 + x^4/47900160 + O(x^5).
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
  // 1 - cos t = 2 sin^2(t/2) avoids the cancellation of 1 - cos t; cot(t/2) stays finite
  // at t = pi, where (1 + cos t)/sin t is 0/0.
  return {s / t, 2.0 * sh * sh * inv_t2, (t - s) * inv_t2 / t, inv_t2 - ch / (2.0 * t * sh)};
}

/// hat(v) w = v x w, for any Eigen 3-vector expression.
template <class Derived>
Eigen::Matrix<typename Derived::Scalar, 3, 3> hat(const Eigen::MatrixBase<Derived>& v) {
  using S = typename Derived::Scalar;
  Eigen::Matrix<S, 3, 3> m;
  m << S(0), -v(2), v(1),  //
      v(2), S(0), -v(0),   //
      -v(1), v(0), S(0);
  return m;
}

}  // namespace tcasim::so3
