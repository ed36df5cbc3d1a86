// validate_dynamics: checks of the Cosserat rod dynamics (cosserat/dynamics.hpp) by the shooting
// method: a released cantilever, small-amplitude free vibration against Euler-Bernoulli, energy
// drift and energy balance, the order in dt, the quasi-static limit.
//
// What it checks (docs/validation.md "validate_dynamics"; references and signal analysis in
// validation/dynamics/dynamics_checks.hpp)
//   1. Released cantilever ([Till2019]: steel, r 1 mm, L 0.5 m, gravity across, a 20 g tip
//      weight removed at t = 0; dt 2 ms, alpha -0.2): every step converges and the total energy
//      never grows (BDF-alpha with alpha > -0.5 dissipates). Writes release.csv.
//   2. Free vibration of a slender steel cantilever (r 0.5 mm, L 0.5 m, no gravity), released
//      from a static tip deflection of 1e-4 L, with and without a tip mass (mass ratio 0.5): the
//      grid states projected on the Euler-Bernoulli mode shapes, the frequencies of one mode-1
//      period fitted jointly (damped sinusoids, variable projection). Gates: within 1e-4 of
//      Euler-Bernoulli (modes 1-3 at dt 2.5e-5 s; quick: mode 1 at dt 1 ms) and within 1e-6
//      (quick 3e-6) of the Timoshenko frequency shifted by BDF-alpha's own oscillator error.
//      Writes free_vibration.csv.
//   3. Energy under a smooth sin^2 tip-force pulse (0.2 s, then free motion to 0.9 s): undamped,
//      the drift after the pulse falls at third order in dt (the scheme's dissipation, decay
//      0.118 omega (omega dt)^3 at alpha -0.2) and the trapezoidal setting conserves; damped
//      (eta 2.3e8 Pa s), the balance W = E - E(0) + D closes at second order. Writes energy.csv
//      (time series at dt 1 ms) and energy_order.csv.
//   4. Order in dt (full run): the frequency error against Timoshenko (dt 1e-4 .. 2.5e-5) and the
//      pulse-forced tip trajectory (dt 2e-3 .. 2.5e-4 against 6.25e-5) in [1.8, 2.2]. Writes
//      dt_order.csv.
//   5. Quasi-static limit (full run): damped rod (damping ratio 0.5) under a smoothstep tip-force
//      ramp over tau = 1, 2, 4 s; the gap to the static shooting solution at the instantaneous
//      force falls like 1 / tau (order in [0.85, 1.15]). Writes quasi_static.csv.
//   6. Voltage step on the paper's circular manipulator (full run): temperature against the
//      closed-form step response, settling to the static answer at the steady temperature.
//   7. PWM-driven three-TCA rod in 3-D (validation/scenarios/three-tca-pwm.json; quick: shorter
//      and two drive rates): temperatures against the closed-form PWM response and its periodic
//      orbit to 1e-9 K, a tip path out of plane, the gap to the static tip at the instantaneous
//      temperatures falling like 1 / s as the drive is slowed s times (order in [0.85, 1.15]).
//      Writes pwm.csv, pwm_quasi_static_order.csv (validation/dynamics/tca_cases.cpp).
//   8. Heated quasi-static limit: the circular manipulator (damping ratio ~0.5) heated 25 ->
//      90 degC by smoothstep ramps over tau = 1, 2, 4 s (quick 1, 2 s at dt 10 ms): the gap to the
//      static solution at the instantaneous temperature falls like 1 / tau (order in [0.85, 1.15]).
//      Writes heated_ramp.csv, heated_ramp_order.csv.
//   9. Adaptive time steps (issue 35) in both methods, shooting and FE: the released cantilever
//      (1 s), the manipulator's voltage step and its 1 Hz 50 % PWM drive (10 s; full run only):
//      the max tip error against a reference refined in rtol falls like rtol^(2/3) (rate
//      in [0.52, 0.82]), the cost against fixed steps at equal error (reported), the two
//      methods' adaptive runs within their references' difference plus (N_S + N_F) rtol L.
//      Writes adaptive.csv, adaptive_order.csv, adaptive_agreement.csv
//      (validation/dynamics/adaptive_cases.cpp).
// Usage
//   validate_dynamics --out-dir out/dynamics            (full: minutes)
//   validate_dynamics --quick --out-dir /tmp/dynamics   (seconds)
//   validate_dynamics --adaptive-only --out-dir out/dynamics   (step 9 alone, minutes)
//   /usr/bin/python3 scripts/plot_dynamics.py out/dynamics
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/convergence.hpp"
#include "cosserat/shooting.hpp"
#include "rod/scenario.hpp"
#include "tca/thermal.hpp"
#include "validation/common/gates.hpp"
#include "validation/dynamics/adaptive_cases.hpp"
#include "validation/dynamics/dynamics_checks.hpp"
#include "validation/dynamics/tca_cases.hpp"

