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
#include "common/finite_difference.hpp"
#include "common/root_finding.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"

namespace tcasim::cosserat {

namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

using state_layout::kDelta;
using state_layout::kP;
using state_layout::kR;

/// Typical temperature scale [K] for the difference step (absolute temperatures ~300 K).
constexpr double kTypicalTemperature_K = 300.0;
/// Bounded least squares is stationary when the projected gradient |J^T e| is below this
/// fraction of |J| |e| (the cosine between the error and the reachable directions): J is
/// exact to ~1e-10 (sensitivities) or ~1e-8 (forward differences), so 1e-7 is attainable
/// and locates the optimum well within the tip tolerance (the distance is second order).
constexpr double kStationarity = 1e-7;
/// A step is considered nil (no move possible inside the bounds) below this fraction of
/// the variables' scale.
constexpr double kNilStep = 1e-13;
/// Trust region on the step, measured relative to each variable's scale (300 K, or the
/// tension scale): starting radius 0.1 (30 K, the TCA laws are strongly nonlinear in T),
/// maximum 1; the gain ratio rho = actual / predicted decrease of |e|^2 accepts a step
/// (rho > kAcceptRatio), widens (> kGoodRatio) or shrinks (< kPoorRatio) the radius.
constexpr double kTrustStart = 0.1;
constexpr double kTrustMax = 1.0;
constexpr double kTrustShrink = 0.25;
constexpr double kAcceptRatio = 1e-4;
constexpr double kGoodRatio = 0.75;
constexpr double kPoorRatio = 0.25;
constexpr int kTrustTrials = 30;
/// Bracketed root finding on temperature (grasp cross-check): stop when the bracket is
/// below this [K] (well under the 0.01 degC agreement the validation asks for).
constexpr double kRootTolerance_K = 1e-8;
/// A closed TCA is moved this far above its coil-opening temperature [K] (see
/// opening_temperature): well above the onset's root tolerance, and a negligible actuation.
constexpr double kOpeningMargin_K = 1e-6;

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
  throw InputError("actuators[" + std::to_string(i) + "].drive.segments",
                   "(" + std::to_string(d.segments.size()) + " segments)",
                   "cannot be adjusted by the inverse and grasp solvers, which set one temperature per "
                   "TCA: give '" + m.actuators[i].name + "' a uniform temperature_degC, or leave it out "
                   "of the adjusted actuators");
}

double get_variable(const rod::RodModel& m, const Actuation& a, int i) {
  return is_tca(m, i) ? a.actuators[i].segments.front().temperature_K : a.actuators[i].tension_N;
}

