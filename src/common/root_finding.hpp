#pragma once
/// Bracketed scalar root finding, the one root finder of the library: Brent's method
/// (inverse quadratic interpolation and secant steps, safeguarded by bisection), so a root
/// inside a sign change is always found, also of a discontinuous f. Users: the TCA laws
/// (src/tca), the inverse solver's blocked-tip cross-check (cosserat/inverse) and the
/// validation programs' calibrations. The rod solvers use their own Newton iterations.
#include <algorithm>
#include <cmath>
#include <optional>

namespace tcasim::roots {

/// Outcome of a bracketed solve.
struct RootResult {
  double x;        ///< root estimate: |bracket| <= 2 * tolerance, |f(x)| <= f_tol or f(x) == 0
  int iterations;  ///< function evaluations after the two end points
};

/// Finds x in [a, b] with f(x) = 0, given fa = f(a), fb = f(b) of opposite signs (or one
/// zero). Stops when the bracket is shorter than 2 (abs_tol + 4 eps |x|), |f(x)| <= f_tol
/// (0: only an exact zero) or after max_iterations evaluations (then x is the best
/// estimate). Returns nullopt when the end points do not bracket a root or f returns a
/// non-finite value (at an end or at an iterate).
template <class F>
std::optional<RootResult> brent(F&& f, double a, double b, double fa, double fb, double abs_tol,
                                int max_iterations = 200, double f_tol = 0.0) {
  constexpr double kEps = 2.220446049250313e-16;
  if (!std::isfinite(fa) || !std::isfinite(fb)) return std::nullopt;
  if (std::abs(fa) <= f_tol) return RootResult{a, 0};
  if (std::abs(fb) <= f_tol) return RootResult{b, 0};
  if ((fa > 0.0) == (fb > 0.0)) return std::nullopt;
  double c = a, fc = fa, d = b - a, e = d;
  int it = 0;
  for (; it < max_iterations; ++it) {
    if ((fb > 0.0) == (fc > 0.0)) {  // keep the root between b and c
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {  // b is the best estimate
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tol = abs_tol + 4.0 * kEps * std::abs(b);
    const double m = 0.5 * (c - b);
    if (std::abs(m) <= tol || std::abs(fb) <= f_tol) break;
    if (std::abs(e) >= tol && std::abs(fa) > std::abs(fb)) {
      // Interpolation: secant when a == c, inverse quadratic otherwise.
      double p, q;
      const double s = fb / fa;
      if (a == c) {
        p = 2.0 * m * s;
        q = 1.0 - s;
      } else {
        const double qa = fa / fc, r = fb / fc;
        p = s * (2.0 * m * qa * (qa - r) - (b - a) * (r - 1.0));
        q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0)
        q = -q;
      else
        p = -p;
      // Accept the step only if it stays well inside the bracket and shrinks fast enough.
      if (2.0 * p < std::min(3.0 * m * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    b += (std::abs(d) > tol) ? d : (m > 0.0 ? tol : -tol);
    fb = f(b);
    if (!std::isfinite(fb)) return std::nullopt;
  }
  return RootResult{b, it};
}

/// Scans [lo, hi] (in `intervals` equal steps, starting at `lo`) for the first sign change
/// of f and refines it with brent(). Returns nullopt if f keeps one sign at all grid points.
template <class F>
std::optional<RootResult> first_root(F&& f, double lo, double hi, int intervals, double abs_tol) {
  double x0 = lo, f0 = f(lo);
  if (f0 == 0.0) return RootResult{lo, 0};
  for (int i = 1; i <= intervals; ++i) {
    const double x1 = (i == intervals) ? hi : lo + (hi - lo) * i / intervals;
    const double f1 = f(x1);
    if ((f1 > 0.0) != (f0 > 0.0) || f1 == 0.0) return brent(f, x0, x1, f0, f1, abs_tol);
    x0 = x1;
    f0 = f1;
  }
  return std::nullopt;
}

}  // namespace tcasim::roots
