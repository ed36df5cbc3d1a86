// Tip Jacobian and compliance of the shooting solution ([Pawlowski2019] Eqs. (34)-(42)) and
// the actuation bounds of the inverse solvers.
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
#include "common/units.hpp"
#include "cosserat/internal/inverse_internal.hpp"
#include "cosserat/inverse.hpp"

namespace tcasim::cosserat {

using namespace inverse_internal;

namespace {

using state_layout::kDelta;
using state_layout::kP;
using state_layout::kR;

/// tip_derivatives with obstacles: the shooting sensitivities ignore the contact forces (their
/// multipliers are unknowns of the contact solve, not of the IVP), so J and C are central
/// differences of whole contact solves, each warm-started from `solution` (step eps^(1/3) of
/// the variable's scale, F_c or F_c L for the tip wrench; one-sided where a side fails). The map is piecewise smooth: where
/// a step changes the contact set the column is the mean slope across it. du_dq is zero and
/// B_u the solution's (empty) Jacobian: the inverse's trial solves then start from the solution
/// itself.
bool contact_tip_derivatives(ShootingSolver& solver, const rod::RodModel& model,
                             const rod::Loads& actuation, const Solution& solution,
                             const std::vector<int>& variables, TipDerivatives& out) {
  const int nq = static_cast<int>(variables.size());
  const double Fc = solver.characteristic_force_N();
  const double h_rel = std::cbrt(std::numeric_limits<double>::epsilon());
  out.ivp_count = 0;
  out.tip_state = solution.tip_state;
  if (out.tip_state.size() <= kDelta) return false;
  const Mat3 R0 = rotation_of(out.tip_state);
  // Central difference of the tip pose over loads a_plus, a_minus (2 h apart); one-sided
  // where one side cannot be solved (a variable at the edge of its TCA law's range).
  auto column = [&](const rod::Loads& a_plus, const rod::Loads& a_minus, double h,
                    Eigen::Ref<Eigen::VectorXd> col) {
    Solution sp = solution, sm = solution;
    const Summary s_plus = solver.solve(a_plus, sp);
    const Summary s_minus = solver.solve(a_minus, sm);
    out.ivp_count += s_plus.ivp_count + s_minus.ivp_count;
    if (s_plus.converged() && s_minus.converged()) {
      col = pose_difference(sp.tip_state, sm.tip_state, R0) / (2.0 * h);
    } else if (s_plus.converged()) {
      col = pose_difference(sp.tip_state, out.tip_state, R0) / h;
    } else if (s_minus.converged()) {
      col = pose_difference(out.tip_state, sm.tip_state, R0) / h;
    } else {
      return false;
    }
    return col.allFinite();
  };
  out.J.resize(6, nq);
  for (int k = 0; k < nq; ++k) {
    const int i = variables[static_cast<std::size_t>(k)];
    const double v = get_variable(model, actuation, i);
    const double h = h_rel * variable_scale(model, i, v, Fc);
    rod::Loads a_plus = actuation, a_minus = actuation;
    set_variable(model, a_plus, i, v + h);
    set_variable(model, a_minus, i, v - h);
    if (!column(a_plus, a_minus, h, out.J.col(k))) return false;
  }
  out.C.resize(6, 6);
  for (int c = 0; c < 6; ++c) {
    const double h = h_rel * Fc * (c < 3 ? 1.0 : model.length_m);
    rod::Loads a_plus = actuation, a_minus = actuation;
    Eigen::Vector3d& f_plus = c < 3 ? a_plus.tip_force_W_N : a_plus.tip_moment_W_Nm;
    Eigen::Vector3d& f_minus = c < 3 ? a_minus.tip_force_W_N : a_minus.tip_moment_W_Nm;
    f_plus[c % 3] += h;
    f_minus[c % 3] -= h;
    if (!column(a_plus, a_minus, h, out.C.col(c))) return false;
  }
  out.du_dq = Eigen::MatrixXd::Zero(solution.unknowns.size(), nq);
  out.B_u = solution.jacobian;
  return true;
}

}  // namespace

bool tip_derivatives(ShootingSolver& solver, const rod::RodModel& model,
                     const rod::Loads& actuation, const Solution& solution,
                     const std::vector<int>& variables, TipDerivativeMethod method,
                     TipDerivatives& out) {
  require(!model.tip_constraint, "model.tip_constraint", "(set)",
          "must be absent: J and C describe a free tip");
  const int nx = solver.unknown_count();
  const int nq = static_cast<int>(variables.size());
  const double Fc = solver.characteristic_force_N();
  const double L = model.length_m;
  require(solution.unknowns.size() == nx, "solution.unknowns",
          static_cast<double>(solution.unknowns.size()),
          "must hold the solver's " + std::to_string(nx) + " unknowns");
  for (int i : variables) {
    require(i >= 0 && i < static_cast<int>(model.actuators.size()), "variables", i,
            "must index a model actuator");
  }
  if (!model.obstacles.empty()) {
    return contact_tip_derivatives(solver, model, actuation, solution, variables, out);
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
      rod::Loads a = actuation;
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
      rod::Loads a = actuation;
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
      rod::Loads a = actuation;
      const double w0 = c < 3 ? actuation.tip_force_W_N[c] : actuation.tip_moment_W_Nm[c - 3];
      const double h = step * std::max(std::abs(w0), c < 3 ? Fc : Fc * L);
      auto eval = [&](double hh, Eigen::VectorXd& r, Eigen::VectorXd& y) {
        if (c < 3)
          a.tip_force_W_N[c] = w0 + hh;
        else
          a.tip_moment_W_Nm[c - 3] = w0 + hh;
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

}  // namespace tcasim::cosserat
