#include "cosserat/inverse.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "common/error.hpp"
#include "common/root_finding.hpp"
#include "common/units.hpp"
#include "cosserat/internal/inverse_internal.hpp"

namespace tcasim::cosserat {

namespace {

using state_layout::kP;
using state_layout::kR;

/// Typical temperature scale [K] for the difference step (absolute temperatures ~300 K).
constexpr double kTypicalTemperature_K = 300.0;
/// Bracketed root finding on temperature (grasp cross-check): stop when the bracket is
/// below this [K] (well under the 0.01 degC agreement the validation asks for).
constexpr double kRootTolerance_K = 1e-8;
/// A closed TCA is moved this far above its coil-opening temperature [K] (see
/// opening_temperature): well above the onset's root tolerance, and a negligible actuation.
constexpr double kOpeningMargin_K = 1e-6;

}  // namespace

namespace inverse_internal {

bool is_tca(const rod::RodModel& m, int i) {
  return m.actuators[i].drive.type == rod::Drive::Type::kTca;
}

/// Index of actuator i's tension in the shooting unknowns (-1 for a tension drive).
int unknown_index(const rod::RodModel& m, int i) {
  if (!is_tca(m, i)) return -1;
  int k = 6;
  for (int j = 0; j < i; ++j) k += is_tca(m, j) ? 1 : 0;
  return k;
}

/// The inverse and grasp solvers adjust one temperature per TCA: a segmented drive (one
/// temperature per segment) is refused rather than silently made uniform.
void require_uniform_temperature(const rod::RodModel& m, int i) {
  const rod::Drive& d = m.actuators[i].drive;
  if (d.type != rod::Drive::Type::kTca || !d.segmented) return;
  throw InputError(
      "actuators[" + std::to_string(i) + "].drive.segments",
      "(" + std::to_string(d.segments.size()) + " segments)",
      "cannot be adjusted by the inverse and grasp solvers, which set one temperature per "
      "TCA: give '" +
          m.actuators[i].name +
          "' a uniform temperature_degC, or leave it out "
          "of the adjusted actuators");
}

double get_variable(const rod::RodModel& m, const rod::Loads& a, int i) {
  return is_tca(m, i) ? a.actuators[i].segments.front().temperature_K : a.actuators[i].tension_N;
}

void set_variable(const rod::RodModel& m, rod::Loads& a, int i, double v) {
  if (is_tca(m, i)) {
    a.set_temperature_K(static_cast<std::size_t>(i), v);
  } else {
    a.actuators[i].tension_N = v;
  }
}

Mat3 rotation_of(const Eigen::VectorXd& y) { return Eigen::Map<const Mat3>(y.data() + kR); }

/// vee of the skew part of M (a rotation increment dR R^T).
Vec3 skew_vee(const Mat3& M) {
  return 0.5 * Vec3(M(2, 1) - M(1, 2), M(0, 2) - M(2, 0), M(1, 0) - M(0, 1));
}

/// Tip pose difference (y_a - y_b) as (dp_W, vee(skew((R_a - R_b) R0^T))).
Eigen::Matrix<double, 6, 1> pose_difference(const Eigen::VectorXd& ya, const Eigen::VectorXd& yb,
                                            const Mat3& R0) {
  Eigen::Matrix<double, 6, 1> d;
  d.head<3>() = ya.segment<3>(kP) - yb.segment<3>(kP);
  d.tail<3>() = skew_vee((rotation_of(ya) - rotation_of(yb)) * R0.transpose());
  return d;
}

/// d phi / dT of actuator i's TCA row (tca::contact_residual, the TCA law with coil contact)
/// at tension T and elongation delta for a uniform shift of its segment temperatures [N/K]:
/// -dF/dT while the coils are open, 0 while they are closed.
double tca_dphi_dT(const rod::RodModel& m, const rod::Loads& a, int i, double tension_N,
                   double delta_m) {
  return tca::contact_residual(*m.actuators[i].drive.tca, tension_N, delta_m,
                               a.actuators[i].segments)
      .dphi_dT_N_K;
}

/// A TCA whose coils are all closed in the solved state (tension x[u]) carries whatever
/// strut force equilibrium needs: the rod does not change with its temperature up to the
/// onset, where the coils open under that force (Tca::onset_temperature). Returns the
/// temperature just above that onset (the same state, now with a temperature sensitivity) if
/// it lies below t_hi_K; none for an open TCA, a tension drive or an onset out of range.
std::optional<double> opening_temperature(const rod::RodModel& m, const rod::Loads& a, int i,
                                          const Solution& solution, double t_hi_K) {
  if (!is_tca(m, i)) return std::nullopt;
  const tca::Tca& tca = *m.actuators[i].drive.tca;
  const double tension_N = solution.unknowns[unknown_index(m, i)];
  const auto& segs = a.actuators[i].segments;
  for (const tca::SegmentContact& c : tca::segment_contacts(tca, tension_N, segs)) {
    if (!c.coils_closed) return std::nullopt;
  }
  const double t_K = segs.front().temperature_K;
  if (t_K >= t_hi_K) return std::nullopt;
  const std::optional<double> onset = tca.onset_temperature(tension_N, t_K, t_hi_K);
  if (!onset || *onset + kOpeningMargin_K >= t_hi_K) return std::nullopt;
  return *onset + kOpeningMargin_K;
}

double variable_scale(const rod::RodModel& m, int i, double v, double Fc) {
  return is_tca(m, i) ? std::max(std::abs(v), kTypicalTemperature_K) : std::max(std::abs(v), Fc);
}

}  // namespace inverse_internal

using namespace inverse_internal;

const char* to_string(InverseResult::Status s) {
  switch (s) {
    case InverseResult::Status::kConverged:
      return "converged";
    case InverseResult::Status::kUnreachable:
      return "unreachable";
    case InverseResult::Status::kMaxIterations:
      return "max_iterations";
    case InverseResult::Status::kForwardFailed:
      return "forward_failed";
  }
  return "unknown";
}

double blocked_normal_force_N(ShootingSolver& constrained_solver, const rod::RodModel& model,
                              double t_K, Solution& solution) {
  require(model.tip_constraint && model.tip_constraint->normal_W, "tip_constraint.normal",
          "(missing)", "a blocked-tip normal force needs a tip_constraint with a normal");
  rod::Loads a = rod::Loads::from_model(model);
  for (int i = 0; i < static_cast<int>(model.actuators.size()); ++i) {
    if (is_tca(model, i)) a.set_temperature_K(static_cast<std::size_t>(i), t_K);
  }
  const Summary s = constrained_solver.solve(a, solution);
  if (!s.converged()) return std::numeric_limits<double>::quiet_NaN();
  // Normal-only reaction lambda n is the last unknown (shooting.hpp): the object pushes
  // the finger back with the normal force -lambda.
  return -solution.unknowns[solution.unknowns.size() - 1];
}

GraspResult solve_grasp(const rod::RodModel& model, const Options& shooting_options,
                        const GraspOptions& options) {
  if (!model.obstacles.empty()) {
    throw DomainError(
        "grasp: obstacles are not supported by the grasp solve yet (its finger presses the "
        "tip_constraint; remove the scenario's obstacles)");
  }
  require(model.tip_constraint.has_value() && model.tip_constraint->normal_W.has_value(),
          "tip_constraint.normal", "(missing)",
          "grasp needs the scenario's tip_constraint with a \"normal\" (the contact direction, "
          "from the finger toward the object)");
  require(options.mass_kg > 0.0, "mass", options.mass_kg, "must be > 0");
  require(options.friction > 0.0, "friction", options.friction, "must be > 0");
  require(options.fingers >= 1, "fingers", options.fingers, "must be >= 1");
  require(options.temperature_tolerance_K > 0.0, "temperature_tolerance_K",
          options.temperature_tolerance_K, "must be > 0");
  int act = -1, n_tca = 0;
  for (int i = 0; i < static_cast<int>(model.actuators.size()); ++i) {
    if (is_tca(model, i)) {
      act = i;
      ++n_tca;
    }
  }
  require(n_tca == 1, "actuators", n_tca, "grasp needs exactly one TCA-driven actuator per finger");
  require_uniform_temperature(model, act);
  Eigen::VectorXd lo, hi;
  actuation_bounds(model, {act}, options.max_temperature_K, std::numeric_limits<double>::infinity(),
                   lo, hi);
  const double t_lo = lo[0], t_hi = hi[0];

  GraspResult res;
  // [Pawlowski2019] Eq. (44): mu n F = m g.
  res.required_force_N =
      options.mass_kg * units::kStandardGravity_m_s2 / (options.friction * options.fingers);
  const double F_req = res.required_force_N;
  const Vec3 n = *model.tip_constraint->normal_W;
  const double x0 = n.dot(model.tip_constraint->position_W_m);

  // Reachability first: the blocked force at the maximum temperature (one forward solve).
  ShootingSolver cs(model, shooting_options);
  {
    Solution hot;
    const double f_max = blocked_normal_force_N(cs, model, t_hi, hot);
    if (!(f_max >= F_req)) {
      res.temperature_K = t_hi;
      res.blocked_normal_force_N = f_max;
      if (hot.tip_state.size() > 0) res.tip_position_W_m = hot.tip_state.segment<3>(kP);
      res.message =
          std::isfinite(f_max)
              ? "not reachable: the blocked-tip normal force at the maximum temperature " +
                    format_value(units::K_to_degC(t_hi)) + " degC is " + format_value(f_max) +
                    " N, below the required " + format_value(F_req) + " N"
              : "the blocked-tip solve at the maximum temperature did not converge";
      return res;
    }
  }

  // Eq. (43) on the free finger loaded at the tip by the contact force -f n.
  rod::RodModel free = model;
  free.tip_constraint.reset();
  ShootingSolver fs(free, shooting_options);
  rod::Loads a = rod::Loads::from_model(free);
  const Vec3 applied = a.tip_force_W_N;
  double T = t_lo, f = 0.0;
  a.set_temperature_K(static_cast<std::size_t>(act), T);
  Solution sol;
  bool converged = false;
  std::string why;
  for (int it = 0; it < options.max_iterations; ++it) {
    a.tip_force_W_N = applied - f * n;
    const Summary s = fs.solve(a, sol);
    if (!s.converged()) {
      why = "forward solve of the loaded free finger failed at " +
            format_value(units::K_to_degC(T)) + " degC: " + s.message;
      break;
    }
    TipDerivatives d;
    if (!tip_derivatives(fs, free, a, sol, {act}, options.method, d)) {
      why = "tip Jacobian evaluation failed";
      break;
    }
    // Closed coils: no temperature sensitivity until they open (J_n = 0); move to the
    // opening temperature, which leaves the loaded finger where it is.
    if (const std::optional<double> t_open = opening_temperature(free, a, act, sol, t_hi)) {
      T = *t_open;
      a.set_temperature_K(static_cast<std::size_t>(act), T);
      res.iterations = it + 1;
      continue;
    }
    const double x = n.dot(d.tip_state.segment<3>(kP));
    const double Jn = n.dot(d.J.block<3, 1>(0, 0));       // dx/dT
    const double Cn = -n.dot(d.C.block<3, 3>(0, 0) * n);  // dx/df (W = -f n)
    const double df = F_req - f;
    // [Pawlowski2019] Eq. (43) dq = -J^-1 C dW, with the Eq. (40) correction J^-1 dx for the
    // drift of the contact coordinate from its held value.
    const double dT = ((x0 - x) - Cn * df) / Jn;
    res.iterations = it + 1;
    if (!std::isfinite(dT)) {
      why = "the tip does not move along the normal with temperature (J_n = 0)";
      break;
    }
    f = F_req;
    if (std::abs(dT) <= options.temperature_tolerance_K && df == 0.0) {
      T += dT;
      converged = true;
      break;
    }
    // Leaving [t_lo, t_hi]: try the bound once; a second step out of it means the force is
    // not reached inside the range.
    double T_new = T + dT;
    if (T_new > t_hi || T_new < t_lo) {
      const bool above = T_new > t_hi;
      const double bound = above ? t_hi : t_lo;
      if (T == bound) {
        why = "the required normal force " + format_value(F_req) + " N needs a temperature " +
              (above ? "above the maximum " : "below the ambient ") +
              format_value(units::K_to_degC(bound)) + " degC (Eq. (43) iteration)";
        break;
      }
      T_new = bound;
    }
    T = T_new;
    a.set_temperature_K(static_cast<std::size_t>(act), T);
  }
  if (!converged && why.empty()) {
    why = "Eq. (43) iteration reached max_iterations = " + std::to_string(options.max_iterations);
  }
  res.temperature_K = T;

  // Blocked-tip forward solve at the found temperature.
  Solution bsol;
  res.blocked_normal_force_N = blocked_normal_force_N(cs, model, T, bsol);
  if (bsol.tip_state.size() > 0) res.tip_position_W_m = bsol.tip_state.segment<3>(kP);

  if (options.cross_check && converged) {
    // Bracketed root of g(T) = F_blocked(T) - F_req on [t_lo, t_hi] (Brent's method).
    Solution rsol;
    auto g = [&](double t) {
      ++res.root_evaluations;
      return blocked_normal_force_N(cs, model, t, rsol) - F_req;
    };
    const double ga = g(t_lo), gb = g(t_hi);
    if (!std::isfinite(ga) || !std::isfinite(gb)) {
      why = "blocked-tip solve failed at a bracket end";
      converged = false;
    } else if ((ga > 0.0) == (gb > 0.0) && ga != 0.0 && gb != 0.0) {
      why = "the blocked-tip force minus the required force does not change sign on [" +
            format_value(units::K_to_degC(t_lo)) + ", " + format_value(units::K_to_degC(t_hi)) +
            "] degC";
      converged = false;
    } else {
      // A bracket shorter than 2 * (kRootTolerance_K / 2): the root to kRootTolerance_K.
      const auto root = roots::brent(g, t_lo, t_hi, ga, gb, 0.5 * kRootTolerance_K);
      if (root) {
        res.root_temperature_K = root->x;
      } else {
        converged = false;
        why = "blocked-tip solve failed";
      }
    }
  }
  res.converged = converged;
  res.message = converged ? std::string() : why;
  return res;
}

}  // namespace tcasim::cosserat
