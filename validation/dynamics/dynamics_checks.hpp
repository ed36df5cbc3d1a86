#pragma once
/// Reference solutions and signal analysis of the rod-dynamics checks (tests
/// tests/cosserat/dynamics_checks*_test.cpp and the program validate_dynamics): cantilever
/// frequencies by Euler-Bernoulli (the transcendental frequency equation with the tip-mass
/// ratio) and by Timoshenko (shear and rotary inertia, by shooting on the harmonic equations),
/// the BDF-alpha map of a linear oscillator, the modal projection of grid states, a
/// least-squares fit of damped sinusoids, and runs of cosserat::RodDynamics (public API only).
/// Header-only: the tests and the validation program include it.
#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "rod/loads.hpp"
#include "rod/model.hpp"

namespace tcasim::dynamics_checks {

inline constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Root finding

/// Root of f in [a, b] (f(a) f(b) <= 0) by bisection to |b - a| <= tol (robust; these
/// functions are cheap).
inline double bisect(const std::function<double(double)>& f, double a, double b, double tol) {
  double fa = f(a);
  const double fb = f(b);
  if (fa == 0.0) return a;
  if (fb == 0.0) return b;
  if ((fa > 0.0) == (fb > 0.0)) throw std::runtime_error("bisect: no sign change");
  while (std::abs(b - a) > tol) {
    const double m = 0.5 * (a + b);
    if (m == a || m == b) break;  // the bracket is down to adjacent doubles
    const double fm = f(m);
    if (fm == 0.0) return m;
    if ((fm > 0.0) == (fa > 0.0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

/// The first `count` roots of f on (lo, hi), bracketed by a scan with `scan_steps` intervals.
inline std::vector<double> scan_roots(const std::function<double(double)>& f, double lo, double hi,
                                      int count, int scan_steps, double tol) {
  std::vector<double> roots;
  double a = lo, fa = f(lo);
  for (int i = 1; i <= scan_steps && static_cast<int>(roots.size()) < count; ++i) {
    const double b = lo + (hi - lo) * i / scan_steps;
    const double fb = f(b);
    if ((fa > 0.0) != (fb > 0.0)) roots.push_back(bisect(f, a, b, tol));
    a = b;
    fa = fb;
  }
  if (static_cast<int>(roots.size()) < count) throw std::runtime_error("scan_roots: too few roots");
  return roots;
}

// ---------------------------------------------------------------------------------------------
// Euler-Bernoulli cantilever with a tip point mass (no rotary inertia of the mass)

/// The frequency equation divided by cosh(x), x = beta L, mu = m_tip / (rho A L):
///   1 + cos x cosh x + mu x (cos x sinh x - sin x cosh x) = 0.
inline double eb_frequency_function(double x, double mu) {
  return 1.0 / std::cosh(x) + std::cos(x) + mu * x * (std::cos(x) * std::tanh(x) - std::sin(x));
}

/// The first `count` roots beta_k L of the cantilever frequency equation with mass ratio mu
/// (mu = 0: 1.8751, 4.6941, 7.8548, ...).
inline std::vector<double> eb_cantilever_roots(double mu, int count) {
  return scan_roots([mu](double x) { return eb_frequency_function(x, mu); }, 1e-3,
                    kPi * (count + 1.0), count, 2000 * (count + 1), 1e-15);
}

/// Bending stiffness and mass per length of a cantilever, with a tip point mass.
struct Beam {
  double EI = 0.0;     ///< [N m^2]
  double GA = 0.0;     ///< shear stiffness [N] (shear coefficient as in the rod model)
  double rhoA = 0.0;   ///< mass per length [kg/m]
  double rhoI = 0.0;   ///< rotary inertia per length [kg m]
  double L = 0.0;      ///< [m]
  double m_tip = 0.0;  ///< [kg]
  double mu() const { return m_tip / (rhoA * L); }
};

/// The beam of a uniform rod model's bending about body x (the rod model's K_se, K_bt, rho).
inline Beam beam_of(const rod::RodModel& m, double m_tip) {
  Beam b;
  const rod::SectionStiffness K = m.stiffness_at(0.0);
  b.EI = K.bending_torsion.x();
  b.GA = K.shear_extension.x();
  b.rhoA = m.mass_per_length_kg_m(0.0);
  b.rhoI = m.material.density_profile.value(0.0) * m.section.properties_at(0.0).I_x_m4;
  b.L = m.length_m;
  b.m_tip = m_tip;
  return b;
}

/// Euler-Bernoulli angular frequencies [rad/s]: omega_k = (beta_k L)^2 sqrt(EI / (rho A L^4)).
inline std::vector<double> eb_frequencies_rad_s(const Beam& b, int count) {
  std::vector<double> w;
  const double scale = std::sqrt(b.EI / (b.rhoA * std::pow(b.L, 4)));
  for (const double x : eb_cantilever_roots(b.mu(), count)) w.push_back(x * x * scale);
  return w;
}

/// Euler-Bernoulli mode shape k (root x = beta_k L) at s: cosh - cos - sigma (sinh - sin),
/// sigma from the free-end moment condition (unchanged by a point mass).
inline double eb_mode_shape(double x, double L, double s) {
  const double sigma = (std::cosh(x) + std::cos(x)) / (std::sinh(x) + std::sin(x));
  const double z = x * s / L;
  return std::cosh(z) - std::cos(z) - sigma * (std::sinh(z) - std::sin(z));
}

// ---------------------------------------------------------------------------------------------
// Timoshenko cantilever (shear stiffness GA, rotary inertia rho I, tip point mass)

/// Determinant of the tip conditions of the harmonic Timoshenko equations at omega:
///   w' = psi + V / GA, psi' = M / EI, V' = -rho A omega^2 w, M' = -V - rho I omega^2 psi,
/// base w = psi = 0, tip M = 0 and V = m_tip omega^2 w (the point mass's inertia), by RK4 on
/// `steps` steps from the two base states (V, M) = (1, 0), (0, 1) (scaled by EI / L^2, EI / L).
inline double timoshenko_determinant(const Beam& b, double omega, int steps = 4000) {
  using V4 = Eigen::Vector4d;
  const double w2 = omega * omega;
  auto rhs = [&](const V4& y) {
    V4 d;
    d << y(1) + y(2) / b.GA, y(3) / b.EI, -b.rhoA * w2 * y(0), -y(2) - b.rhoI * w2 * y(1);
    return d;
  };
  const double h = b.L / steps;
  V4 y1(0.0, 0.0, b.EI / (b.L * b.L), 0.0), y2(0.0, 0.0, 0.0, b.EI / b.L);
  for (V4* y : {&y1, &y2}) {
    for (int i = 0; i < steps; ++i) {
      const V4 k1 = rhs(*y), k2 = rhs(*y + 0.5 * h * k1), k3 = rhs(*y + 0.5 * h * k2),
               k4 = rhs(*y + h * k3);
      *y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
  }
  // Rows: M(L) = 0 (scaled by EI / L), V(L) - m omega^2 w(L) = 0 (scaled by EI / L^2).
  auto row = [&](const V4& y) {
    return Eigen::Vector2d(y(3) * b.L / b.EI, (y(2) - b.m_tip * w2 * y(0)) * b.L * b.L / b.EI);
  };
  const Eigen::Vector2d a = row(y1), c = row(y2);
  return a(0) * c(1) - a(1) * c(0);
}

/// Timoshenko angular frequencies [rad/s], each bracketed below the Euler-Bernoulli one (shear
/// and rotary inertia lower the frequencies).
inline std::vector<double> timoshenko_frequencies_rad_s(const Beam& b, int count,
                                                        int steps = 4000) {
  const std::vector<double> eb = eb_frequencies_rad_s(b, count);
  std::vector<double> w;
  for (const double we : eb) {
    auto f = [&](double om) { return timoshenko_determinant(b, om, steps); };
    w.push_back(scan_roots(f, 0.95 * we, 1.0 + 1e-9 * we + we, 1, 20, 1e-13 * we).front());
  }
  return w;
}

// ---------------------------------------------------------------------------------------------
// BDF-alpha on a linear oscillator

/// Numerical angular frequency and decay rate of BDF-alpha (docs/conventions.md "Time
/// discretization: BDF-alpha") applied to z_t = i omega z: the principal root zeta of
///   (c0 - i omega) zeta^2 + (c1 + d1 i omega) zeta + c2 = 0
/// gives omega_h = arg(zeta) / dt and decay sigma_h = -ln|zeta| / dt.
struct DiscreteOscillator {
  double omega = 0.0;  ///< [rad/s]
  double decay = 0.0;  ///< [1/s]
};

inline DiscreteOscillator bdf_alpha_oscillator(double omega, double dt, double alpha) {
  using C = std::complex<double>;
  const double c0 = (1.5 + alpha) / (dt * (1.0 + alpha)), c1 = -2.0 / dt,
               c2 = (0.5 + alpha) / (dt * (1.0 + alpha)), d1 = alpha / (1.0 + alpha);
  const C lam(0.0, omega);
  const C a = c0 - lam, bq = c1 + d1 * lam, c = c2;
  const C disc = std::sqrt(bq * bq - 4.0 * a * c);
  const C z1 = (-bq + disc) / (2.0 * a), z2 = (-bq - disc) / (2.0 * a);
  const C exact = std::exp(lam * dt);
  const C z = std::abs(z1 - exact) < std::abs(z2 - exact) ? z1 : z2;
  return {std::arg(z) / dt, -std::log(std::abs(z)) / dt};
}

// ---------------------------------------------------------------------------------------------
// Modal projection and sinusoid fit

/// Modal coordinate of the lateral displacement u(s_i) = p_x(s_i) (a rod along +z, excited
/// along x) on the Euler-Bernoulli mode with root x: mass-weighted projection
///   a = (int rho A u phi ds + m_tip u(L) phi(L)) / (int rho A phi^2 ds + m_tip phi(L)^2),
/// Simpson's rule on the N + 1 grid points (N even) or the trapezoid rule (N odd).
inline double modal_coordinate(const std::vector<Eigen::VectorXd>& grid, const Beam& b, double x) {
  const int n = static_cast<int>(grid.size()) - 1;
  const double h = b.L / n;
  double num = 0.0, den = 0.0;
  for (int i = 0; i <= n; ++i) {
    const bool end = i == 0 || i == n;
    const double w =
        (n % 2 == 0) ? h / 3.0 * (end ? 1.0 : (i % 2 ? 4.0 : 2.0)) : (end ? 0.5 * h : h);
    const double phi = eb_mode_shape(x, b.L, i * h);
    num += w * b.rhoA * grid[i](0) * phi;
    den += w * b.rhoA * phi * phi;
  }
  const double phiL = eb_mode_shape(x, b.L, b.L);
  num += b.m_tip * grid[n](0) * phiL;
  den += b.m_tip * phiL * phiL;
  return num / den;
}

/// A fit of signals y_j(t) (one per row group) by damped sinusoids with shared frequencies and
/// decay rates: y_j(t) = c_j + sum_k exp(-sigma_k t) (a_jk cos omega_k t + b_jk sin omega_k t).
struct SinusoidFit {
  std::vector<double> omega;  ///< [rad/s]
  std::vector<double> decay;  ///< [1/s]
  double rms_residual = 0.0;  ///< RMS of the residual over all samples
  double rms_signal = 0.0;    ///< RMS of the signals
  int iterations = 0;
};

/// Variable projection: for given (omega, sigma) the amplitudes solve a linear least-squares
/// problem per signal (QR); (omega, sigma) by Levenberg-Marquardt with a forward-difference
/// Jacobian, started from `omega0` and zero decay.
inline SinusoidFit fit_damped_sinusoids(const std::vector<double>& t,
                                        const std::vector<std::vector<double>>& signals,
                                        const std::vector<double>& omega0) {
  const int K = static_cast<int>(omega0.size());
  const int ns = static_cast<int>(t.size());
  const int nsig = static_cast<int>(signals.size());
  auto residual = [&](const Eigen::VectorXd& p) {
    Eigen::MatrixXd A(ns, 2 * K + 1);
    for (int i = 0; i < ns; ++i) {
      A(i, 0) = 1.0;
      for (int k = 0; k < K; ++k) {
        const double e = std::exp(-p(K + k) * t[i]);
        A(i, 1 + 2 * k) = e * std::cos(p(k) * t[i]);
        A(i, 2 + 2 * k) = e * std::sin(p(k) * t[i]);
      }
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
    Eigen::VectorXd r(ns * nsig);
    for (int j = 0; j < nsig; ++j) {
      const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(signals[j].data(), ns);
      r.segment(j * ns, ns) = y - A * qr.solve(y);
    }
    return r;
  };
  Eigen::VectorXd p(2 * K);
  for (int k = 0; k < K; ++k) {
    p(k) = omega0[k];
    p(K + k) = 0.0;
  }
  Eigen::VectorXd r = residual(p);
  double cost = r.squaredNorm(), lambda = 1e-3;
  SinusoidFit fit;
  for (int it = 0; it < 100; ++it) {
    Eigen::MatrixXd J(r.size(), 2 * K);
    for (int k = 0; k < 2 * K; ++k) {
      const double dp = 1e-7 * std::max(1.0, std::abs(p(k < K ? k : k - K)));
      Eigen::VectorXd q = p;
      q(k) += dp;
      J.col(k) = (residual(q) - r) / dp;
    }
    const Eigen::MatrixXd H = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 20; ++tries) {
      Eigen::MatrixXd Hl = H;
      Hl.diagonal() *= 1.0 + lambda;
      const Eigen::VectorXd dp = -Hl.ldlt().solve(g);
      const Eigen::VectorXd q = p + dp;
      const Eigen::VectorXd rq = residual(q);
      if (rq.squaredNorm() < cost) {
        const double rel = std::abs(cost - rq.squaredNorm()) / std::max(cost, 1e-300);
        p = q;
        r = rq;
        cost = rq.squaredNorm();
        lambda = std::max(lambda / 10.0, 1e-12);
        improved = true;
        fit.iterations = it + 1;
        if (rel < 1e-14) tries = 100;
        break;
      }
      lambda *= 10.0;
    }
    if (!improved) break;
  }
  double ss = 0.0;
  for (const auto& s : signals)
    for (const double v : s) ss += v * v;
  fit.rms_signal = std::sqrt(ss / (static_cast<double>(ns) * nsig));
  fit.rms_residual = std::sqrt(cost / (static_cast<double>(ns) * nsig));
  for (int k = 0; k < K; ++k) {
    fit.omega.push_back(p(k));
    fit.decay.push_back(p(K + k));
  }
  return fit;
}

// ---------------------------------------------------------------------------------------------
// Runs of the rod dynamics

/// A rod along +z without gravity (loads: only the tip force), for the small-amplitude checks.
inline rod::Loads tip_force_loads(const rod::RodModel& m, double fx_N) {
  rod::Loads l = rod::Loads::from_model(m);
  l.gravity_W_m_s2.setZero();
  l.tip_force_W_N = Eigen::Vector3d(fx_N, 0.0, 0.0);
  l.tip_moment_W_Nm.setZero();
  return l;
}

/// Outcome of a free-vibration run: the fitted frequencies and the references.
struct FreeVibration {
  std::vector<double> omega;        ///< fitted [rad/s]
  std::vector<double> decay;        ///< fitted decay rates [1/s]
  std::vector<double> omega_eb;     ///< Euler-Bernoulli [rad/s]
  std::vector<double> omega_timo;   ///< Timoshenko [rad/s]
  std::vector<double> omega_sched;  ///< Timoshenko shifted by the BDF-alpha oscillator error
  std::vector<double> decay_sched;  ///< decay rate of BDF-alpha on the Timoshenko frequency
  double fit_rms_ratio = 0.0;       ///< residual RMS / signal RMS of the fit
  int steps = 0;                    ///< time steps run
  int grid_steps = 0;               ///< N
  int intervals = 0;                ///< M
  double wall_s = 0.0;
  bool converged = false;
  std::string message;
  /// Relative error of mode k against EB.
  double eb_error(int k) const { return omega[k] / omega_eb[k] - 1.0; }
  double timo_error(int k) const { return omega[k] / omega_timo[k] - 1.0; }
};

/// Small-amplitude free vibration: static deflection under a tip force fx (no gravity), released
/// at t = 0; the grid states projected on the first `modes` EB mode shapes (plus one more to
/// absorb its leak) are fitted jointly over `duration` s. options.tip_mass_kg is the tip mass.
inline FreeVibration free_vibration(const rod::RodModel& m, cosserat::DynamicsOptions o,
                                    double fx_N, double duration_s, int modes,
                                    int sample_every = 1) {
  FreeVibration out;
  const Beam b = beam_of(m, o.tip_mass_kg.value_or(m.tip_mass_kg));
  const int K = modes + 1;
  const std::vector<double> roots = eb_cantilever_roots(b.mu(), K);
  const std::vector<double> w_eb = eb_frequencies_rad_s(b, K);
  cosserat::RodDynamics d(m, o);
  out.grid_steps = o.steps;
  cosserat::DynamicsSummary s = d.initialize(tip_force_loads(m, fx_N));
  out.intervals = d.intervals();
  if (!s.converged()) {
    out.message = "initialize: " + s.message;
    return out;
  }
  const rod::Loads released = tip_force_loads(m, 0.0);
  const int steps = static_cast<int>(std::lround(duration_s / o.dt_s));
  std::vector<double> t;
  std::vector<std::vector<double>> sig(K);
  auto sample = [&]() {
    t.push_back(d.time_s());
    for (int k = 0; k < K; ++k) sig[k].push_back(modal_coordinate(d.grid_states(), b, roots[k]));
  };
  const auto t0 = std::chrono::steady_clock::now();
  sample();
  for (int k = 0; k < steps; ++k) {
    s = d.step(released);
    if (!s.converged()) {
      out.message = "step " + std::to_string(k) + ": " + s.message;
      return out;
    }
    if ((k + 1) % sample_every == 0) sample();
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.steps = steps;
  const SinusoidFit fit = fit_damped_sinusoids(t, sig, w_eb);
  out.fit_rms_ratio = fit.rms_residual / fit.rms_signal;
  const std::vector<double> w_timo = timoshenko_frequencies_rad_s(b, modes);
  for (int k = 0; k < modes; ++k) {
    out.omega.push_back(fit.omega[k]);
    out.decay.push_back(fit.decay[k]);
    out.omega_eb.push_back(w_eb[k]);
    out.omega_timo.push_back(w_timo[k]);
    const DiscreteOscillator osc = bdf_alpha_oscillator(w_timo[k], o.dt_s, o.alpha);
    out.omega_sched.push_back(osc.omega);
    out.decay_sched.push_back(osc.decay);
  }
  out.converged = true;
  return out;
}

/// A tip-force pulse F(t) = F0 sin^2(pi t / tau) along x for t < tau, 0 after: smooth (its
/// spectrum falls like omega^-3 above 1 / tau), so it excites the first modes only.
inline double sine_squared_pulse(double t, double F0, double tau) {
  if (t <= 0.0 || t >= tau) return 0.0;
  const double s = std::sin(kPi * t / tau);
  return F0 * s * s;
}

/// Time series of a forced run (rod along +z, no gravity, no strings): per step the time, the
/// tip x, the mechanical energy E = kinetic + strain, the work of the tip force (trapezoid rule
/// on F . v_tip) and the energy dissipated by Kelvin-Voigt damping (trapezoid rule on the
/// dissipated power, docs/validation.md "validate_dynamics").
struct ForcedRun {
  std::vector<double> t, tip_x, energy, work, dissipated;
  bool converged = false;
  std::string message;
  double wall_s = 0.0;
  int steps = 0;
  /// The balance residual E(t) - E(0) + D(t) - W(t) at sample i.
  double balance(std::size_t i) const { return energy[i] - energy[0] + dissipated[i] - work[i]; }
};

/// Kelvin-Voigt strain-rate bookkeeping on the grid points: the section law of the rod dynamics
/// without strings, K z + B z_t = (N, M) per component (K, B diagonal), with the BDF-alpha
/// z_t = c0 z + c1 z(n) + c2 z(n-1) + d1 z_t(n), gives the strains z and rates z_t of the solver
/// at each grid point exactly; P = int z_t . B z_t ds (Simpson or trapezoid).
class DissipationMeter {
 public:
  DissipationMeter(const rod::RodModel& m, const cosserat::DynamicsOptions& o) : o_(o) {
    const Eigen::Vector3d kse = m.shear_extension_stiffness(), kbt = m.bending_torsion_stiffness();
    const double eta = o.viscosity_Pa_s.value_or(m.material.viscosity_profile.value(0.0));
    const rod::SectionStiffness B =
        rod::section_stiffness(m.section.properties_at(0.0), eta, m.material.shear_modulus(eta));
    K_ << kse, kbt;
    B_ << B.shear_extension, B.bending_torsion;
    L_ = m.length_m;
    const double a = o.alpha, dt = o.dt_s;
    c0_ = (1.5 + a) / (dt * (1.0 + a));
    c1_ = -2.0 / dt;
    c2_ = (0.5 + a) / (dt * (1.0 + a));
    d1_ = a / (1.0 + a);
  }
  /// The static initial state (z_t = 0, z(-1) = z(0)).
  void start(const std::vector<Eigen::VectorXd>& grid) {
    z_.clear();
    for (const auto& y : grid) {
      Eigen::Matrix<double, 6, 1> nm = y.segment<6>(12);
      z_.push_back(nm.cwiseQuotient(K_));
    }
    zp_ = z_;
    zt_.assign(grid.size(), Eigen::Matrix<double, 6, 1>::Zero());
  }
  /// After a step: updates the strains and returns the dissipated power [W].
  double step(const std::vector<Eigen::VectorXd>& grid) {
    const int n = static_cast<int>(grid.size()) - 1;
    const double h = L_ / n;
    double P = 0.0;
    for (int i = 0; i <= n; ++i) {
      const Eigen::Matrix<double, 6, 1> hist = c1_ * z_[i] + c2_ * zp_[i] + d1_ * zt_[i];
      const Eigen::Matrix<double, 6, 1> nm = grid[i].segment<6>(12);
      const Eigen::Matrix<double, 6, 1> z =
          (nm - B_.cwiseProduct(hist)).cwiseQuotient(K_ + c0_ * B_);
      zp_[i] = z_[i];
      z_[i] = z;
      zt_[i] = c0_ * z + hist;
      const bool end = i == 0 || i == n;
      const double w =
          (n % 2 == 0) ? h / 3.0 * (end ? 1.0 : (i % 2 ? 4.0 : 2.0)) : (end ? 0.5 * h : h);
      P += w * zt_[i].dot(B_.cwiseProduct(zt_[i]));
    }
    return P;
  }

 private:
  cosserat::DynamicsOptions o_;
  Eigen::Matrix<double, 6, 1> K_, B_;
  double L_ = 0.0, c0_ = 0.0, c1_ = 0.0, c2_ = 0.0, d1_ = 0.0;
  std::vector<Eigen::Matrix<double, 6, 1>> z_, zp_, zt_;
};

/// Runs from rest (static under force_x(0)) under the tip force force_x(t) along x for
/// `duration` s, recording every `sample_every` steps (energies need every step: the work and
/// dissipation integrals are accumulated each step).
inline ForcedRun forced_run(const rod::RodModel& m, const cosserat::DynamicsOptions& o,
                            const std::function<double(double)>& force_x, double duration_s,
                            int sample_every = 1) {
  ForcedRun out;
  cosserat::RodDynamics d(m, o);
  cosserat::DynamicsSummary s = d.initialize(tip_force_loads(m, force_x(0.0)));
  if (!s.converged()) {
    out.message = "initialize: " + s.message;
    return out;
  }
  DissipationMeter meter(m, o);
  meter.start(d.grid_states());
  auto tip_power = [&](double f) {
    const Eigen::VectorXd& y = d.grid_states().back();
    const Eigen::Map<const Eigen::Matrix3d> R(y.data() + 3);
    return f * (R * y.segment<3>(18)).x();
  };
  auto mech = [&](double f) {
    return d.kinetic_energy_J() + d.potential_energy_J() + f * d.tip_position_W_m().x();
  };
  double f_prev = force_x(0.0), P_in_prev = 0.0, P_d_prev = 0.0, W = 0.0, D = 0.0;
  auto record = [&](double f) {
    out.t.push_back(d.time_s());
    out.tip_x.push_back(d.tip_position_W_m().x());
    out.energy.push_back(mech(f));
    out.work.push_back(W);
    out.dissipated.push_back(D);
  };
  record(f_prev);
  const int steps = static_cast<int>(std::lround(duration_s / o.dt_s));
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    const double f = force_x((k + 1) * o.dt_s);
    s = d.step(tip_force_loads(m, f));
    if (!s.converged()) {
      out.message = "step " + std::to_string(k) + ": " + s.message;
      return out;
    }
    const double P_in = tip_power(f), P_d = meter.step(d.grid_states());
    W += 0.5 * o.dt_s * (P_in_prev + P_in);
    D += 0.5 * o.dt_s * (P_d_prev + P_d);
    P_in_prev = P_in;
    P_d_prev = P_d;
    f_prev = f;
    if ((k + 1) % sample_every == 0) record(f);
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.steps = steps;
  out.converged = true;
  return out;
}

/// A uniform steel rod along +z (E 200 GPa, poisson 0.25, rho 8000 kg/m^3, circular section of
/// radius r): the cantilever of [Till2019]'s dynamics example at r = 1 mm, L = 0.5 m; the
/// slender rod of the frequency checks at r = 0.5 mm.
inline rod::RodModel steel_rod(double r_m, double length_m) {
  rod::RodModel m;
  m.name = "steel-cantilever";
  m.length_m = length_m;
  const double d = 2.0 * r_m;
  m.section.shape = rod::Section::Shape::kCircle;
  m.section.width_profile = rod::Profile(d);
  m.section.height_profile = rod::Profile(d);
  m.material.youngs_modulus_profile = rod::Profile(200e9);
  m.material.poisson_ratio = 0.25;  // G = 200e9 / 2.5
  m.material.density_profile = rod::Profile(8000.0);
  return m;
}

/// Smoothstep 3 u^2 - 2 u^3 on [0, 1] (0 before, 1 after).
inline double smoothstep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

}  // namespace tcasim::dynamics_checks
