// Target solve of the inverse problem: bounded, trust-region least squares on the actuation
// ([Pawlowski2019] Section IV with the tip Jacobian of inverse_jacobian.cpp).

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "common/error.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "cosserat/internal/inverse_internal.hpp"
#include "cosserat/inverse.hpp"

namespace tcasim::cosserat {

using namespace inverse_internal;

namespace {

using state_layout::kDelta;
using state_layout::kP;

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
      if (fixed[i])
        ef -= A.col(i) * dq[i];
      else
        free_idx.push_back(i);
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
      if (q[i] + dq[i] > hi[i]) {
        dq[i] = hi[i] - q[i];
        fixed[i] = true;
        violated = true;
      }
      if (q[i] + dq[i] < lo[i]) {
        dq[i] = lo[i] - q[i];
        fixed[i] = true;
        violated = true;
      }
    }
    if (!violated) break;
  }
  return dq;
}

}  // namespace

InverseResult solve_inverse(ShootingSolver& solver, const rod::RodModel& model,
                            const Eigen::Vector3d& target_W_m, const InverseOptions& options,
                            rod::Loads& actuation, Solution& solution) {
  require(target_W_m.allFinite(), "target", target_W_m.norm(), "must be finite");
  require(options.tolerance_m > 0.0, "options.tolerance_m", options.tolerance_m, "must be > 0");
  require(options.max_iterations >= 1, "options.max_iterations", options.max_iterations,
          "must be >= 1");
  const bool any_component =
      options.components[0] || options.components[1] || options.components[2];
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
    if (options.target_R_WB)
      dth = so3::log(Mat3(*options.target_R_WB * rotation_of(y).transpose()));
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
      const std::optional<double> t_open =
          opening_temperature(model, actuation, vars[k], solution, hi[k]);
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
        return finish(
            InverseResult::Status::kForwardFailed,
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
      rod::Loads at = actuation;
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

}  // namespace tcasim::cosserat
