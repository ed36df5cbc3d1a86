// Starting points of the fine-level Newton iteration: the multi-level cold start (coarse
// level, middle level and Richardson extrapolation), the warm start's coarse-grid
// correction and TCA-row refresh, and the path extrapolation of sweeps (Solution::path).
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "cosserat/internal/shooting_impl.hpp"

namespace tcasim::cosserat {

using namespace stage_names;

namespace {

/// Scaled residual to which the coarse level is converged: coarse IVPs are cheap, and the
/// coarse-grid correction of a warm start is only as accurate as the coarse solutions.
constexpr double kCoarseTolerance = 1e-9;
/// A cold start hands the coarse (or middle) level's Jacobian to the next level only if it
/// was Broyden-updated at most this many times since it was computed.
constexpr int kMaxHandedOverUpdates = 1;
/// Path extrapolation (ShootingSolver::kPathHistory): relative distance from the line below
/// which an earlier actuation counts as on it, and the smallest spacing of the path's
/// parameters in units of the new step.
constexpr double kPathCollinearity = 1e-9;
constexpr double kPathMinSpacing = 0.5;

}  // namespace

Summary::Status ShootingSolver::Impl::direct_solve(const rod::Loads& act, Solution& sol, bool warm,
                                                   Eigen::VectorXd& x, Eigen::MatrixXd& J,
                                                   Summary& summary, std::string& why) {
  // Two-level start (Options::coarse_steps). Cold: converge the coarse problem first
  // (cheap IVPs); its solution is within the coarse discretization error of the fine one.
  // Warm: coarse-grid correction x = x_fine,old + (x_coarse,new - x_coarse,old), whose
  // error is the change of the discretization error between the two actuations.
  Eigen::VectorXd coarse_x;
  Eigen::MatrixXd coarse_J;
  if (coarse_level) {
    const bool warm_coarse =
        warm && sol.coarse_unknowns.size() == nx && sol.coarse_unknowns.allFinite();
    // A warm start with a Jacobian goes straight to the fine level: its first residual is
    // usually free (IVP memo), and the Broyden-updated Jacobian saves the coarse solve.
    const bool warm_fine = warm && J.rows() == nx && options.warm_start_fine_only;
    if ((!warm || warm_coarse) && !warm_fine) {
      Eigen::VectorXd xc = warm ? sol.coarse_unknowns : x;
      // Cold: J is empty, or the Jacobian of a warm start that warm_start_pays turned down
      // (close to the coarse one: it saves the coarse sensitivity IVP).
      Eigen::MatrixXd Jc =
          warm ? (sol.coarse_jacobian.rows() == nx ? sol.coarse_jacobian : Eigen::MatrixXd()) : J;
      std::string coarse_why;
      level = &*coarse_level;
      const Summary::Status sc = newton(act, 1.0, xc, Jc, summary, coarse_why, kCoarseTolerance);
      level = &fine_level;
      if (sc == Summary::Status::kConverged) {
        if (warm) {
          x += xc - sol.coarse_unknowns;
        } else {
          x = xc;
          // A Jacobian updated more than once since it was computed has drifted far from
          // the one at xc: the fine level then starts with a fresh (coarse-level) one.
          if (jacobian_updates <= kMaxHandedOverUpdates) J = Jc;
          if (mid_level) cold_extrapolation(act, xc, Jc, x, J, summary);
        }
        coarse_x = xc;
        coarse_J = Jc;
      }
    }
  }
  sol.coarse_unknowns = coarse_x;
  sol.coarse_jacobian = coarse_J;
  if (warm && J.rows() == nx && coarse_x.size() == 0) refresh_tca_rows(act, x, J);
  return newton(act, 1.0, x, J, summary, why, options.tolerance);
}

bool ShootingSolver::Impl::warm_start_pays(const rod::Loads& act, const Solution& sol,
                                           const Eigen::MatrixXd& J, Eigen::VectorXd& x_cold,
                                           bool& loaded_guess) {
  // Only where the warm start would go straight to the fine level (direct_solve).
  if (!coarse_level || J.rows() != nx || !options.warm_start_fine_only) return true;
  // An IVP the memo answers: only temperatures or tip loads changed, which enter the tip
  // residual alone; the fine residual is free and refresh_tca_rows updates the Jacobian.
  const Eigen::VectorXd& xw = sol.unknowns;
  set_parameters(act, 1.0, xw);
  if (memo_answers(xw)) return true;
  Eigen::VectorXd r;
  level = &*coarse_level;
  const bool warm_ok = residual(act, 1.0, xw, r);
  bool pays = true;
  if (!warm_ok || r.lpNorm<Eigen::Infinity>() > std::sqrt(options.tolerance)) {
    x_cold = initial_guess(act, 1.0, true, &loaded_guess);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(J);
    const Eigen::VectorXd dw = warm_ok ? Eigen::VectorXd(lu.solve(r)) : Eigen::VectorXd();
    if (residual(act, 1.0, x_cold, r)) {
      // Newton's steps to the coarse solution, each unknown relative to its size.
      const Eigen::VectorXd dc = lu.solve(r);
      double step_w = warm_ok ? 0.0 : std::numeric_limits<double>::infinity(), step_c = 0.0;
      for (int i = 0; i < nx; ++i) {
        const double size = std::max(std::abs(xw[i]), std::abs(x_cold[i]));
        if (!(size > 0.0)) continue;
        if (warm_ok) step_w = std::max(step_w, std::abs(dw[i]) / size);
        step_c = std::max(step_c, std::abs(dc[i]) / size);
      }
      if (step_c < step_w) {
        pays = false;
        remember(1.0, x_cold);  // the cold path's first coarse residual is then the memo's
      }
    }
    if (pays) loaded_guess = false;
  }
  level = &fine_level;
  return pays;
}

Summary::Status ShootingSolver::Impl::omega_star_homotopy(const rod::Loads& act, Solution& sol,
                                                          Eigen::VectorXd& x, Eigen::MatrixXd& J,
                                                          Summary& summary, std::string& why) {
  struct Restore {  // mu = 1 on every return
    ShootingSolver::Impl& s;
    ~Restore() { s.set_omega_star_fraction(1.0); }
  } restore{*this};
  set_omega_star_fraction(0.0);
  bool loaded_guess = false;
  x = initial_guess(act, 1.0, true, &loaded_guess);
  J.resize(0, 0);
  Summary::Status st = direct_solve(act, sol, false, x, J, summary, why);
  if (st != Summary::Status::kConverged && loaded_guess) {
    x = initial_guess(act, 1.0, false);
    J.resize(0, 0);
    st = direct_solve(act, sol, false, x, J, summary, why);
  }
  if (st != Summary::Status::kConverged) {
    why = "at the base's reference curvature: " + why;
    return st;
  }
  double mu = 0.0, step = 1.0;
  while (mu < 1.0) {
    const double mt = std::min(1.0, mu + step);
    set_omega_star_fraction(mt);
    Eigen::VectorXd xt = x;
    Eigen::MatrixXd Jt = J;
    Solution trial;  // the coarse fields of the warm direct solve
    trial.coarse_unknowns = sol.coarse_unknowns;
    trial.coarse_jacobian = sol.coarse_jacobian;
    st = direct_solve(act, trial, true, xt, Jt, summary, why);
    if (st == Summary::Status::kConverged) {
      mu = mt;
      x = xt;
      J = Jt;
      sol.coarse_unknowns = trial.coarse_unknowns;
      sol.coarse_jacobian = trial.coarse_jacobian;
      step = std::min(2.0 * step, 1.0 - mu);
    } else {
      step *= 0.5;
      if (step < options.min_continuation_step) {
        why = "reference-curvature homotopy stalled at fraction " + format_value(mu) + ": " + why;
        return st;
      }
    }
  }
  return Summary::Status::kConverged;
}

void ShootingSolver::Impl::cold_extrapolation(const rod::Loads& act, const Eigen::VectorXd& xc,
                                              const Eigen::MatrixXd& Jc, Eigen::VectorXd& x,
                                              Eigen::MatrixXd& J, Summary& summary) {
  Eigen::VectorXd xm = xc;
  Eigen::MatrixXd Jm = Jc;
  std::string why;
  level = &*mid_level;
  const Summary::Status sm = newton(act, 1.0, xm, Jm, summary, why, kCoarseTolerance);
  level = &fine_level;
  if (sm != Summary::Status::kConverged) return;
  const double p = ode::order_of(options.integrator.method);
  const double a = std::pow(static_cast<double>(options.coarse_steps), -p);
  const double b = std::pow(2.0 * options.coarse_steps, -p);
  const double c = std::pow(static_cast<double>(options.integrator.steps), -p);
  x = xm + ((c - b) / (b - a)) * (xm - xc);
  J = jacobian_updates <= kMaxHandedOverUpdates ? Jm : Eigen::MatrixXd();
}

void ShootingSolver::Impl::refresh_tca_rows(const rod::Loads& act, const Eigen::VectorXd& x,
                                            Eigen::MatrixXd& J) {
  if (n_tca == 0 || !memo_valid || x_acc.size() != x.size() || x_acc != x) return;
  const std::vector<double> a_old = acc_dphi_dT, b_old = acc_dphi_ddelta;
  Eigen::VectorXd r;
  if (!residual(act, 1.0, x, r)) return;
  remember(1.0, x);  // Newton's first residual at x is then answered by the memo too
  for (int i = 0; i < n_act; ++i) {
    const int k = unknown_of[i];
    if (k < 0 || b_old[i] == 0.0 || !std::isfinite(dphi_ddelta[i])) continue;
    J(k, k) -= a_old[i] / Fc;
    J.row(k) *= dphi_ddelta[i] / b_old[i];
    J(k, k) += dphi_dT[i] / Fc;
  }
}

Eigen::VectorXd ShootingSolver::Impl::actuation_vector(const rod::Loads& act) {
  int n = 9;
  for (const rod::ActuatorLoad& d : act.actuators) n += 1 + 2 * static_cast<int>(d.segments.size());
  Eigen::VectorXd a(n);
  int k = 0;
  for (const rod::ActuatorLoad& d : act.actuators) {
    a[k++] = d.tension_N;
    for (const tca::Segment& seg : d.segments) {
      a[k++] = seg.fraction;
      a[k++] = seg.temperature_K;
    }
  }
  a.segment<3>(k) = act.tip_force_W_N;
  a.segment<3>(k + 3) = act.tip_moment_W_Nm;
  a.segment<3>(k + 6) = act.gravity_W_m_s2;
  return a;
}

bool ShootingSolver::Impl::extrapolate_path(const Solution& sol, const Eigen::VectorXd& a, int nx,
                                            Eigen::VectorXd& x) {
  const auto& path = sol.path;
  if (path.size() < 2) return false;
  const Solution::PathPoint& last = path.back();
  if (last.actuation.size() != a.size() || last.unknowns.size() != nx) return false;
  const Eigen::VectorXd d = a - last.actuation;
  const double dd = d.squaredNorm();
  if (!(dd > 0.0) || !std::isfinite(dd)) return false;
  std::vector<double> t{0.0};
  for (int k = static_cast<int>(path.size()) - 2; k >= 0; --k) {
    const Solution::PathPoint& p = path[k];
    if (p.actuation.size() != a.size() || p.unknowns.size() != nx) break;
    const Eigen::VectorXd v = p.actuation - last.actuation;
    const double tk = v.dot(d) / dd;
    // On the line (to round-off of the actuation values) and behind the previous node.
    if ((v - tk * d).norm() > kPathCollinearity * (v.norm() + std::sqrt(dd))) break;
    if (tk > t.back() - kPathMinSpacing) break;
    t.push_back(tk);
  }
  const int m = static_cast<int>(t.size());
  if (m < 2) return false;
  x.setZero(nx);
  for (int k = 0; k < m; ++k) {
    double w = 1.0;  // Lagrange basis polynomial of node t[k] at t = 1
    for (int l = 0; l < m; ++l) {
      if (l != k) w *= (1.0 - t[l]) / (t[k] - t[l]);
    }
    x += w * path[path.size() - 1 - k].unknowns;  // t[k] belongs to the k-th newest point
  }
  return x.allFinite();
}

void ShootingSolver::Impl::record_path(Solution& sol, bool warm, bool converged,
                                       Eigen::VectorXd a) {
  if (!converged) {
    sol.path.clear();
    return;
  }
  if (!warm) sol.path.clear();
  if (!sol.path.empty() && sol.path.back().actuation.size() == a.size() &&
      sol.path.back().actuation == a) {
    sol.path.back().unknowns = sol.unknowns;  // the same point again: no duplicate node
    return;
  }
  sol.path.push_back({std::move(a), sol.unknowns});
  if (static_cast<int>(sol.path.size()) > ShootingSolver::kPathHistory)
    sol.path.erase(sol.path.begin());
}

}  // namespace tcasim::cosserat