void set_variable(const rod::RodModel& m, Actuation& a, int i, double v) {
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
double tca_dphi_dT(const rod::RodModel& m, const Actuation& a, int i, double tension_N,
                   double delta_m) {
  return tca::contact_residual(*m.actuators[i].drive.tca, tension_N, delta_m, a.actuators[i].segments)
      .dphi_dT_N_K;
}

/// A TCA whose coils are all closed in the solved state (tension x[u]) carries whatever
/// strut force equilibrium needs: the rod does not change with its temperature up to the
/// onset, where the coils open under that force (Tca::onset_temperature). Returns the
/// temperature just above that onset (the same state, now with a temperature sensitivity) if
/// it lies below t_hi_K; none for an open TCA, a tension drive or an onset out of range.
std::optional<double> opening_temperature(const rod::RodModel& m, const Actuation& a, int i,
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

}  // namespace

const char* to_string(InverseResult::Status s) {
  switch (s) {
    case InverseResult::Status::kConverged: return "converged";
    case InverseResult::Status::kUnreachable: return "unreachable";
    case InverseResult::Status::kMaxIterations: return "max_iterations";
    case InverseResult::Status::kForwardFailed: return "forward_failed";
  }
  return "unknown";
}

bool tip_derivatives(ShootingSolver& solver, const rod::RodModel& model,
                     const Actuation& actuation, const Solution& solution,
                     const std::vector<int>& variables, TipDerivativeMethod method,
                     TipDerivatives& out) {
  require(!model.tip_constraint, "model.tip_constraint", "(set)",
          "must be absent: J and C describe a free tip");
  const int nx = solver.unknown_count();
  const int nq = static_cast<int>(variables.size());
  const double Fc = solver.characteristic_force_N();
  const double L = model.length_m;
  require(solution.unknowns.size() == nx, "solution.unknowns", static_cast<double>(solution.unknowns.size()),
          "must hold the solver's " + std::to_string(nx) + " unknowns");
  for (int i : variables) {
    require(i >= 0 && i < static_cast<int>(model.actuators.size()), "variables", i,
            "must index a model actuator");
  }
  const Eigen::VectorXd& x = solution.unknowns;
  out.ivp_count = 0;
  Eigen::MatrixXd Bu(nx, nx), Eu(6, nx), Bq(nx, nq), Eq(6, nq), BW(nx, 6), EW(6, 6);
  Eigen::VectorXd r0, y0, rp, rm, yp, ym;

  if (method == TipDerivativeMethod::kSensitivity) {
    Eigen::MatrixXd dy;
    ++out.ivp_count;
    if (!solver.tip_sensitivities(actuation, x, r0, Bu, y0, dy)) return false;
    const Mat3 R0 = rotation_of(y0);
    for (int j = 0; j < nx; ++j) {
      Eu.block<3, 1>(0, j) = dy.block<3, 1>(kP, j);
      const Eigen::Map<const Mat3> dR(dy.col(j).data() + kR);
      Eu.block<3, 1>(3, j) = skew_vee(dR * R0.transpose());
    }
    // Temperatures enter only the TCA residual r_k = phi(T_k, delta_k, temps) / F_c.
    Eq.setZero();
    Bq.setZero();
    for (int k = 0; k < nq; ++k) {
      const int i = variables[k];
      if (is_tca(model, i)) {
        const int u = unknown_index(model, i);
        Bq(u, k) = tca_dphi_dT(model, actuation, i, x[u], y0[kDelta + i]) / Fc;
        continue;
      }
      // A tension drive enters the IVP: central differences (two IVPs).
      Actuation a = actuation;
      const double v = get_variable(model, actuation, i);
      const double h = fd::kCentralRelativeStep * variable_scale(model, i, v, Fc);
      set_variable(model, a, i, v + h);
      out.ivp_count += 2;
      if (!solver.residual_and_tip_state(a, x, rp, yp)) return false;
      set_variable(model, a, i, v - h);
      if (!solver.residual_and_tip_state(a, x, rm, ym)) return false;
      Bq.col(k) = (rp - rm) / (2.0 * h);
      Eq.col(k) = pose_difference(yp, ym, R0) / (2.0 * h);
    }
    // The tip wrench enters only the tip conditions: dr_n/dF_e = -R^T/F_c,
    // dr_m/dM_e = -R^T/(F_c L).
    BW.setZero();
    EW.setZero();
    BW.block<3, 3>(0, 0) = -R0.transpose() / Fc;
    BW.block<3, 3>(3, 3) = -R0.transpose() / (Fc * L);
  } else {
    const bool central = method == TipDerivativeMethod::kCentralDifference;
    const double step = fd::relative_step(central);  // common/finite_difference.hpp
    ++out.ivp_count;
    if (!solver.residual_and_tip_state(actuation, x, r0, y0)) return false;
    const Mat3 R0 = rotation_of(y0);
    // One perturbed evaluation pair: (eval(+h) - eval(-h)) / 2h or (eval(+h) - base) / h.
    // `backward`: the variable sits within h of its upper limit (a TCA at its material's
    // maximum temperature): one-sided differences toward -h instead, second order
    // (3 f(0) - 4 f(-h) + f(-2h)) / 2h when central.
    auto column = [&](auto&& eval, double h, Eigen::Ref<Eigen::VectorXd> B,
                      Eigen::Ref<Eigen::VectorXd> E, bool backward = false) {
      if (backward) {
        out.ivp_count += central ? 2 : 1;
        if (!eval(-h, rm, ym)) return false;
        if (!central) {
          B = (r0 - rm) / h;
          E = pose_difference(y0, ym, R0) / h;
          return true;
        }
        if (!eval(-2.0 * h, rp, yp)) return false;
        B = (3.0 * r0 - 4.0 * rm + rp) / (2.0 * h);
        E = (-4.0 * pose_difference(ym, y0, R0) + pose_difference(yp, y0, R0)) / (2.0 * h);
        return true;
      }
      ++out.ivp_count;
      if (!eval(+h, rp, yp)) return false;
      if (central) {
        ++out.ivp_count;
        if (!eval(-h, rm, ym)) return false;
        B = (rp - rm) / (2.0 * h);
        E = pose_difference(yp, ym, R0) / (2.0 * h);
      } else {
        B = (rp - r0) / h;
        E = pose_difference(yp, y0, R0) / h;
      }
      return true;
    };
    // E_u, B_u: perturbed initial unknowns (typical scales as in the shooting solver: the
    // strain deviations nu(0) - nu* of F_c, curvatures 1/L, tensions F_c).
    const Eigen::Vector3d K_nu = model.shear_extension_stiffness();
    Eigen::VectorXd xp = x;
    for (int j = 0; j < nx; ++j) {
      const double typ = j < 3 ? Fc / K_nu[j] : (j < 6 ? 1.0 / L : Fc);
      const double h = step * std::max(std::abs(x[j]), typ);
      auto eval = [&](double hh, Eigen::VectorXd& r, Eigen::VectorXd& y) {
        xp[j] = x[j] + hh;
        const bool ok = solver.residual_and_tip_state(actuation, xp, r, y);
        xp[j] = x[j];
        return ok;
      };
      if (!column(eval, h, Bu.col(j), Eu.col(j))) return false;
    }
    // E_q, B_q: perturbed actuation.
    for (int k = 0; k < nq; ++k) {
      const int i = variables[k];
      const double v = get_variable(model, actuation, i);
      const double h = step * variable_scale(model, i, v, Fc);
      Actuation a = actuation;
      auto eval = [&](double hh, Eigen::VectorXd& r, Eigen::VectorXd& y) {
        set_variable(model, a, i, v + hh);
        return solver.residual_and_tip_state(a, x, r, y);
      };
      const double v_max = is_tca(model, i)
                               ? model.actuators[i].drive.tca->material().max_temperature_K
                               : std::numeric_limits<double>::infinity();
      if (!column(eval, h, Bq.col(k), Eq.col(k), v + h > v_max)) return false;
    }
    // E_W, B_W: perturbed tip wrench.
    for (int c = 0; c < 6; ++c) {
      Actuation a = actuation;
      const double w0 = c < 3 ? actuation.tip_force_W_N[c] : actuation.tip_moment_W_Nm[c - 3];
      const double h = step * std::max(std::abs(w0), c < 3 ? Fc : Fc * L);
      auto eval = [&](double hh, Eigen::VectorXd& r, Eigen::VectorXd& y) {
        if (c < 3) a.tip_force_W_N[c] = w0 + hh; else a.tip_moment_W_Nm[c - 3] = w0 + hh;
        return solver.residual_and_tip_state(a, x, r, y);
      };
      if (!column(eval, h, BW.col(c), EW.col(c))) return false;
    }
  }
  // [Pawlowski2019] Eqs. (41)-(42): J = E_q - E_u B_u^-1 B_q, C = E_W - E_u B_u^-1 B_W.
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(Bu);
  const Eigen::MatrixXd du_dq = -lu.solve(Bq);
  const Eigen::MatrixXd du_dW = -lu.solve(BW);
  out.J = Eq + Eu * du_dq;
  out.C = EW + Eu * du_dW;
  out.du_dq = du_dq;
  out.B_u = std::move(Bu);
  out.tip_state = y0;
  return out.J.allFinite() && out.C.allFinite();
}

void actuation_bounds(const rod::RodModel& model, const std::vector<int>& variables,
                      double max_temperature_K, double max_tension_N, Eigen::VectorXd& lower,
                      Eigen::VectorXd& upper) {
  const int nq = static_cast<int>(variables.size());
  lower.resize(nq);
  upper.resize(nq);
  for (int k = 0; k < nq; ++k) {
    const int i = variables[k];
    if (is_tca(model, i)) {
      const tca::Material& mat = model.actuators[i].drive.tca->material();
      lower[k] = mat.reference_temperature_K;
      upper[k] = std::isnan(max_temperature_K) ? mat.max_temperature_K
                                                : std::min(mat.max_temperature_K, max_temperature_K);
      require(upper[k] > lower[k], "max_temperature_degC", units::K_to_degC(upper[k]),
              "must be above the ambient (reference) temperature " +
                  format_value(units::K_to_degC(lower[k])) + " degC of actuator '" +
                  model.actuators[i].name + "'");
    } else {
      lower[k] = 0.0;
      upper[k] = max_tension_N;
      require(upper[k] > 0.0, "max_tension_N", max_tension_N, "must be > 0");
    }
  }
}

namespace {

/// Least-squares step of min |A dq - e|^2 + mu |D dq|^2 with lo <= q + dq <= hi: variables
/// whose step leaves the box are fixed at the violated bound and the rest re-solved
/// (minimum-norm for a redundant A).
Eigen::VectorXd bounded_step(const Eigen::MatrixXd& A, const Eigen::VectorXd& e, double mu,
                             const Eigen::VectorXd& D, const Eigen::VectorXd& q,
                             const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const int m = static_cast<int>(q.size());
  Eigen::VectorXd dq = Eigen::VectorXd::Zero(m);
  std::vector<bool> fixed(m, false);
  for (int pass = 0; pass <= m; ++pass) {
    std::vector<int> free_idx;
    Eigen::VectorXd ef = e;
    for (int i = 0; i < m; ++i) {
      if (fixed[i]) ef -= A.col(i) * dq[i]; else free_idx.push_back(i);
    }
    if (free_idx.empty()) break;
    const int nf = static_cast<int>(free_idx.size());
    Eigen::MatrixXd Af(A.rows() + nf, nf);
    Af.setZero();
    for (int c = 0; c < nf; ++c) {
      Af.block(0, c, A.rows(), 1) = A.col(free_idx[c]);
      Af(A.rows() + c, c) = std::sqrt(mu) * D[free_idx[c]];
    }
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(A.rows() + nf);
    rhs.head(A.rows()) = ef;
    const Eigen::VectorXd s = Af.completeOrthogonalDecomposition().solve(rhs);
    bool violated = false;
    for (int c = 0; c < nf; ++c) {
      const int i = free_idx[c];
      dq[i] = s[c];
      if (q[i] + dq[i] > hi[i]) { dq[i] = hi[i] - q[i]; fixed[i] = true; violated = true; }
      if (q[i] + dq[i] < lo[i]) { dq[i] = lo[i] - q[i]; fixed[i] = true; violated = true; }
    }
    if (!violated) break;
  }
  return dq;
}

}  // namespace

InverseResult solve_inverse(ShootingSolver& solver, const rod::RodModel& model,
                            const Eigen::Vector3d& target_W_m, const InverseOptions& options,
                            Actuation& actuation, Solution& solution) {
  require(target_W_m.allFinite(), "target", target_W_m.norm(), "must be finite");
  require(options.tolerance_m > 0.0, "options.tolerance_m", options.tolerance_m, "must be > 0");
  require(options.max_iterations >= 1, "options.max_iterations", options.max_iterations,
          "must be >= 1");
  const bool any_component = options.components[0] || options.components[1] || options.components[2];
  require(any_component || options.target_R_WB.has_value(), "options.components", 0.0,
          "must select at least one tip position component (or give an orientation target)");
  InverseResult res;
  res.actuators = options.actuators;
  if (res.actuators.empty()) {
    for (int i = 0; i < static_cast<int>(model.actuators.size()); ++i) res.actuators.push_back(i);
  }
  require(!res.actuators.empty(), "actuators", 0.0, "the model has no actuator to adjust");
  for (int i : res.actuators) {
    require(i >= 0 && i < static_cast<int>(model.actuators.size()), "options.actuators", i,
            "must index a model actuator");
    require_uniform_temperature(model, i);
  }
  const std::vector<int>& vars = res.actuators;
  const int nq = static_cast<int>(vars.size());
  Eigen::VectorXd lo, hi;
  actuation_bounds(model, vars, options.max_temperature_K, options.max_tension_N, lo, hi);
  Eigen::VectorXd q(nq);
  for (int k = 0; k < nq; ++k) {
    q[k] = std::clamp(get_variable(model, actuation, vars[k]), lo[k], hi[k]);
    set_variable(model, actuation, vars[k], q[k]);
  }
  const double L = model.length_m;
  std::vector<int> rows;
  for (int c = 0; c < 3; ++c) {
    if (options.components[c]) rows.push_back(c);
  }
  if (options.target_R_WB) {
    for (int c = 3; c < 6; ++c) rows.push_back(c);
  }
  const int ne = static_cast<int>(rows.size());
  // Targeted error e (position rows [m], orientation rows x L [m]) at tip state y.
  auto error_of = [&](const Eigen::VectorXd& y) {
    Eigen::VectorXd e(ne);
    const Vec3 dp = target_W_m - y.segment<3>(kP);
    Vec3 dth = Vec3::Zero();
    if (options.target_R_WB) dth = so3::log(Mat3(*options.target_R_WB * rotation_of(y).transpose()));
    for (int k = 0; k < ne; ++k) e[k] = rows[k] < 3 ? dp[rows[k]] : L * dth[rows[k] - 3];
    return e;
  };
  auto finish = [&](InverseResult::Status st, std::string why, const Eigen::VectorXd& y) {
    res.status = st;
    res.message = std::move(why);
    res.values = q;
    res.at_bound.assign(nq, false);
    for (int k = 0; k < nq; ++k) res.at_bound[k] = q[k] <= lo[k] || q[k] >= hi[k];
    if (y.size() > kDelta) {
      res.tip_position_W_m = y.segment<3>(kP);
      res.tip_R_WB = rotation_of(y);
      Vec3 dp = target_W_m - res.tip_position_W_m;
      for (int c = 0; c < 3; ++c) {
        if (!options.components[c]) dp[c] = 0.0;
      }
      res.distance_m = dp.norm();
      if (options.target_R_WB) {
        res.orientation_error_rad =
            so3::log(Mat3(*options.target_R_WB * res.tip_R_WB.transpose())).norm();
      }
    }
    return res;
  };

  ++res.forward_solves;
  Summary s = solver.solve(actuation, solution);
  if (!s.converged()) {
    return finish(InverseResult::Status::kForwardFailed,
                  std::string("forward solve at the starting actuation failed: ") + s.message,
                  Eigen::VectorXd());
  }
  double radius = kTrustStart;
  TipDerivatives d;
  // A TCA with closed coils has no temperature sensitivity (a zero column of J) until its
  // coils open, and every temperature up to that onset gives the same state: such a TCA is
  // moved to its opening temperature, which is also its lower bound for this step.
  Eigen::VectorXd lo_step = lo;
  for (int it = 0;; ++it) {
    lo_step = lo;
    bool moved = false;
    for (int k = 0; k < nq; ++k) {
      const std::optional<double> t_open = opening_temperature(model, actuation, vars[k], solution, hi[k]);
      if (!t_open) continue;
      q[k] = std::max(q[k], *t_open);
      lo_step[k] = q[k];
      set_variable(model, actuation, vars[k], q[k]);
      moved = true;
    }
    if (moved) {
      ++res.forward_solves;
      s = solver.solve(actuation, solution);
      if (!s.converged()) {
        return finish(InverseResult::Status::kForwardFailed,
                      std::string("forward solve at the coil-opening temperature failed: ") + s.message,
                      solution.tip_state);
      }
    }
    if (!tip_derivatives(solver, model, actuation, solution, vars, options.method, d)) {
      return finish(InverseResult::Status::kForwardFailed, "tip Jacobian evaluation failed",
                    solution.tip_state);
    }
    const Eigen::VectorXd& y = d.tip_state;
    const Eigen::VectorXd e = error_of(y);
    const double err = e.norm();
    if (e.lpNorm<Eigen::Infinity>() <= options.tolerance_m && err <= options.tolerance_m) {
      return finish(InverseResult::Status::kConverged, "", y);
    }
    Eigen::MatrixXd A(ne, nq);
    for (int k = 0; k < ne; ++k) {
      A.row(k) = rows[k] < 3 ? d.J.row(rows[k]) : Eigen::RowVectorXd(L * d.J.row(rows[k]));
    }
    // Projected gradient of |e|^2/2 (descent direction A^T e): a variable at a bound whose
    // descent direction points out of the box is held.
    Eigen::VectorXd g = A.transpose() * e;
    for (int k = 0; k < nq; ++k) {
      if ((q[k] >= hi[k] && g[k] > 0.0) || (q[k] <= lo_step[k] && g[k] < 0.0)) g[k] = 0.0;
    }
    if (g.norm() <= kStationarity * A.norm() * err) {
      return finish(InverseResult::Status::kUnreachable,
                    "target not reachable within the actuation bounds: least-squares distance " +
                        format_value(err) + " m",
                    y);
    }
    if (it >= options.max_iterations) {
      return finish(InverseResult::Status::kMaxIterations,
                    "reached max_iterations = " + std::to_string(options.max_iterations) +
                        " with distance " + format_value(err) + " m",
                    y);
    }
    Eigen::VectorXd D(nq), scale(nq);
    for (int k = 0; k < nq; ++k) {
      D[k] = std::max(A.col(k).norm(), 1e-300);
      scale[k] = variable_scale(model, vars[k], q[k], solver.characteristic_force_N());
    }
    bool accepted = false;
    for (int trial = 0; trial < kTrustTrials && !accepted; ++trial) {
      // [Pawlowski2019] Eq. (40) with dW = 0: e = J dq, solved in the bounded (minimum-norm)
      // least-squares sense, then shortened to the trust radius.
      Eigen::VectorXd dq = bounded_step(A, e, 0.0, D, q, lo_step, hi);
      const double size = (dq.array().abs() / scale.array()).maxCoeff();
      if (size <= kNilStep) break;
      const bool truncated = size > radius;
      if (truncated) dq *= radius / size;  // stays in the box (q and q + dq are inside)
      Actuation at = actuation;
      for (int k = 0; k < nq; ++k) set_variable(model, at, vars[k], q[k] + dq[k]);
      Solution st = solution;
      // First-order warm start du = -B_u^-1 B_q dq (the coarse level restarts).
      st.unknowns += d.du_dq * dq;
      st.coarse_unknowns.resize(0);
      st.jacobian = d.B_u;  // fresh at the old point: Newton starts without recomputing it
      st.path.clear();      // this first-order start, not an extrapolation along past trials
      ++res.forward_solves;
      const Summary ss = solver.solve(at, st);
      const double predicted = err * err - (e - A * dq).squaredNorm();
      const double err_new = ss.converged() ? error_of(st.tip_state).norm() : err;
      const double rho = predicted > 0.0 ? (err * err - err_new * err_new) / predicted : -1.0;
      if (ss.converged() && err_new < err && rho > kAcceptRatio) {
        accepted = true;
        actuation = at;
        solution = std::move(st);
        q += dq;
        if (rho > kGoodRatio && truncated) radius = std::min(2.0 * radius, kTrustMax);
        if (rho < kPoorRatio) radius *= kTrustShrink;
      } else {
        radius = (dq.array().abs() / scale.array()).maxCoeff() * kTrustShrink;
      }
    }
    if (!accepted) {
      return finish(InverseResult::Status::kUnreachable,
                    "no step inside the actuation bounds reduces the distance " +
                        format_value(err) + " m (least-squares optimum)",
                    y);
    }
    ++res.iterations;
  }
}

double blocked_normal_force_N(ShootingSolver& constrained_solver, const rod::RodModel& model,
                              double t_K, Solution& solution) {
  require(model.tip_constraint && model.tip_constraint->normal_W, "tip_constraint.normal",
          "(missing)", "a blocked-tip normal force needs a tip_constraint with a normal");
  Actuation a = Actuation::from_model(model);
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
    if (is_tca(model, i)) { act = i; ++n_tca; }
  }
  require(n_tca == 1, "actuators", n_tca, "grasp needs exactly one TCA-driven actuator per finger");
  require_uniform_temperature(model, act);
  Eigen::VectorXd lo, hi;
  actuation_bounds(model, {act}, options.max_temperature_K,
                   std::numeric_limits<double>::infinity(), lo, hi);
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
      res.message = std::isfinite(f_max)
                        ? "not reachable: the blocked-tip normal force at the maximum temperature " +
                              format_value(units::K_to_degC(t_hi)) + " degC is " +
                              format_value(f_max) + " N, below the required " +
                              format_value(F_req) + " N"
                        : "the blocked-tip solve at the maximum temperature did not converge";
      return res;
    }
  }

  // Eq. (43) on the free finger loaded at the tip by the contact force -f n.
  rod::RodModel free = model;
  free.tip_constraint.reset();
  ShootingSolver fs(free, shooting_options);
  Actuation a = Actuation::from_model(free);
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
    const double Jn = n.dot(d.J.block<3, 1>(0, 0));                  // dx/dT
    const double Cn = -n.dot(d.C.block<3, 3>(0, 0) * n);             // dx/df (W = -f n)
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

