// validate_dynamics steps 7 and 8 (validation/dynamics/dynamics.cpp has the header of the
// program; docs/validation.md "validate_dynamics"):
//   7. PWM-driven three-TCA rod in 3-D (validation/scenarios/three-tca-pwm.json): the
//      temperatures against the closed-form piecewise-exponential response of the lumped law
//      (every step) and its periodic steady state (every period end), every step converging, a
//      tip path out of any plane, and the tip following the static solution at the
//      instantaneous temperatures: the drive slowed by s (heat capacity and PWM periods times
//      s), the largest gap falls like 1 / s.
//   8. Heated quasi-static limit: the circular manipulator (temperature drive, damping ratio
//      about 0.5) heated 25 -> 90 degC by smoothstep ramps over tau; the largest gap to the
//      static solution at the instantaneous temperature falls like 1 / tau (a viscous lag).
#include "validation/dynamics/tca_cases.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/units.hpp"
#include "rod/scenario.hpp"
#include "validation/dynamics/tca_checks.hpp"

namespace tcasim::dynamics_validation {

namespace {

namespace dc = tcasim::dynamics_checks;

const std::filesystem::path& scenario_dir() {
  static const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios";
  return dir;
}

nlohmann::json read_json(const std::string& name) {
  std::ifstream in(scenario_dir() / name);
  return nlohmann::json::parse(in);
}

/// The closed form's round-off over a run: the exact thermal step and the part-by-part walk
/// each lose about 1e-13 of the temperature per exponential (thousands of them).
constexpr double kThermalRoundOff_K = 1e-9;
/// Time step of the PWM runs: 2^-7 s (2^-6 s quick), so every switching time is a step time
/// exactly (the exact thermal step holds the input of the step's end).
constexpr double kPwmDt = 1.0 / 128.0, kPwmDtQuick = 1.0 / 64.0;

struct PwmRod {
  rod::RodModel model;
  std::vector<dc::Pwm> pwm;  // per actuator
};

/// three-tca-pwm.json with the drive slowed by `slow` (PWM periods and heat capacity times it).
PwmRod pwm_rod(double slow) {
  nlohmann::json j = read_json("three-tca-pwm.json");
  PwmRod r;
  for (auto& a : j["actuators"]) {
    nlohmann::json& p = a["drive"]["electric"]["voltage_V"]["pwm"];
    p["period_s"] = p["period_s"].get<double>() * slow;
    r.pwm.push_back({p["period_s"].get<double>(), p["duty"].get<double>(), p["high"].get<double>(),
                     p["low"].get<double>()});
  }
  r.model = rod::parse_scenario(j, scenario_dir().string());
  for (auto& a : r.model.actuators) a.drive.electric.at(0).thermal.heat_capacity_J_K *= slow;
  return r;
}

/// Ratio of the smaller to the larger principal spread of the tip's path across the rod's axis
/// (x, y): 0 for a path in a plane through the axis.
double out_of_plane_ratio(const std::vector<Eigen::Vector3d>& tip) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : tip) mean += p.head<2>();
  mean /= static_cast<double>(tip.size());
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
  for (const auto& p : tip) C += (p.head<2>() - mean) * (p.head<2>() - mean).transpose();
  const Eigen::Vector2d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(C).eigenvalues();
  return std::sqrt(std::max(ev(0), 0.0) / ev(1));
}

}  // namespace

