// The unknowns a cold solve starts from (docs/conventions.md "Initial guess").
#include <array>
#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "common/lie_series.hpp"
#include "cosserat/internal/shooting_impl.hpp"
#include "rod/closed_form.hpp"

namespace tcasim::cosserat {

using namespace stage_names;

using internal::hat;

namespace {

/// Initial guess with gravity: nodes of the load-strain quadrature, fixed-point
/// iterations, and the convergence test on the change of the mean strains (relative to
/// 1/L + their size).
constexpr int kGuessNodes = 8;
constexpr int kGuessIterations = 12;
constexpr double kGuessTolerance = 1e-3;
/// The guess's TCA tensions solve T_k = F_tca(delta_k(T)) to this residual over F_c.
constexpr double kGuessTensionTolerance = 1e-12;

/// The closed-form strains (rod::closed_form_strains) of tensions cTs: e = nu - nu*, omega, with
/// the base section's stiffnesses K_nu, K_omega and reference curvature omega*(0).
void closed_form(const rod::RodModel& m, const Vec3& K_nu, const Vec3& K_omega,
                 const Vec3& omega_star, const std::vector<double>& cTs, Vec3& e, Vec3& omega) {
  const rod::ConstantStrains cf =
      rod::closed_form_strains(m, rod::SectionStiffness{K_nu, K_omega}, omega_star, cTs);
  e = cf.e;
  omega = cf.omega;
}

}  // namespace

Eigen::VectorXd ShootingSolver::Impl::initial_guess(const rod::Loads& act, double lambda,
                                                    bool with_gravity, bool* used_gravity) {
  if (used_gravity) *used_gravity = false;
  // The guess in 3-D unknowns; a planar problem's lies in the plane (its other components
  // are exact zeros) and the layout keeps its in-plane unknowns.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(6 + n_tca + n_con);
  set_parameters(act, lambda, Eigen::VectorXd::Zero(nx));  // cT of the known tensions, TCA segments
  std::vector<double> cTs = cT;
  Vec3 e, omega;  // e = nu - nu*
  if (with_gravity && !f_ext_W.isZero(0.0)) {
    Vec6 mean = Vec6::Zero();
    for (int it = 0; it < kGuessIterations; ++it) {
      guess_tensions(mean, cTs, x);
      closed_form(model, K_nu, K_omega, omega_star, cTs, e, omega);
      Vec6 next_mean, base;
      load_strains(nu_star + e + mean.head<3>(), omega + mean.tail<3>(), next_mean, base);
      if (!next_mean.allFinite() || !base.allFinite()) break;
      const double change = (next_mean - mean).lpNorm<Eigen::Infinity>();
      mean = next_mean;
      if (change <= kGuessTolerance * (1.0 / L + mean.lpNorm<Eigen::Infinity>())) {
        guess_tensions(mean, cTs, x);
        closed_form(model, K_nu, K_omega, omega_star, cTs, e, omega);
        x.head<3>() = e + base.head<3>();
        x.segment<3>(3) = omega + base.tail<3>();
        if (used_gravity) *used_gravity = true;
        layout->reduce_unknowns(x);
        return x;
      }
    }
  }
  guess_tensions(Vec6::Zero(), cTs, x);  // without gravity (none, or no fixed point)
  closed_form(model, K_nu, K_omega, omega_star, cTs, e, omega);
  x.head<3>() = e;
  x.segment<3>(3) = omega;
  layout->reduce_unknowns(x);
  return x;
}

void ShootingSolver::Impl::guess_tensions(const Vec6& extra, std::vector<double>& cTs,
                                          Eigen::VectorXd& x) {
  if (n_tca == 0) return;
  rod::GuessTensionOptions o;
  o.tolerance_N = kGuessTensionTolerance * Fc;
  o.base_stiffness = rod::SectionStiffness{K_nu, K_omega};
  Eigen::VectorXd T = Eigen::VectorXd::Zero(n_tca);
  const bool ok = rod::solve_guess_tensions(model, act_of, scaled_segments, extra, o, cTs, T);
  if (ok) {
    x.segment(6, n_tca) = T;
  } else {
    x.segment(6, n_tca).setZero();
  }
  for (int k = 0; k < n_tca; ++k) cTs[act_of[k]] = count[act_of[k]] * x[6 + k];
}

void ShootingSolver::Impl::arc_pose(const Vec3& nu, const Vec3& omega, double s, Mat3& R,
                                    Vec3& p) const {
  // [Sola2018] R = Exp(a) = I + a_c A + b_c A^2, V = s Jl(a) = s (I + b_c A + c_c A^2) with
  // the series of common/lie_series.hpp (a_c = sin t / t, b_c = (1 - cos t) / t^2,
  // c_c = (t - sin t) / t^3, t = |a|).
  const Vec3 a = s * omega;
  const Mat3 A = hat(a), A2 = A * A;
  const so3::Coefficients<double> k = so3::coefficients(a.squaredNorm());
  const double c1 = k.a, c2 = k.b, c3 = k.c;
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
