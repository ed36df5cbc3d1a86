#include "rod/reference_path.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "common/units.hpp"

namespace tcasim::rod {
namespace {

/// Nodes of the Gauss-Legendre rule per panel (exact for polynomials of degree 31).
constexpr int kGaussPoints = 16;
/// Panels per period at the start of the refinement, and the most panels tried.
constexpr int kInitialPanels = 4;
constexpr int kMaxPanels = 1 << 14;
/// Refinement stops when doubling the panels changes the integral by less than this
/// relative amount (a few units of round-off).
constexpr double kQuadratureRelativeTolerance = 4.0 * std::numeric_limits<double>::epsilon();

struct GaussRule {
  std::array<double, kGaussPoints> x{}, w{};  ///< on [-1, 1]
};

/// Gauss-Legendre nodes and weights by Newton's method on P_n from the Chebyshev guesses
/// cos(pi (i + 3/4)/(n + 1/2)) ([Press2007] Sec. 4.6.1, gauleg): converged to round-off.
GaussRule make_gauss_rule() {
  GaussRule g;
  const int n = kGaussPoints;
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(units::kPi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      // P_n(x) by the three-term recurrence; dp = P_n'(x).
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) <= 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    g.x[static_cast<std::size_t>(i)] = -x;
    g.x[static_cast<std::size_t>(n - 1 - i)] = x;
    g.w[static_cast<std::size_t>(i)] = w;
    g.w[static_cast<std::size_t>(n - 1 - i)] = w;
  }
  return g;
}

double composite_gauss(const std::function<double(double)>& f, double a, double b, int panels) {
  static const GaussRule g = make_gauss_rule();
  const double h = (b - a) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = a + (p + 0.5) * h;
    for (int i = 0; i < kGaussPoints; ++i) sum += g.w[i] * f(mid + 0.5 * h * g.x[i]);
  }
  return 0.5 * h * sum;
}

/// int_a^b f, the panels doubled until the value settles to round-off.
double integrate(const std::function<double(double)>& f, double a, double b) {
  if (b <= a) return 0.0;
  double previous = composite_gauss(f, a, b, kInitialPanels);
  for (int panels = 2 * kInitialPanels; panels <= kMaxPanels; panels *= 2) {
    const double current = composite_gauss(f, a, b, panels);
    if (std::abs(current - previous) <= kQuadratureRelativeTolerance * std::abs(current))
      return current;
    previous = current;
  }
  return previous;
}

}  // namespace

ReferencePath reference_path(const Routing& routing, const Eigen::Vector3d& omega_B_1_m,
                             double length_m) {
  return reference_path(routing, omega_B_1_m, 0.0, length_m);
}