void pwm_three_tca(validation::Gates& g, const std::string& out, bool quick) {
  const double dt = quick ? kPwmDtQuick : kPwmDt;
  const std::vector<double> slows =
      quick ? std::vector<double>{1.0, 2.0} : std::vector<double>{1.0, 2.0, 4.0};
  const double base_duration = quick ? 4.0 : 8.0;  // s, at slow = 1
  fmt::print("Step 7: PWM-driven three-TCA rod in 3-D (dt {} s, drive slowed by", dt);
  for (const double s : slows) fmt::print(" {}", s);
  fmt::print(")\n");
  std::ofstream csv(out + "/pwm.csv");
  csv << "slow,t_s";
  const PwmRod first = pwm_rod(1.0);
  for (const auto& a : first.model.actuators)
    csv << fmt::format(",{0}_temperature_degC,{0}_closed_form_degC,{0}_tension_N", a.name);
  csv << ",tip_x_m,tip_y_m,tip_z_m,static_tip_x_m,static_tip_y_m,static_tip_z_m,gap_m\n";
  std::vector<double> rate, gap;
  for (const double slow : slows) {
    const PwmRod r = pwm_rod(slow);
    const rod::RodModel& m = r.model;
    const int n = static_cast<int>(m.actuators.size());
    std::vector<tca::ThermalParameters> th;
    std::vector<double> T0;
    const rod::Loads l0 = rod::Loads::from_model(m);
    for (int i = 0; i < n; ++i) {
      th.push_back(m.actuators[i].drive.electric.at(0).thermal);
      T0.push_back(l0.actuators[i].segments.at(0).temperature_K);
    }
    cosserat::DynamicsOptions o;
    o.dt_s = dt;
    o.steps = cosserat::recommended_steps(m, o);
    o.tolerance = 1e-12;
    const long steps = std::lround(base_duration * slow / dt);
    double worst_T = 0.0, worst_cycle = 0.0;
    std::vector<std::vector<double>> T_cf_rows;
    const auto each_step = [&](const cosserat::RodDynamics& d) {
      const double t = d.time_s();
      const std::vector<std::vector<double>> T = d.segment_temperatures_K();
      std::vector<double> cf;
      for (int i = 0; i < n; ++i) {
        cf.push_back(dc::pwm_temperature_K(th[i], r.pwm[i], T0[i], t));
        worst_T = std::max(worst_T, std::abs(T[i][0] - cf.back()));
        // At a period end the distance to the periodic orbit is (T0 - T_L) exp(-t / tau).
        const double periods = t / r.pwm[i].period_s;
        if (periods == std::floor(periods)) {
          const double TL = dc::pwm_cycle(th[i], r.pwm[i]).end_of_period_K;
          const double pred = TL + (T0[i] - TL) * std::exp(-t / th[i].time_constant_s());
          worst_cycle = std::max(worst_cycle, std::abs(T[i][0] - pred));
        }
      }
      T_cf_rows.push_back(cf);
    };
    const long every = std::lround(0.125 * slow / dt);
    const dc::QuasiStaticRun run = dc::quasi_static_run(
        m, o,
        [&m](double t) { return t > 0.0 ? rod::Loads::at_time(m, t) : rod::Loads::from_model(m); },
        steps, every, each_step);
    const std::string tag = fmt::format("PWM three-TCA rod, drive slowed {}x", slow);
    if (!g.check(tag + ": every step converges", run.converged,
                 run.converged ? fmt::format("{} steps", steps) : run.message, "all converge")) {
      return;
    }
    for (std::size_t k = 0; k < run.t_s.size(); ++k) {
      const long step = std::lround(run.t_s[k] / dt);
      csv << fmt::format("{},{:.6f}", slow, run.t_s[k]);
      for (int i = 0; i < n; ++i) {
        const double cf = step == 0 ? T0[i] : T_cf_rows[step - 1][i];
        csv << fmt::format(",{:.9f},{:.9f},nan", units::K_to_degC(run.temperature_K[k][i]),
                           units::K_to_degC(cf));
      }
      const Eigen::Vector3d &p = run.tip_m[k], &ps = run.static_tip_m[k];
      csv << fmt::format(",{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.4e}\n", p.x(), p.y(), p.z(),
                         ps.x(), ps.y(), ps.z(), run.gap_m[k]);
    }
    const double plane = out_of_plane_ratio(run.tip_m);
    fmt::print(
        "  slowed {}x: worst |T - closed form| {:.2e} K, periodic-orbit check {:.2e} K, tip "
        "travel {:.3e} m, worst gap to static {:.3e} m ({:.3e} of travel), out-of-plane {:.3f}\n",
        slow, worst_T, worst_cycle, run.travel_m, run.worst_gap_m, run.worst_gap_m / run.travel_m,
        plane);
    g.at_most(tag + ": worst |T - closed-form PWM response| [K]", worst_T, kThermalRoundOff_K);
    g.at_most(tag + ": worst |T - periodic orbit + exp(-t/tau) decay| at period ends [K]",
              worst_cycle, kThermalRoundOff_K);
    // Both bending directions take part: a path in one plane through the axis gives 0.
    g.within(tag + ": tip path out of plane (minor / major spread across the axis)", plane, 0.05,
             1.0);
    rate.push_back(1.0 / slow);
    gap.push_back(run.worst_gap_m / run.travel_m);
  }
  std::ofstream orders(out + "/pwm_quasi_static_order.csv");
  orders << "study,h,error,observed_order\n";
  // A viscous lag behind a drive of rate 1 / s: gap ~ (relaxation time) x (static tip speed).
  gate_orders(g,
              "PWM three-TCA rod: gap to the static tip at the instantaneous temperatures vs "
              "drive rate 1/s (order 1)",
              rate, gap, 1.0, 0.15, orders);
}

