// Rod dynamics with TCA drives (cosserat/dynamics.hpp, docs/conventions.md "TCAs in rod
// dynamics"): a voltage step on the paper's circular manipulator. The temperature follows the
// closed-form step response of the lumped law; the rod settles to the static solve at the
// steady temperature.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "cosserat/shooting.hpp"
#include "rod/loads.hpp"
#include "rod/scenario.hpp"
#include "support/convergence.hpp"
#include "tca/thermal.hpp"
#include "validation/dynamics/tca_checks.hpp"

namespace tcasim::cosserat::testing {
namespace {

/// The exact thermal step of a law linear in T reproduces the closed form to round-off of
/// the temperature (about 1e-13 of 360 K per step, accumulated over the steps).
constexpr double kThermalRoundOff_K = 1e-9;
/// Voltage of the scenario: a steady 90 degC.
constexpr double kVoltage_V = 0.714;

/// validation/scenarios/circular-manipulator-voltage.json with the voltage switched on at
/// t = 0+ (ambient before), Kelvin-Voigt damping of 1000 Pa s (first bending mode damped at
/// about 0.3 of critical), the heat capacity divided by 20 (time constant 0.17 s instead of
/// 3.43 s, so the test runs in a fraction of a second) and a constant resistance (the closed
/// form holds).
rod::RodModel voltage_step_manipulator() {
  const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios";
  std::ifstream in(dir / "circular-manipulator-voltage.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["actuators"][0]["drive"]["electric"] = {
      {"voltage_V", {{"step", {{"t_s", 0.0}, {"before", 0.0}, {"after", kVoltage_V}}}}}};
  j["body"]["material"]["viscosity_Pa_s"] = 1000.0;
  rod::RodModel m = rod::parse_scenario(j, dir.string());
  tca::ThermalParameters& th = m.actuators[0].drive.electric[0].thermal;
  th.heat_capacity_J_K /= 20.0;
  th.resistance_temperature_coefficient_1_K = 0.0;
  return m;
}

TEST(RodDynamicsTca, VoltageStepFollowsTheThermalStepResponseAndSettlesToTheStaticSolve) {
  const rod::RodModel m = voltage_step_manipulator();
  const tca::ThermalParameters& th = m.actuators[0].drive.electric[0].thermal;
  const tca::SteadyTemperature ss =
      tca::steady_temperature(th, tca::ElectricInput::kVoltage, kVoltage_V);
  ASSERT_TRUE(ss.exists);
  const double tau = th.time_constant_s(), T_amb = th.ambient_K;
  // Static reference at the steady temperature (RK8, converged to round-off on this rod).
  Options so;
  so.integrator.method = ode::Method::kRk8;
  so.integrator.steps = 64;
  so.tolerance = 1e-12;
  ShootingSolver ref(m, so);
  Solution sol;
  const rod::Loads steady = rod::Loads::at_time(m, 1.0);
  ASSERT_NEAR(steady.actuators[0].segments[0].temperature_K, ss.temperature_K, 1e-9);
  ASSERT_TRUE(ref.solve(steady, sol).converged());
  const Eigen::Vector3d p_static = sol.tip_state.head<3>();

  DynamicsOptions o;
  o.dt_s = 5e-3;
  o.steps = recommended_steps(m, o);
  o.tolerance = 1e-12;
  RodDynamics d(m, o);
  ASSERT_TRUE(d.initialize(rod::Loads::from_model(m)).converged());
  EXPECT_NEAR(d.segment_temperatures_K()[0][0], T_amb, 1e-12);
  const Eigen::Vector3d p0 = d.tip_position_W_m();
  const int n_steps = 400;  // 2 s, 12 time constants
  double err_at[3] = {0, 0, 0};
  for (int k = 1; k <= n_steps; ++k) {
    const double t = k * o.dt_s;
    const DynamicsSummary s = d.step(rod::Loads::at_time(m, t));
    ASSERT_TRUE(s.converged()) << "t = " << t << ": " << s.message;
    // [Yip2017] lumped step response T(t) = T_amb + (T_ss - T_amb) (1 - exp(-t / tau)).
    const double T_cf = T_amb + (ss.temperature_K - T_amb) * (1.0 - std::exp(-t / tau));
    ASSERT_NEAR(d.segment_temperatures_K()[0][0], T_cf, kThermalRoundOff_K) << "t = " << t;
    const double err = (d.tip_position_W_m() - p_static).norm();
    if (k == 100) err_at[0] = err;
    if (k == 200) err_at[1] = err;
    if (k == n_steps) err_at[2] = err;
  }
  const double travel = (p_static - p0).norm();
  std::printf("tip travel %.4e m; |tip - static| at 0.5, 1, 2 s: %.3e %.3e %.3e m\n", travel,
              err_at[0], err_at[1], err_at[2]);
  // The gap to the static answer falls with time ...
  EXPECT_LT(err_at[1], 0.5 * err_at[0]);
  EXPECT_LT(err_at[2], 0.5 * err_at[1]);
  // ... down to the grid's spatial error against the RK8 reference (RK4 on the dynamics grid)
  // and the thermal remainder exp(-12) of the travel.
  EXPECT_LT(err_at[2], 1e-4 * travel);
  // The tension at the end is the static one.
  EXPECT_NEAR(d.tensions_N()[0], sol.tensions_N[0], 1e-4 * std::abs(sol.tensions_N[0]));
}

// Heated quasi-static limit: the circular manipulator (temperature drive; Kelvin-Voigt 1400 Pa s,
// first bending mode damped at about half of critical) heated 25 -> 90 degC by a smoothstep ramp
// over tau follows the static solution at its instantaneous temperature; the largest gap falls
// like 1 / tau (a viscous lag: relaxation time times the static tip's speed). Measured at
// dt = 10 ms: gaps 1.6e-2, 7.7e-3, 3.8e-3 L of a 0.59 L tip travel, orders 1.07, 1.03.
TEST(RodDynamicsTca, ASlowlyHeatedDampedManipulatorFollowsTheStaticSolutionAtItsTemperature) {
  const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios";
  std::ifstream in(dir / "circular-manipulator.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["body"]["material"]["viscosity_Pa_s"] = 1400.0;
  const rod::RodModel m = rod::parse_scenario(j, dir.string());
  std::vector<double> rate, gap;
  for (const double tau : {1.0, 2.0, 4.0}) {
    DynamicsOptions o;
    o.dt_s = 1e-2;
    o.steps = recommended_steps(m, o);
    o.tolerance = 1e-12;
    const long steps = std::lround(tau / o.dt_s);
    const dynamics_checks::QuasiStaticRun run = dynamics_checks::quasi_static_run(
        m, o, dynamics_checks::heating_ramp(m, 298.15, 363.15, tau), steps, steps / 20);
    ASSERT_TRUE(run.converged) << run.message;
    // At the ramp's end the heating rate is back to 0: so is most of the lag.
    EXPECT_LT(run.gap_m.back(), 0.2 * run.worst_gap_m);
    std::printf("ramp %.0f s: largest gap %.3e L of a %.3e L travel\n", tau,
                run.worst_gap_m / m.length_m, run.travel_m / m.length_m);
    rate.push_back(1.0 / tau);
    gap.push_back(run.worst_gap_m / m.length_m);
  }
  test_support::ExpectOrderInBracket(rate, gap, 1.0, 0.15);
}

}  // namespace
}  // namespace tcasim::cosserat::testing
