// Damped Newton on the shooting residual (line search, Broyden updates, finite-difference
// Jacobians) and the continuation in the load fraction.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "cosserat/internal/shooting_impl.hpp"

namespace tcasim::cosserat {

using namespace stage_names;

namespace {

/// Armijo constant of the backtracking line search on phi = ||r||^2 / 2 (Newton's
/// direction d solves J d = -r, so phi'(0) = -2 phi: accept phi(t) <= (1 - 2 c t) phi).
constexpr double kArmijo = 1e-4;
/// With a Broyden-updated (stale) Jacobian, at most this many halvings before the
/// Jacobian is recomputed by differences.
constexpr int kStaleLineSearchSteps = 1;
/// A stale-Jacobian step that reduces ||r|| by less than this factor discards the
/// Jacobian (the next iteration recomputes it).
constexpr double kBroydenMinReduction = 0.5;
/// Relative finite-difference steps: sqrt(eps) (forward) and eps^(1/3) (central)
/// balance truncation and round-off errors.
constexpr double kForwardStep = 1.4901161193847656e-08;  // sqrt(eps)
constexpr double kCentralStep = 6.0554544523933395e-06;  // eps^(1/3)

}  // namespace

Summary::Status ShootingSolver::Impl::newton(const rod::Loads& act, double lambda,
                                             Eigen::VectorXd& x, Eigen::MatrixXd& J,
                                             Summary& summary, std::string& why, double tolerance) {
  Eigen::VectorXd r(nx), xt(nx), rt(nx), dx(nx);
  if (!residual(act, lambda, x, r)) {
    why = "the IVP or a TCA law failed at the initial guess";
    return Summary::Status::kInitialPointFailed;
  }
  remember(lambda, x);
  bool fresh = false;
  if (J.rows() != nx || J.cols() != nx) J.resize(0, 0);
  for (int it = 0;; ++it) {
    summary.residual = r.lpNorm<Eigen::Infinity>();
    if (summary.residual <= tolerance) return Summary::Status::kConverged;
    if (it >= options.max_iterations) {
      why = "reached max_iterations = " + std::to_string(options.max_iterations) +
            " with scaled residual " + format_value(summary.residual);
      return Summary::Status::kMaxIterations;
    }
    if (J.size() == 0) {
      bool approximate = false;
      const bool ok = options.jacobian == JacobianMethod::kSensitivity
                          ? newton_jacobian(act, lambda, x, r, J, approximate)
                          : fd_jacobian(act, lambda, x, r, J);
      if (!ok) {
        why = "Jacobian evaluation failed (non-finite IVP)";
        J.resize(0, 0);
        return Summary::Status::kLineSearchFailed;
      }
      fresh = !approximate;  // a coarse-level Jacobian is treated like a stale one
      jacobian_updates = 0;
    }
    dx = J.partialPivLu().solve(-r);
    if (!dx.allFinite()) {
      if (!fresh) {
        J.resize(0, 0);
        --it;
        continue;
      }
      why = "singular shooting Jacobian";
      return Summary::Status::kSingularJacobian;
    }
    const double phi = 0.5 * r.squaredNorm();
    double t = 1.0;
    bool accepted = false;
    const int max_ls = fresh ? options.max_line_search_steps : kStaleLineSearchSteps;
    for (int ls = 0; ls < max_ls; ++ls, t *= 0.5) {
      xt = x + t * dx;
      if (residual(act, lambda, xt, rt) &&
          0.5 * rt.squaredNorm() <= (1.0 - 2.0 * kArmijo * t) * phi) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      if (!fresh) {
        J.resize(0, 0);
        --it;
        continue;
      }  // retry with a fresh FD Jacobian
      why = "line search found no decrease of ||r||^2 along the Newton direction";
      return Summary::Status::kLineSearchFailed;
    }
    ++summary.iterations;
    const bool poor = rt.norm() > kBroydenMinReduction * r.norm();
    // A poor step with a fresh Jacobian: the map is far from linear here. Sensitivities
    // are cheap enough to recompute; an FD Jacobian (nx IVPs) is Broyden-updated instead.
    const bool fd = options.jacobian != JacobianMethod::kSensitivity;
    if (options.broyden_updates && (!poor || (fresh && fd))) {
      // Broyden's "good" update: J += (dr - J s) s^T / (s^T s).
      const Eigen::VectorXd s = xt - x;
      const double ss = s.squaredNorm();
      if (ss > 0.0) J.noalias() += ((rt - r) - J * s) * (s.transpose() / ss);
      fresh = false;
      ++jacobian_updates;
    } else {
      J.resize(0, 0);
    }
    x = xt;
    r = rt;
    remember(lambda, x);
  }
}

bool ShootingSolver::Impl::newton_jacobian(const rod::Loads& act, double lambda,
                                           const Eigen::VectorXd& x, Eigen::VectorXd& r,
                                           Eigen::MatrixXd& J, bool& approximate) {
  approximate = false;
  const bool fine = level == &fine_level;
  if (!fine || !coarse_level || !coarse_level->has_sensitivities() ||
      (coarse_jacobian_x.size() == x.size() && coarse_jacobian_x == x)) {
    return residual_and_jacobian(act, lambda, x, r, J);
  }
  coarse_jacobian_x = x;
  Eigen::VectorXd rc;
  level = &*coarse_level;
  const bool ok = residual_and_jacobian(act, lambda, x, rc, J);
  level = &fine_level;
  if (!ok) return residual_and_jacobian(act, lambda, x, r, J);
  approximate = true;
  return true;
}

Eigen::VectorXd ShootingSolver::Impl::typical_scale() const {
  assert(x_tca == 6 && "the planar reduction uses sensitivity Jacobians, never differences");
  Eigen::VectorXd t(nx);
  t.head<3>() = Fc * K_nu_inv;  // the strain deviation of the characteristic force
  t.segment<3>(3).setConstant(1.0 / L);
  t.segment(6, n_tca).setConstant(Fc);
  t.tail(n_con).setConstant(Fc);
  return t;
}

bool ShootingSolver::Impl::fd_jacobian(const rod::Loads& act, double lambda,
                                       const Eigen::VectorXd& x, const Eigen::VectorXd& r0,
                                       Eigen::MatrixXd& J) {
  J.resize(nx, nx);
  const Eigen::VectorXd typ = typical_scale();
  Eigen::VectorXd xp = x, rp(nx), rm(nx);
  const bool central = options.jacobian == JacobianMethod::kCentralDifference;
  for (int j = 0; j < nx; ++j) {
    const double base = std::max(std::abs(x[j]), typ[j]);
    double h = (central ? kCentralStep : kForwardStep) * base;
    const double xj = x[j];
    xp[j] = xj + h;
    h = xp[j] - xj;  // exactly representable step
    if (!residual(act, lambda, xp, rp)) {
      xp[j] = xj;
      return false;
    }
    if (central) {
      xp[j] = xj - h;
      if (!residual(act, lambda, xp, rm)) {
        xp[j] = xj;
        return false;
      }
      J.col(j) = (rp - rm) / (2.0 * h);
    } else {
      J.col(j) = (rp - r0) / h;
    }
    xp[j] = xj;
  }
  return J.allFinite();
}

Summary::Status ShootingSolver::Impl::continuation(const rod::Loads& act, Eigen::VectorXd& x,
                                                   Eigen::MatrixXd& J, Summary& summary,
                                                   std::string& why) {
  const std::string direct_why = why;
  double lambda = 0.0;
  Eigen::VectorXd xc = initial_guess(act, 0.0, false);
  Eigen::MatrixXd Jc;
  Summary::Status st = newton(act, 0.0, xc, Jc, summary, why, options.tolerance);
  if (st != Summary::Status::kConverged) {
    why = "direct solve: " + direct_why + "; unloaded solve: " + why;
    x = xc;
    J.resize(0, 0);
    return st;
  }
  double step = 0.5;
  while (lambda < 1.0) {
    const double lt = std::min(1.0, lambda + step);
    Eigen::VectorXd xt = xc;
    Eigen::MatrixXd Jt = Jc;
    st = newton(act, lt, xt, Jt, summary, why, options.tolerance);
    if (st == Summary::Status::kConverged) {
      lambda = lt;
      xc = xt;
      Jc = Jt;
      ++summary.continuation_steps;
      step = std::min(2.0 * step, 1.0 - lambda);  // never retry a failed target
    } else {
      step *= 0.5;
      if (step < options.min_continuation_step) {
        // Report the residual at the full load for the returned point.
        Eigen::VectorXd r;
        summary.residual = residual(act, 1.0, xc, r) ? r.lpNorm<Eigen::Infinity>()
                                                     : std::numeric_limits<double>::infinity();
        why = "continuation stalled at load fraction " + format_value(lambda) + " (step < " +
              format_value(options.min_continuation_step) + "): " + why;
        x = xc;
        J.resize(0, 0);
        return Summary::Status::kContinuationFailed;
      }
    }
  }
  x = xc;
  J = Jc;
  return Summary::Status::kConverged;
}

}  // namespace tcasim::cosserat
