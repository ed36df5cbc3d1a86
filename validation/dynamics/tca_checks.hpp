#pragma once
/// References and runs of the TCA-driven rod-dynamics checks
/// (tests/cosserat/dynamics_checks_test.cpp and validate_dynamics): the closed-form temperature of
/// the lumped thermal law under a PWM input (piecewise exponential, and its periodic steady state),
/// the static solution at given TCA temperatures, and a slowly heated damped rod against the static
/// solution at its instantaneous temperature. Header-only (public API of cosserat::RodDynamics and
/// cosserat::ShootingSolver only).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "cosserat/shooting.hpp"
#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "tca/thermal.hpp"

namespace tcasim::dynamics_checks {

/// A PWM input (docs/scenario-format.md "Time profiles"): `high` on (k P, k P + d P], `low` on
/// (k P + d P, (k + 1) P].
struct Pwm {
  double period_s = 1.0;
  double duty = 0.5;
  double high = 0.0;
  double low = 0.0;
};

/// Steady temperature [K] of a constant voltage v on a TCA of constant resistance:
/// hA (T - T_amb) = v^2 / R0.
inline double linear_steady_temperature_K(const tca::ThermalParameters& th, double v) {
  return th.ambient_K + v * v / (th.resistance_ohm * th.conductance_W_K);
}

/// Closed-form temperature at t [s] of the lumped law C dT/dt = v(t)^2 / R0 - hA (T - T_amb)
/// (constant resistance: linear in T) under a PWM voltage, from T0 at t = 0: over each constant
/// part of length l the exact solution T <- T_inf + (T - T_inf) exp(-l / tau), tau = C / hA
/// ([Yip2017]), walked part by part from t = 0.
inline double pwm_temperature_K(const tca::ThermalParameters& th, const Pwm& pwm, double T0_K,
                                double t_s) {
  const double tau = th.time_constant_s();
  const double T_high = linear_steady_temperature_K(th, pwm.high),
               T_low = linear_steady_temperature_K(th, pwm.low);
  double T = T0_K, a = 0.0;
  for (long k = 0; a < t_s; ++k) {
    const double t_on = k * pwm.period_s, t_off = t_on + pwm.duty * pwm.period_s,
                 t_end = (k + 1) * pwm.period_s;
    for (const auto& [b, T_inf] : {std::pair{t_off, T_high}, std::pair{t_end, T_low}}) {
      const double e = std::min(b, t_s);
      if (e > a) {
        T = T_inf + (T - T_inf) * std::exp(-(e - a) / tau);
        a = e;
      }
    }
  }
  return T;
}

/// The periodic steady state of the PWM-driven lumped law: the temperatures at the end of the
/// high part and at the end of a period. With x = exp(-d P / tau), y = exp(-(1 - d) P / tau):
///   T_H = T_inf,high (1 - x) + x T_L,  T_L = T_inf,low (1 - y) + y T_H,
/// so T_L = (T_inf,low (1 - y) + y (1 - x) T_inf,high) / (1 - x y). A start T0 differs from the
/// orbit by (T0 - T_L) exp(-t / tau) at every later period end t = n P (the law is linear).
struct PwmCycle {
  double end_of_high_K = 0.0;
  double end_of_period_K = 0.0;
};
inline PwmCycle pwm_cycle(const tca::ThermalParameters& th, const Pwm& pwm) {
  const double tau = th.time_constant_s();
  const double x = std::exp(-pwm.duty * pwm.period_s / tau),
               y = std::exp(-(1.0 - pwm.duty) * pwm.period_s / tau);
  const double Th = linear_steady_temperature_K(th, pwm.high),
               Tl = linear_steady_temperature_K(th, pwm.low);
  PwmCycle c;
  c.end_of_period_K = (Tl * (1.0 - y) + y * (1.0 - x) * Th) / (1.0 - x * y);
  c.end_of_high_K = Th * (1.0 - x) + x * c.end_of_period_K;
  return c;
}

/// A static shooting solver converged to round-off on these rods (RK8, 64 steps).
inline cosserat::Options reference_static_options() {
  cosserat::Options so;
  so.integrator.method = ode::Method::kRk8;
  so.integrator.steps = 64;
  so.tolerance = 1e-12;
  return so;
}

/// A damped rod driven slowly by temperatures: per sample the time, the dynamic tip, the static
/// tip at the same temperatures and their distance.
struct QuasiStaticRun {
  std::vector<double> t_s, gap_m;
  std::vector<Eigen::Vector3d> tip_m, static_tip_m;
  std::vector<std::vector<double>> temperature_K;  ///< first segment of each actuator
  double worst_gap_m = 0.0;
  double travel_m = 0.0;  ///< largest distance of the static tip from its start
  bool converged = false;
  std::string message;
};

/// Runs `steps` time steps of `o` from the static state at loads_at(0), sampling every
/// `sample_every` steps: the dynamic tip against the static solution (reference options) at the
/// dynamics' instantaneous TCA temperatures, loads_at(t) otherwise.
/// `each_step` (optional) sees the solver after every converged step.
inline QuasiStaticRun quasi_static_run(
    const rod::RodModel& m, const cosserat::DynamicsOptions& o,
    const std::function<rod::Loads(double)>& loads_at, long steps, long sample_every,
    const std::function<void(const cosserat::RodDynamics&)>& each_step = {}) {
  QuasiStaticRun out;
  cosserat::RodDynamics d(m, o);
  const cosserat::DynamicsSummary s0 = d.initialize(loads_at(0.0));
  if (!s0.converged()) {
    out.message = "initialize: " + s0.message;
    return out;
  }
  cosserat::ShootingSolver ref(m, reference_static_options());
  cosserat::Solution sol;
  Eigen::Vector3d p_start = Eigen::Vector3d::Zero();
  auto sample = [&](long k) {
    const double t = d.time_s();
    rod::Loads l = loads_at(t);
    const std::vector<std::vector<double>> T = d.segment_temperatures_K();
    for (std::size_t i = 0; i < T.size(); ++i)
      for (std::size_t j = 0; j < T[i].size(); ++j)
        l.actuators[i].segments[j].temperature_K = T[i][j];
    if (!ref.solve(l, sol).converged()) {
      out.message = "static reference at t = " + std::to_string(t) + " did not converge";
      return false;
    }
    const Eigen::Vector3d ps = sol.tip_state.head<3>(), p = d.tip_position_W_m();
    if (k == 0) p_start = ps;
    out.t_s.push_back(t);
    out.tip_m.push_back(p);
    out.static_tip_m.push_back(ps);
    out.gap_m.push_back((p - ps).norm());
    std::vector<double> Tf;
    for (const auto& Ti : T) Tf.push_back(Ti.empty() ? std::nan("") : Ti.front());
    out.temperature_K.push_back(Tf);
    out.worst_gap_m = std::max(out.worst_gap_m, out.gap_m.back());
    out.travel_m = std::max(out.travel_m, (ps - p_start).norm());
    return true;
  };
  if (!sample(0)) return out;
  for (long k = 1; k <= steps; ++k) {
    const cosserat::DynamicsSummary s = d.step(loads_at(k * o.dt_s));
    if (!s.converged()) {
      out.message = "step to t = " + std::to_string(k * o.dt_s) + ": " + s.message;
      return out;
    }
    if (each_step) each_step(d);
    if (k % sample_every == 0 && !sample(k)) return out;
  }
  out.converged = true;
  return out;
}

/// Smoothstep temperature ramp from T_from to T_to over tau [s] (C^1: no jump in the heating
/// rate at either end), the loads of a temperature-driven TCA rod (every TCA segment).
inline std::function<rod::Loads(double)> heating_ramp(const rod::RodModel& m, double T_from_K,
                                                      double T_to_K, double tau_s) {
  return [&m, T_from_K, T_to_K, tau_s](double t) {
    const double u = std::clamp(t / tau_s, 0.0, 1.0);
    const double T = T_from_K + (T_to_K - T_from_K) * u * u * (3.0 - 2.0 * u);
    rod::Loads l = rod::Loads::from_model(m);
    for (auto& a : l.actuators)
      for (auto& sg : a.segments) sg.temperature_K = T;
    return l;
  };
}

}  // namespace tcasim::dynamics_checks