namespace tcasim::dynamics_validation {

namespace {
/// Smallest and largest observed order of a ladder (h decreasing).
std::pair<double, double> order_range(const std::vector<double>& h, const std::vector<double>& e) {
  const std::vector<double> p = observed_orders(h, e);
  double lo = 1e300, hi = -1e300;
  for (const double v : p) {
    if (!std::isfinite(v)) return {v, v};  // a NaN order fails the gates
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return {lo, hi};
}
}  // namespace

void gate_orders(validation::Gates& g, const std::string& name, const std::vector<double>& h,
                 const std::vector<double>& e, double expected, double tol, std::ofstream& csv) {
  const std::vector<double> p = observed_orders(h, e);
  for (std::size_t i = 0; i < h.size(); ++i)
    // The study name is quoted: it may hold commas.
    csv << fmt::format("\"{}\",{:.6e},{:.6e},{}\n", name, h[i], e[i],
                       i == 0 ? std::string() : fmt::format("{:.4f}", p[i - 1]));
  const auto [lo, hi] = order_range(h, e);
  g.within(name + ": smallest observed order", lo, expected - tol, expected + tol);
  g.within(name + ": largest observed order", hi, expected - tol, expected + tol);
}

}  // namespace tcasim::dynamics_validation

namespace {

using namespace tcasim;
using dynamics_validation::gate_orders;
namespace dc = tcasim::dynamics_checks;
using validation::Gates;

cosserat::DynamicsOptions options_at(const rod::RodModel& m, double dt, double alpha = -0.2) {
  cosserat::DynamicsOptions o;
  o.dt_s = dt;
  o.alpha = alpha;
  o.tolerance = 1e-12;
  o.steps = cosserat::recommended_steps(m, o);
  return o;
}

double tip_force_for(const rod::RodModel& m, double fraction) {
  const dc::Beam b = dc::beam_of(m, 0.0);
  return fraction * 3.0 * b.EI / (b.L * b.L);
}

// Step 1 ---------------------------------------------------------------------------------------
void released_cantilever(Gates& g, const std::string& out, bool quick) {
  const rod::RodModel m = dc::steel_rod(1e-3, 0.5);
  cosserat::DynamicsOptions o;
  o.dt_s = 2e-3;
  o.alpha = -0.2;
  o.steps = 40;
  rod::Loads sag = rod::Loads::from_model(m);
  sag.gravity_W_m_s2 = Eigen::Vector3d(-9.81, 0.0, 0.0);
  rod::Loads released = sag;
  sag.tip_force_W_N = 0.020 * sag.gravity_W_m_s2;
  const double duration = quick ? 0.2 : 1.0;
  fmt::print("Step 1: released steel cantilever, N {}, dt {} s, {} s\n", o.steps, o.dt_s, duration);
  cosserat::RodDynamics d(m, o);
  const cosserat::DynamicsSummary s0 = d.initialize(sag);
  if (!s0.converged()) {
    g.check("release: static initialization converges", false, s0.message, "converged");
    return;
  }
  std::ofstream csv(out + "/release.csv");
  csv << "t_s,tip_x_m,tip_y_m,tip_z_m,kinetic_J,potential_J,total_J\n";
  auto row = [&]() {
    const Eigen::Vector3d p = d.tip_position_W_m();
    csv << fmt::format("{:.6f},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n", d.time_s(), p.x(),
                       p.y(), p.z(), d.kinetic_energy_J(), d.potential_energy_J(),
                       d.kinetic_energy_J() + d.potential_energy_J());
  };
  row();
  const int steps = static_cast<int>(std::lround(duration / o.dt_s));
  int failed = -1;
  double rise = -1e300, e0 = 0.0, e_prev = 0.0;
  for (int k = 0; k < steps; ++k) {
    const cosserat::DynamicsSummary s = d.step(released);
    if (!s.converged()) {
      failed = k;
      break;
    }
    const double e = d.kinetic_energy_J() + d.potential_energy_J();
    if (k == 0) e0 = e;
    if (k > 0) rise = std::max(rise, (e - e_prev) / std::abs(e0));
    e_prev = e;
    row();
  }
  g.check("release: every step converges", failed < 0,
          failed < 0 ? fmt::format("{} steps", steps) : fmt::format("step {} failed", failed),
          "all converge");
  g.at_most("release: largest energy rise per step (relative to E after step 1)", rise, 1e-12);
}

// Step 2 ---------------------------------------------------------------------------------------
void free_vibration(Gates& g, const std::string& out, bool quick) {
  const rod::RodModel m = dc::steel_rod(0.5e-3, 0.5);
  const dc::Beam b0 = dc::beam_of(m, 0.0);
  const double dt = quick ? 1e-3 : 2.5e-5;
  const int modes = quick ? 1 : 3;
  fmt::print("Step 2: free vibration of the slender cantilever, {} mode(s), dt {} s\n", modes, dt);
  std::ofstream csv(out + "/free_vibration.csv");
  csv << "mass_ratio,mode,dt_s,grid_steps,omega_rad_s,euler_bernoulli_rad_s,timoshenko_rad_s,"
         "error_vs_eb,error_vs_timoshenko,timoshenko_correction,error_vs_timoshenko_plus_scheme,"
         "decay_1_s,scheme_decay_1_s,wall_s\n";
  for (const double mu : {0.0, 0.5}) {
    cosserat::DynamicsOptions o = options_at(m, dt);
    o.tip_mass_kg = mu * b0.rhoA * b0.L;
    const double w1 = dc::eb_frequencies_rad_s(dc::beam_of(m, *o.tip_mass_kg), 1)[0];
    const int every = quick ? 1 : 4;
    const dc::FreeVibration fv = dc::free_vibration(
        m, o, tip_force_for(m, 1e-4), (quick ? 2.0 : 1.0) * 2.0 * dc::kPi / w1, modes, every);
    const std::string tag = fmt::format("free vibration mu {}", mu);
    if (!fv.converged) {
      g.check(tag + ": run converges", false, fv.message, "converged");
      continue;
    }
    fmt::print("  mu {}: N {}, {} steps in {:.1f} s\n", mu, fv.grid_steps, fv.steps, fv.wall_s);
    for (int k = 0; k < modes; ++k) {
      const double sched = fv.omega[k] / fv.omega_sched[k] - 1.0;
      csv << fmt::format(
          "{},{},{:.3e},{},{:.10e},{:.10e},{:.10e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.2f}"
          "\n",
          mu, k + 1, dt, fv.grid_steps, fv.omega[k], fv.omega_eb[k], fv.omega_timo[k],
          fv.eb_error(k), fv.timo_error(k), fv.omega_timo[k] / fv.omega_eb[k] - 1.0, sched,
          fv.decay[k], fv.decay_sched[k], fv.wall_s);
      g.at_most(fmt::format("{} mode {}: |omega / omega_EB - 1|", tag, k + 1),
                std::abs(fv.eb_error(k)), 1e-4);
      g.at_most(fmt::format("{} mode {}: |omega / (Timoshenko + scheme error) - 1|", tag, k + 1),
                std::abs(sched), quick ? 3e-6 : 1e-6);
    }
  }
}

// Step 3 ---------------------------------------------------------------------------------------
constexpr double kPulse = 0.2, kPulseRun = 0.9;

dc::ForcedRun pulse_run(const rod::RodModel& m, double dt, double alpha, double eta,
                        int every = 1) {
  cosserat::DynamicsOptions o = options_at(m, dt, alpha);
  o.viscosity_Pa_s = eta;
  const double F0 = tip_force_for(m, 1e-2);
  return dc::forced_run(
      m, o, [F0](double t) { return dc::sine_squared_pulse(t, F0, kPulse); }, kPulseRun, every);
}

std::size_t index_at(const dc::ForcedRun& r, double t) {
  std::size_t i = 0;
  while (i + 1 < r.t.size() && r.t[i] < t - 1e-12) ++i;
  return i;
}

void energy(Gates& g, const std::string& out, bool quick, std::ofstream& orders) {
  const rod::RodModel m = dc::steel_rod(0.5e-3, 0.5);
  const double w1 = dc::eb_frequencies_rad_s(dc::beam_of(m, 0.0), 1)[0];
  const double eta = 2.3e8;
  fmt::print("Step 3: energy under a sin^2 tip-force pulse (undamped and eta {} Pa s)\n", eta);
  std::vector<double> dts = {4e-3, 2e-3, 1e-3};
  if (!quick) dts.push_back(5e-4);
  std::vector<double> drift, balance, damped_balance;
  std::ofstream series(out + "/energy.csv");
  series << "case,t_s,tip_x_m,energy_J,work_J,dissipated_J,balance_J\n";
  for (const double dt : dts) {
    for (const double visc : {0.0, eta}) {
      const dc::ForcedRun r = pulse_run(m, dt, -0.2, visc);
      const std::string tag = visc > 0.0 ? "damped" : "undamped";
      if (!r.converged) {
        g.check(fmt::format("energy {} dt {}: run converges", tag, dt), false, r.message,
                "converged");
        return;
      }
      const std::size_t ip = index_at(r, kPulse), ie = r.t.size() - 1;
      double worst = 0.0;
      for (std::size_t i = 0; i <= ie; ++i) worst = std::max(worst, std::abs(r.balance(i)));
      if (visc == 0.0) {
        drift.push_back((r.energy[ip] - r.energy[ie]) / r.energy[ip]);
        balance.push_back(std::abs(r.balance(ip)) / r.work[ip]);
        const double pred =
            2.0 * dc::bdf_alpha_oscillator(w1, dt, -0.2).decay * (r.t[ie] - r.t[ip]);
        fmt::print("  dt {:.0e}: undamped drift {:.3e} (mode-1 prediction {:.3e})\n", dt,
                   drift.back(), pred);
        g.within(fmt::format("energy undamped dt {}: drift / mode-1 prediction", dt),
                 drift.back() / pred, 1.0, 1.3);
      } else {
        damped_balance.push_back(worst / r.work[ip]);
        fmt::print("  dt {:.0e}: damped: dissipated {:.3e} J of {:.3e} J, balance {:.3e}\n", dt,
                   r.dissipated[ie], r.work[ip], damped_balance.back());
        bool falls = true;
        for (std::size_t i = ip + 10; i <= ie; ++i) falls = falls && r.energy[i] < r.energy[i - 10];
        g.check(fmt::format("energy damped dt {}: energy falls over every 10 steps after the pulse",
                            dt),
                falls, falls ? "falls" : "rises somewhere", "falls");
      }
      if (dt == 1e-3)
        for (std::size_t i = 0; i <= ie; ++i)
          series << fmt::format("{},{:.6f},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n", tag, r.t[i],
                                r.tip_x[i], r.energy[i], r.work[i], r.dissipated[i], r.balance(i));
    }
  }
  gate_orders(g, "undamped energy drift after the pulse (order 3)", dts, drift, 3.0, 0.3, orders);
  gate_orders(g, "undamped balance during the pulse (order 2)", dts, balance, 2.0, 0.3, orders);
  gate_orders(g, "damped energy balance residual (order 2)", dts, damped_balance, 2.0, 0.2, orders);
  const dc::ForcedRun trap = pulse_run(m, 4e-3, -0.5, 0.0);
  if (!trap.converged) {
    g.check("trapezoidal (alpha -0.5) dt 4 ms: run converges", false, trap.message, "converged");
    return;
  }
  const std::size_t ip = index_at(trap, kPulse);
  g.at_most("trapezoidal (alpha -0.5) dt 4 ms: energy drift after the pulse",
            std::abs(trap.energy.back() - trap.energy[ip]) / trap.energy[ip], 1e-7);
}

// Step 4 ---------------------------------------------------------------------------------------
void dt_order(Gates& g, std::ofstream& orders) {
  fmt::print("Step 4: order in dt (frequency error, smoothly forced trajectory)\n");
  const rod::RodModel m = dc::steel_rod(0.5e-3, 0.5);
  const dc::Beam b = dc::beam_of(m, 0.0);
  const double w1 = dc::eb_frequencies_rad_s(b, 1)[0];
  std::vector<double> h;
  std::vector<std::vector<double>> err(3);
  for (const double dt : {1e-4, 5e-5, 2.5e-5}) {
    const int every = std::max(1, static_cast<int>(std::lround(1e-4 / dt)));
    const dc::FreeVibration fv = dc::free_vibration(m, options_at(m, dt), tip_force_for(m, 1e-4),
                                                    2.0 * dc::kPi / w1, 3, every);
    if (!fv.converged) {
      g.check(fmt::format("frequency order dt {}: run converges", dt), false, fv.message,
              "converged");
      return;
    }
    h.push_back(dt);
    for (int k = 0; k < 3; ++k) err[k].push_back(std::abs(fv.timo_error(k)));
  }
  for (int k = 0; k < 3; ++k)
    gate_orders(g, fmt::format("frequency error mode {} vs Timoshenko (order 2)", k + 1), h, err[k],
                2.0, 0.2, orders);
  auto run = [&](double dt) {
    return pulse_run(m, dt, -0.2, 0.0, static_cast<int>(std::lround(0.01 / dt)));
  };
  const dc::ForcedRun ref = run(6.25e-5);
  if (!ref.converged) {
    g.check("trajectory order: reference converges", false, ref.message, "converged");
    return;
  }
  std::vector<double> th, te;
  for (const double dt : {2e-3, 1e-3, 5e-4, 2.5e-4}) {
    const dc::ForcedRun r = run(dt);
    if (!r.converged || r.tip_x.size() != ref.tip_x.size()) {
      g.check(fmt::format("trajectory order dt {}: run converges", dt), false, r.message,
              "converged");
      return;
    }
    double e = 0.0;
    for (std::size_t i = 0; i < r.tip_x.size(); ++i)
      e = std::max(e, std::abs(r.tip_x[i] - ref.tip_x[i]));
    th.push_back(dt);
    te.push_back(e / m.length_m);
  }
  gate_orders(g, "pulse-forced tip trajectory, max error / L (order 2)", th, te, 2.0, 0.2, orders);
}

// Step 5 ---------------------------------------------------------------------------------------
void quasi_static(Gates& g, const std::string& out) {
  fmt::print("Step 5: quasi-static limit under a slow tip-force ramp\n");
  const rod::RodModel m = dc::steel_rod(0.5e-3, 0.5);
  const double F0 = tip_force_for(m, 0.2);
  cosserat::Options so;
  so.integrator.method = ode::Method::kRk8;
  so.integrator.steps = 64;
  so.tolerance = 1e-12;
  std::ofstream csv(out + "/quasi_static.csv");
  csv << "ramp_s,t_s,force_N,tip_x_m,static_tip_x_m,gap_over_L\n";
  std::vector<double> rate, gap;
  for (const double tau : {1.0, 2.0, 4.0}) {
    cosserat::DynamicsOptions o = options_at(m, 4e-3);
    o.viscosity_Pa_s = 1.14e10;
    cosserat::RodDynamics d(m, o);
    if (!d.initialize(dc::tip_force_loads(m, 0.0)).converged()) {
      g.check("quasi-static: initialization converges", false, "failed", "converged");
      return;
    }
    const int steps = static_cast<int>(std::lround(tau / o.dt_s));
    double worst = 0.0;
    for (int k = 1; k <= steps; ++k) {
      const double f = F0 * dc::smoothstep(k * o.dt_s / tau);
      const cosserat::DynamicsSummary s = d.step(dc::tip_force_loads(m, f));
      if (!s.converged()) {
        g.check(fmt::format("quasi-static ramp {} s: steps converge", tau), false, s.message,
                "converged");
        return;
      }
      if (k % (steps / 20) == 0) {
        cosserat::ShootingSolver solver(m, so);
        cosserat::Solution sol;
        if (!solver.solve(dc::tip_force_loads(m, f), sol).converged()) {
          g.check("quasi-static: static reference converges", false, "failed", "converged");
          return;
        }
        const double gp = (d.tip_position_W_m() - sol.tip_state.head<3>()).norm() / m.length_m;
        worst = std::max(worst, gp);
        csv << fmt::format("{},{:.4f},{:.6e},{:.9e},{:.9e},{:.4e}\n", tau, d.time_s(), f,
                           d.tip_position_W_m().x(), sol.tip_state(0), gp);
      }
    }
    fmt::print("  ramp {} s: largest gap {:.3e} L\n", tau, worst);
    rate.push_back(1.0 / tau);
    gap.push_back(worst);
  }
  std::ofstream orders(out + "/quasi_static_order.csv");
  orders << "study,h,error,observed_order\n";
  gate_orders(g, "quasi-static gap vs ramp rate 1/tau (order 1)", rate, gap, 1.0, 0.15, orders);
}

// Step 6 ---------------------------------------------------------------------------------------
/// A voltage step on the paper's circular manipulator (temperature, tension and tip over time,
/// settling to the static answer at the steady temperature); voltage_step.csv.
void run_tca_cases(Gates& g, const std::string& out, bool quick) {
  if (quick) {
    // The quick run's TCA check is the unit test RodDynamicsTca (a shortened time constant).
    fmt::print("Step 6: voltage step on the circular manipulator: full run only\n");
    return;
  }
  fmt::print("Step 6: voltage step on the circular manipulator (40 s)\n");
  // validation/scenarios/circular-manipulator-voltage.json with the voltage switched on at
  // t = 0+ (ambient before) and Kelvin-Voigt damping of 1000 Pa s; the shipped thermal data
  // (time constant 3.43 s, constant resistance).
  const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios";
  std::ifstream in(dir / "circular-manipulator-voltage.json");
  nlohmann::json j = nlohmann::json::parse(in);
  const double volts = j["actuators"][0]["drive"]["electric"]["voltage_V"].get<double>();
  j["actuators"][0]["drive"]["electric"] = {
      {"voltage_V", {{"step", {{"t_s", 0.0}, {"before", 0.0}, {"after", volts}}}}}};
  j["body"]["material"]["viscosity_Pa_s"] = 1000.0;
  const rod::RodModel m = rod::parse_scenario(j, dir.string());
  const tca::ThermalParameters& th = m.actuators[0].drive.electric[0].thermal;
  const tca::SteadyTemperature ss =
      tca::steady_temperature(th, tca::ElectricInput::kVoltage, volts);
  if (!g.check("voltage step: a steady temperature exists", ss.exists,
               ss.exists ? fmt::format("{:.3f} degC", ss.temperature_K - 273.15) : ss.reason,
               "exists")) {
    return;
  }
  const double tau = th.time_constant_s(), T_amb = th.ambient_K;
  // Static answer at the steady temperature (RK8, converged to round-off on this rod).
  cosserat::Options so;
  so.integrator.method = ode::Method::kRk8;
  so.integrator.steps = 64;
  so.tolerance = 1e-12;
  cosserat::ShootingSolver ref(m, so);
  cosserat::Solution sol;
  const bool ref_ok = ref.solve(rod::Loads::at_time(m, 1.0), sol).converged();
  if (!g.check("voltage step: static solve at the steady temperature converges", ref_ok,
               ref_ok ? "converged" : "failed", "converged")) {
    return;
  }
  const Eigen::Vector3d p_static = sol.tip_state.head<3>();
  cosserat::DynamicsOptions o;
  o.dt_s = 1e-2;
  o.steps = cosserat::recommended_steps(m, o);
  o.tolerance = 1e-12;
  cosserat::RodDynamics d(m, o);
  const cosserat::DynamicsSummary init = d.initialize(rod::Loads::from_model(m));
  if (!g.check("voltage step: static state at ambient converges", init.converged(),
               init.converged() ? "converged" : init.message, "converged")) {
    return;
  }
  const Eigen::Vector3d p0 = d.tip_position_W_m();
  std::ofstream csv(out + "/voltage_step.csv");
  csv << "t_s,temperature_degC,closed_form_temperature_degC,tension_N,tip_x_m,tip_z_m,"
         "static_tip_x_m,static_tip_z_m\n";
  auto row = [&](double T_cf) {
    const Eigen::Vector3d p = d.tip_position_W_m();
    csv << fmt::format("{:.4f},{:.9f},{:.9f},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n", d.time_s(),
                       d.segment_temperatures_K()[0][0] - 273.15, T_cf - 273.15, d.tensions_N()[0],
                       p.x(), p.z(), p_static.x(), p_static.z());
  };
  row(T_amb);
  const int n_steps = 4000;  // 40 s, 11.7 time constants
  double worst_T = 0.0;
  for (int k = 1; k <= n_steps; ++k) {
    const double t = k * o.dt_s;
    const cosserat::DynamicsSummary s = d.step(rod::Loads::at_time(m, t));
    if (!s.converged()) {
      g.check("voltage step: every step converges", false,
              fmt::format("t = {} s: {}", t, s.message), "all converge");
      return;
    }
    // Lumped step response T(t) = T_amb + (T_ss - T_amb) (1 - exp(-t / tau)) ([Yip2017]).
    const double T_cf = T_amb + (ss.temperature_K - T_amb) * (1.0 - std::exp(-t / tau));
    worst_T = std::max(worst_T, std::abs(d.segment_temperatures_K()[0][0] - T_cf));
    if (k % 10 == 0) row(T_cf);
  }
  const double travel = (p_static - p0).norm();
  const double gap = (d.tip_position_W_m() - p_static).norm();
  fmt::print(
      "  tip travel {:.4e} m; |tip - static| at 40 s {:.3e} m; worst |T - closed form| "
      "{:.2e} K\n",
      travel, gap, worst_T);
  // Constant resistance: the exact thermal step reproduces the closed form to round-off.
  if (th.resistance_temperature_coefficient_1_K == 0.0) {
    g.at_most("voltage step: worst |T - closed-form step response| [K]", worst_T, 1e-9);
  }
  // After 11.7 time constants the thermal remainder is 8e-6 of the temperature rise; the grid's
  // spatial error (RK4 at the dynamics grid against RK8) adds below 1e-4 of the travel.
  g.at_most("voltage step: |tip - static at the steady temperature| / travel at 40 s", gap / travel,
            1e-4);
  g.at_most("voltage step: |tension - static tension| / |static tension| at 40 s",
            std::abs(d.tensions_N()[0] - sol.tensions_N[0]) / std::abs(sol.tensions_N[0]), 1e-4);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Checks of the Cosserat rod dynamics by shooting"};
  bool quick = false;
  std::string out_dir = "dynamics-out";
  app.add_flag("--quick", quick, "the fast subset (seconds)");
  app.add_option("--out-dir", out_dir, "output folder for CSV files");
  bool adaptive_only = false;
  app.add_flag("--adaptive-only", adaptive_only, "step 9 alone (full settings; minutes)");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out_dir);
  Gates gates("validate_dynamics");
  try {
    if (adaptive_only) {
      dynamics_validation::adaptive_steps(gates, out_dir, false);
      gates.write_csv(out_dir);
      return gates.finish();
    }
    released_cantilever(gates, out_dir, quick);
    free_vibration(gates, out_dir, quick);
    std::ofstream orders(out_dir + "/dt_order.csv");
    orders << "study,h,error,observed_order\n";
    energy(gates, out_dir, quick, orders);
    if (!quick) {
      dt_order(gates, orders);
      quasi_static(gates, out_dir);
    }
    run_tca_cases(gates, out_dir, quick);
    dynamics_validation::pwm_three_tca(gates, out_dir, quick);
    dynamics_validation::heated_quasi_static(gates, out_dir, quick);
    dynamics_validation::adaptive_steps(gates, out_dir, quick);
  } catch (const std::exception& e) {
    gates.check("validate_dynamics: runs without an exception", false, e.what(), "no exception");
  }
  gates.write_csv(out_dir);
  return gates.finish();
}