ReferencePath reference_path(const Routing& routing, const Eigen::Vector3d& omega_B_1_m,
                             double s0_m, double s1_m) {
  if (routing.type == Routing::Type::kSpline) {
    // Piece by piece between the knots (the model version, with a constant omega*).
    RodModel body;
    body.set_reference_curvature(omega_B_1_m);
    return reference_path(routing, body, s0_m, s1_m);
  }
  const double length_m = s1_m - s0_m;
  ReferencePath out;
  out.min_axial_s_m = s0_m;
  const Eigen::Vector3d& w = omega_B_1_m;
  if (routing.type == Routing::Type::kStraight) {
    // r' = 0: q* = e3 + omega* x r is constant along s.
    const Eigen::Vector3d q = Eigen::Vector3d::UnitZ() + w.cross(routing.r(0.0));
    out.length_m = length_m * q.norm();
    out.min_axial = q.z();
    return out;
  }
  // Helix r = R (cos t, sin t, 0), t = phi + 2 pi k s, r' = 2 pi k R (-sin t, cos t, 0):
  //   q* = (-c sin t, c cos t, 1 + R (w1 sin t - w2 cos t)),  c = (2 pi k + w3) R,
  // and w1 sin t - w2 cos t = rho sin(t - theta), rho = |omega*_perp|, theta = atan2(w2, w1).
  const double R = routing.radius_m;
  const double k = routing.turns_per_m;
  const double c = (2.0 * units::kPi * k + w.z()) * R;
  const double rho = std::hypot(w.x(), w.y());
  const double theta = std::atan2(w.y(), w.x());
  const auto axial = [&](double t) { return 1.0 + R * rho * std::sin(t - theta); };
  const auto speed = [&](double t) { return std::hypot(c, axial(t)); };

  const double t0 = routing.phase_rad + 2.0 * units::kPi * k * s0_m;
  const double t1 = routing.phase_rad + 2.0 * units::kPi * k * s1_m;
  const double lo = std::min(t0, t1), hi = std::max(t0, t1);
  // Minimum of sin(t - theta) on [lo, hi]: -1 where t - theta = -pi/2 + 2 pi n lies inside,
  // else at an end.
  const double first_min =
      theta - 0.5 * units::kPi +
      2.0 * units::kPi * std::ceil((lo - theta + 0.5 * units::kPi) / (2.0 * units::kPi));
  const double t_min = first_min <= hi ? first_min : (axial(lo) <= axial(hi) ? lo : hi);
  out.min_axial = axial(t_min);
  out.min_axial_s_m = s0_m + (k != 0.0 ? (t_min - t0) / (2.0 * units::kPi * k) : 0.0);
  if (rho * R == 0.0 || k == 0.0) {
    // |q*| is constant along s (no bending precurvature, or a helix without turns).
    out.length_m = length_m * speed(t0);
    return out;
  }
  // ds = dt / (2 pi |k|); |q*(t)| has period 2 pi.
  const double period = 2.0 * units::kPi;
  const double whole = std::floor((hi - lo) / period);
  const double one_period = whole > 0.0 ? integrate(speed, lo, lo + period) : 0.0;
  const double rest = integrate(speed, lo + whole * period, hi);
  out.length_m = (whole * one_period + rest) / (2.0 * units::kPi * std::abs(k));
  return out;
}

ReferencePath reference_path(const Routing& routing, const RodModel& model) {
  return reference_path(routing, model, 0.0, model.length_m);
}

ReferencePath reference_path(const Routing& routing, const RodModel& model, double s0_m,
                             double s1_m) {
  const auto& prof = model.reference_curvature_profile;
  const bool spline = routing.type == Routing::Type::kSpline;
  if (!spline && prof[0].is_constant() && prof[1].is_constant() && prof[2].is_constant()) {
    return reference_path(routing, model.reference_curvature_at(0.0), s0_m, s1_m);
  }
  // A spline is smooth between its knots (docs/scenario-format.md "General routing and string
  // extent"): its knots are piece ends too, each piece evaluated on its own side of a kink.
  std::vector<double> knots{s0_m, s1_m};
  for (const Profile& p : prof) {
    for (double s : p.breakpoints()) {
      if (s > s0_m && s < s1_m) knots.push_back(s);
    }
  }
  if (spline) {
    for (double s : routing.knot_s_m) {
      if (s > s0_m && s < s1_m) knots.push_back(s);
    }
  }
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
  ReferencePath out;
  out.min_axial = HUGE_VAL;
  const bool straight = routing.type == Routing::Type::kStraight;
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double a = knots[k], b = knots[k + 1];
    if (!(b > a)) continue;
    const double mid = 0.5 * (a + b);
    const auto omega = [&](double s) {
      const Side side = s < mid ? Side::kRight : Side::kLeft;  // the piece's own limits
      return Eigen::Vector3d(prof[0].value(s, side), prof[1].value(s, side),
                             prof[2].value(s, side));
    };
    const auto q = [&](double s) -> Eigen::Vector3d {
      const Side side = s < mid ? Side::kRight : Side::kLeft;
      return Eigen::Vector3d::UnitZ() + omega(s).cross(routing.r(s, side)) + routing.dr(s, side);
    };
    out.length_m += integrate([&](double s) { return q(s).norm(); }, a, b);
    const int samples = straight ? 1 : 256;
    for (int i = 0; i <= samples; ++i) {
      const double s = a + (b - a) * i / samples;
      const double axial = q(s).z();
      if (axial < out.min_axial) {
        out.min_axial = axial;
        out.min_axial_s_m = s;
      }
    }
  }
  return out;
}

}  // namespace tcasim::rod