Eigen::Vector3d parse_vector3(const std::string& text, const std::string& flag) {
  Eigen::Vector3d v;
  std::size_t pos = 0;
  int k = 0;
  const std::string rule = "must be three comma-separated finite numbers X,Y,Z";
  while (true) {
    const std::size_t comma = text.find(',', pos);
    const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    require(k < 3, flag, text, rule);
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    require(used > 0 && item.find_first_not_of(" \t", used) == std::string::npos && std::isfinite(value),
            flag, text, rule);
    v[k++] = value;
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  require(k == 3, flag, text, rule);
  return v;
}

std::vector<int> actuator_indices(const rod::RodModel& model, const std::string& names,
                                  const std::string& flag) {
  std::vector<int> out;
  if (names.empty()) {
    for (int i = 0; i < static_cast<int>(model.actuators.size()); ++i) out.push_back(i);
    return out;
  }
  std::string all;
  for (const auto& a : model.actuators) all += (all.empty() ? "" : ", ") + a.name;
  std::size_t pos = 0;
  while (pos <= names.size()) {
    const std::size_t comma = names.find(',', pos);
    const std::string name = names.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    int found = -1;
    for (int i = 0; i < static_cast<int>(model.actuators.size()); ++i) {
      if (model.actuators[i].name == name) found = i;
    }
    require(found >= 0, flag, names,
            "names an actuator the scenario does not have: '" + name + "' (it has: " + all + ")");
    require(std::find(out.begin(), out.end(), found) == out.end(), flag, names,
            "names actuator '" + name + "' twice");
    out.push_back(found);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out;
}

}  // namespace tcasim::cosserat