void heated_quasi_static(validation::Gates& g, const std::string& out, bool quick) {
  fmt::print("Step 8: heated quasi-static limit (circular manipulator, 25 -> 90 degC ramps)\n");
  nlohmann::json j = read_json("circular-manipulator.json");
  j["body"]["material"]["viscosity_Pa_s"] = 1400.0;  // first bending mode: damping ratio ~0.5
  const rod::RodModel m = rod::parse_scenario(j, scenario_dir().string());
  const std::vector<double> taus =
      quick ? std::vector<double>{1.0, 2.0} : std::vector<double>{1.0, 2.0, 4.0};
  std::ofstream csv(out + "/heated_ramp.csv");
  csv << "ramp_s,t_s,temperature_degC,tip_x_m,tip_z_m,static_tip_x_m,static_tip_z_m,gap_over_L\n";
  std::vector<double> rate, gap;
  for (const double tau : taus) {
    cosserat::DynamicsOptions o;
    o.dt_s = quick ? 1e-2 : 5e-3;  // the samples (every 20th of the ramp) end at tau
    o.steps = cosserat::recommended_steps(m, o);
    o.tolerance = 1e-12;
    const long steps = std::lround(tau / o.dt_s);
    const dc::QuasiStaticRun run = dc::quasi_static_run(
        m, o, dc::heating_ramp(m, units::degC_to_K(25.0), units::degC_to_K(90.0), tau), steps,
        steps / 20);
    if (!g.check(fmt::format("heated ramp {} s: every step converges", tau), run.converged,
                 run.converged ? "converged" : run.message, "all converge")) {
      return;
    }
    for (std::size_t k = 0; k < run.t_s.size(); ++k) {
      csv << fmt::format("{},{:.4f},{:.6f},{:.9e},{:.9e},{:.9e},{:.9e},{:.4e}\n", tau, run.t_s[k],
                         units::K_to_degC(run.temperature_K[k][0]), run.tip_m[k].x(),
                         run.tip_m[k].z(), run.static_tip_m[k].x(), run.static_tip_m[k].z(),
                         run.gap_m[k] / m.length_m);
    }
    fmt::print("  ramp {} s: largest gap {:.3e} L (tip travel {:.3e} L)\n", tau,
               run.worst_gap_m / m.length_m, run.travel_m / m.length_m);
    rate.push_back(1.0 / tau);
    gap.push_back(run.worst_gap_m / m.length_m);
  }
  std::ofstream orders(out + "/heated_ramp_order.csv");
  orders << "study,h,error,observed_order\n";
  gate_orders(g,
              "heated ramp: gap to the static solution at the instantaneous temperature vs "
              "ramp rate 1/tau (order 1)",
              rate, gap, 1.0, 0.15, orders);
}

}  // namespace tcasim::dynamics_validation
