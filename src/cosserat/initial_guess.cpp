// The unknowns a cold solve starts from (docs/conventions.md "Initial guess").
#include <array>
#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "cosserat/shooting_impl.hpp"

namespace tcasim::cosserat {

using namespace state_layout;
using internal::all_finite;
using internal::Mat3;
using internal::Vec3;
using internal::Vec6;

using internal::hat;

namespace {

/// Initial guess with gravity: nodes of the load-strain quadrature, fixed-point
/// iterations, and the convergence test on the change of the mean strains (relative to
/// 1/L + their size).
constexpr int kGuessNodes = 8;
constexpr int kGuessIterations = 12;
constexpr double kGuessTolerance = 1e-3;

}  // namespace

Eigen::VectorXd ShootingSolver::Impl::initial_guess(const Actuation& act, double lambda,
                                                    bool with_gravity, bool* used_gravity) {
  if (planar) {
    // The 3-D guess of a planar problem lies in the plane (its other components are
    // exact zeros): keep its in-plane unknowns.
    return reduce(parent->initial_guess(act, lambda, with_gravity, used_gravity));
  }
  if (used_gravity) *used_gravity = false;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(nx);
  set_parameters(act, lambda, x);  // cT of the known tensions, scaled TCA segments
  std::vector<double> cTs = cT;
  Vec3 e, omega;  // e = nu - nu*
  if (with_gravity && !f_ext_W.isZero(0.0)) {
    Vec6 mean = Vec6::Zero();
    for (int it = 0; it < kGuessIterations; ++it) {
      guess_tensions(mean, cTs, x);
      closed_form_strains(cTs, e, omega);
      Vec6 next_mean, base;
      load_strains(nu_star + e + mean.head<3>(), omega + mean.tail<3>(), next_mean, base);
      if (!next_mean.allFinite() || !base.allFinite()) break;
      const double change = (next_mean - mean).lpNorm<Eigen::Infinity>();
      mean = next_mean;
      if (change <= kGuessTolerance * (1.0 / L + mean.lpNorm<Eigen::Infinity>())) {
        guess_tensions(mean, cTs, x);
        closed_form_strains(cTs, e, omega);
        x.head<3>() = e + base.head<3>();
        x.segment<3>(3) = omega + base.tail<3>();
        if (used_gravity) *used_gravity = true;
        return x;
      }
    }
  }
  guess_tensions(Vec6::Zero(), cTs, x);  // without gravity (none, or no fixed point)
  closed_form_strains(cTs, e, omega);
  x.head<3>() = e;
  x.segment<3>(3) = omega;
  return x;
}

void ShootingSolver::Impl::guess_tensions(const Vec6& extra, std::vector<double>& cTs,
                                          Eigen::VectorXd& x) {
  if (n_tca == 0) return;
  Vec3 nu, omega;
  Eigen::VectorXd T = Eigen::VectorXd::Zero(n_tca), g(n_tca), dT(n_tca);
  Eigen::MatrixXd G(n_tca, n_tca);
  // Residuals g_k = phi_k(T_k, delta_k(T)) of the closed-form model (the TCA law with coil
  // contact, tca::contact_residual); it may throw.
  auto eval = [&](const Eigen::VectorXd& Tk, Eigen::VectorXd& gk, Eigen::MatrixXd* Gk) {
    for (int k = 0; k < n_tca; ++k) cTs[act_of[k]] = count[act_of[k]] * Tk[k];
    closed_form_strains(cTs, nu, omega);
    nu += nu_star + extra.head<3>();
    omega += extra.tail<3>();
    for (int k = 0; k < n_tca; ++k) {
      const int i = act_of[k];
      const rod::Routing& ro = model.actuators[i].routing;
      const double delta =
          (span_hi[i] - span_lo[i]) * (nu + omega.cross(ro.r(0.0)) + ro.dr(0.0)).norm() -
          model.actuators[i].rest_length_m;
      const tca::ContactResidual c =
          tca::contact_residual(*model.actuators[i].drive.tca, Tk[k], delta, scaled_segments[i]);
      gk[k] = c.phi_N;
      if (Gk) {
        const Vec3 ri = ro.r(0.0);
        for (int l = 0; l < n_tca; ++l) {
          const Vec3 rl = model.actuators[act_of[l]].routing.r(0.0);
          // d delta_k / d T_l = -L C_kl c_l (closed form)
          const double C = from_base(act_of[l]) ? 1.0 / K_nu.z() + ri.y() * rl.y() / K_omega.x() +
                                                      ri.x() * rl.x() / K_omega.y()
                                                : 0.0;
          (*Gk)(k, l) = (k == l ? c.dphi_dF : 0.0) -
                        c.dphi_ddelta_N_m * (span_hi[i] - span_lo[i]) * C * count[act_of[l]];
        }
      }
    }
    return gk.allFinite();
  };
  bool ok = false;
  try {
    ok = eval(T, g, &G);
    for (int it = 0; ok && it < 30 && g.lpNorm<Eigen::Infinity>() > 1e-12 * Fc; ++it) {
      dT = G.partialPivLu().solve(-g);
      double t = 1.0;
      Eigen::VectorXd Tt(n_tca), gt(n_tca);
      bool accepted = false;
      for (int ls = 0; ls < 30 && !accepted; ++ls, t *= 0.5) {
        Tt = T + t * dT;
        try {
          accepted = eval(Tt, gt, nullptr) && gt.squaredNorm() < g.squaredNorm();
        } catch (const DomainError&) {
          accepted = false;
        }
      }
      if (!accepted) break;
      T = Tt;
      ok = eval(T, g, &G);
    }
  } catch (const DomainError&) {
    ok = false;
  }
  if (ok && T.allFinite()) {
    x.segment(6, n_tca) = T;
  } else {
    x.segment(6, n_tca).setZero();
  }
  for (int k = 0; k < n_tca; ++k) cTs[act_of[k]] = count[act_of[k]] * x[6 + k];
}

void ShootingSolver::Impl::closed_form_strains(const std::vector<double>& cTs, Vec3& e,
                                               Vec3& omega) const {
  double sum_T = 0.0, sum_Tx = 0.0, sum_Ty = 0.0;
  for (int i = 0; i < n_act; ++i) {
    if (!from_base(i)) continue;  // no share of the base wrench
    const Vec3 r = model.actuators[i].routing.r(0.0);
    sum_T += cTs[i];
    sum_Tx += cTs[i] * r.x();
    sum_Ty += cTs[i] * r.y();
  }
  e = Vec3(0.0, 0.0, -sum_T / K_nu.z());
  omega = omega_star + Vec3(-sum_Ty / K_omega.x(), sum_Tx / K_omega.y(), 0.0);
}

void ShootingSolver::Impl::arc_pose(const Vec3& nu, const Vec3& omega, double s, Mat3& R,
                                    Vec3& p) const {
  const Vec3 a = s * omega;
  const double th = a.norm();
  const Mat3 A = hat(a), A2 = A * A;
  double c1, c2, c3;  // sin(th)/th, (1 - cos th)/th^2, (th - sin th)/th^3
  if (th < 1e-4) {
    c1 = 1.0 - th * th / 6.0;
    c2 = 0.5 - th * th / 24.0;
    c3 = 1.0 / 6.0 - th * th / 120.0;
  } else {
    c1 = std::sin(th) / th;
    c2 = (1.0 - std::cos(th)) / (th * th);
    c3 = (th - std::sin(th)) / (th * th * th);
  }
  R = model.R_WB0 * (Mat3::Identity() + c1 * A + c2 * A2);
  p = model.base_position_W_m + model.R_WB0 * (s * (nu + c2 * (A * nu) + c3 * (A2 * nu)));
}

void ShootingSolver::Impl::load_strains(const Vec3& nu, const Vec3& omega, Vec6& mean,
                                        Vec6& base) const {
  constexpr int N = kGuessNodes;
  std::array<Mat3, N + 1> R;
  std::array<Vec3, N + 1> p;
  for (int k = 0; k <= N; ++k) arc_pose(nu, omega, L * k / N, R[k], p[k]);
  const double h = L / N;
  mean.setZero();
  Vec3 c_tail = Vec3::Zero();  // int_s^L p, trapezoidal rule, accumulated from the tip
  for (int k = N; k >= 0; --k) {
    if (k < N) c_tail += 0.5 * h * (p[k] + p[k + 1]);
    const double tail = L - k * h;
    const Vec3 n = tail * f_ext_W;
    const Vec3 m = (c_tail - tail * p[k]).cross(f_ext_W);
    Vec6 d;
    d << K_nu_inv.cwiseProduct(R[k].transpose() * n),
        K_omega_inv.cwiseProduct(R[k].transpose() * m);
    mean += (k == 0 || k == N ? 0.5 : 1.0) / N * d;
    if (k == 0) base = d;
  }
}

}  // namespace tcasim::cosserat
