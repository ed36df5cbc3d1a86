// FE dynamics with TCA drives (beam_fe/dynamics.hpp, docs/conventions.md "Beam FE dynamics"):
// the exact step Jacobian with the TCA rows and columns against finite differences, static
// states that stay at rest (a TCA at constant temperature, segments, closed coils), a voltage
// step that follows the thermal step response and settles to the FE static solve at the steady
// temperature, the same step against the shooting dynamics, the trajectory's temperature
// columns, and convergence at the dynamic cross-check's tolerance.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/dynamics.hpp"
#include "common/units.hpp"
#include "cosserat/dynamics.hpp"
#include "dynamics_tca_models.hpp"
#include "method/dynamics.hpp"
#include "rod/loads.hpp"
#include "support/rod_models.hpp"
#include "tca/thermal.hpp"

namespace tcasim::beam_fe::testing {
namespace {

/// The exact thermal step of a law linear in T reproduces the closed form to round-off of the
/// temperature (about 1e-13 of 360 K per step, accumulated over the steps).
constexpr double kThermalRoundOff_K = 1e-9;
/// A static state under unchanged loads is a fixed point of the step: the tip moves by the
/// Newton tolerance's share only.
constexpr double kRestDrift = 1e-11;

/// Max |J - J_fd| / max |J| of the step Jacobian at unknowns x near the motion's.
double jacobian_error(BeamDynamics& d, const rod::Loads& loads) {
  const int nv = static_cast<int>(d.velocities().size());
  const std::vector<double> T = d.tensions_N();
  std::vector<int> tca;
  for (std::size_t i = 0; i < d.segment_temperatures_K().size(); ++i)
    if (!d.segment_temperatures_K()[i].empty()) tca.push_back(static_cast<int>(i));
  const int n = nv + static_cast<int>(tca.size());
  Eigen::VectorXd x(n);
  x.head(nv) = d.velocities();
  for (int i = 0; i < nv; ++i) x[i] += 0.3 * std::sin(1.0 + 7.0 * i) * (i % 6 < 3 ? 0.005 : 0.5);
  for (std::size_t j = 0; j < tca.size(); ++j) x[nv + static_cast<int>(j)] = 1.02 * T[tca[j]];
  Eigen::SparseMatrix<double> J;
  d.step_residual(loads, x, &J);
  const Eigen::MatrixXd Jd(J);
  EXPECT_EQ(Jd.rows(), n);
  Eigen::MatrixXd Jfd(n, n);
  for (int j = 0; j < n; ++j) {
    const double eps = j >= nv ? 1e-6 * std::abs(x[j]) : j % 6 < 3 ? 1e-6 : 1e-5;
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += eps;
    xm[j] -= eps;
    Jfd.col(j) = (d.step_residual(loads, xp) - d.step_residual(loads, xm)) / (2.0 * eps);
  }
  const double err = (Jd - Jfd).cwiseAbs().maxCoeff();
  // The TCA block (rows and columns) must be in the comparison and not zero.
  EXPECT_GT(Jd.bottomRows(n - nv).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(Jd.rightCols(n - nv).cwiseAbs().maxCoeff(), 0.0);
  std::printf("max |J - J_fd| / max |J| = %.2e (%d unknowns, %d TCA)\n",
              err / Jd.cwiseAbs().maxCoeff(), n, n - nv);
  return err / Jd.cwiseAbs().maxCoeff();
}

// The step Jacobian with the TCA rows (T - F_tca(delta(q), temperatures)) and the string
// columns (c dl/dq): an electric TCA with R(T) in the middle of its heating, a tension string,
// Kelvin-Voigt damping and a tip mass; and a segmented TCA (two segments, count 2).
TEST(BeamDynamicsTca, StepJacobianWithTcaRowsMatchesFiniteDifferences) {
  for (const int order : {1, 2}) {
    SCOPED_TRACE(order == 1 ? "linear" : "quadratic");
    rod::RodModel m = voltage_step_manipulator(1000.0, true);
    test_support::add_tension_string(m, "tendon", -0.002, 0.001, 0.01);
    DynamicsOptions o;
    o.elements = 4;
    o.order = order;
    o.dt_s = 5e-3;
    o.rho_inf = 0.7;
    o.tip_mass_kg = 2e-4;
    BeamDynamics d(m, o);
    ASSERT_TRUE(d.initialize(rod::Loads::from_model(m)).converged());
    for (int k = 1; k <= 4; ++k)
      ASSERT_TRUE(d.step(rod::Loads::at_time(m, k * o.dt_s)).converged());
    EXPECT_GT(d.segment_temperatures_K()[0][0], units::degC_to_K(26.0));  // heating
    EXPECT_LT(jacobian_error(d, rod::Loads::at_time(m, 5 * o.dt_s)), 1e-6);
  }
  {
    SCOPED_TRACE("segmented TCA");
    const rod::RodModel m = scenario_model(scenario_json("segmented-tca"));
    DynamicsOptions o;
    o.elements = 4;
    o.dt_s = 5e-3;
    o.viscosity_Pa_s = 500.0;
    BeamDynamics d(m, o);
    ASSERT_TRUE(d.initialize(rod::Loads::from_model(m)).converged());
    rod::Loads hot = rod::Loads::from_model(m);
    hot.set_segment_temperatures_K(0, {units::degC_to_K(130.0), units::degC_to_K(60.0)});
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(d.step(hot).converged());
    EXPECT_LT(jacobian_error(d, hot), 1e-6);
  }
}

/// Steps `d` `steps` times under `loads`; the largest tip displacement from the start [m].
double rest_drift(BeamDynamics& d, const rod::Loads& loads, int steps) {
  const Eigen::Vector3d p0 = d.tip_position_W_m();
  double drift = 0.0;
  for (int k = 0; k < steps; ++k) {
    const BeamDynamicsSummary s = d.step(loads);
    EXPECT_TRUE(s.converged()) << s.message;
    drift = std::max(drift, (d.tip_position_W_m() - p0).norm());
  }
  return drift;
}

// A static state with TCAs at constant temperature is a fixed point of the time step: the
// circular manipulator at 90 degC, the segmented TCA (120 / 40 degC) and a TCA whose coils are
// held closed by a tendon (coil contact), with and without damping.
TEST(BeamDynamicsTca, StaticStatesWithTcasAtConstantTemperatureStayAtRest) {
  rod::RodModel strut = test_support::strut_rod(0.5, units::degC_to_K(25.0));
  strut.material.density_profile =
      rod::Profile(1040.0);  // the square manipulator's body, with mass
  const std::vector<std::pair<std::string, rod::RodModel>> cases = {
      {"circular manipulator at 90 degC", scenario_model(scenario_json("circular-manipulator"))},
      {"segmented TCA", scenario_model(scenario_json("segmented-tca"))},
      {"closed coils", strut}};
  for (const auto& [name, m] : cases) {
    for (const double eta : {0.0, 1000.0}) {
      SCOPED_TRACE(::testing::Message() << name << ", eta " << eta);
      DynamicsOptions o;
      o.elements = 8;
      o.dt_s = 2e-3;
      o.viscosity_Pa_s = eta;
      BeamDynamics d(m, o);
      const rod::Loads loads = rod::Loads::from_model(m);
      ASSERT_TRUE(d.initialize(loads).converged());
      const std::vector<double> T0 = d.tensions_N();
      EXPECT_LT(rest_drift(d, loads, 10), kRestDrift * m.length_m);
      EXPECT_LT(d.kinetic_energy_J(), 1e-24);  // elastic energy of the bending: ~1e-5 J
      for (std::size_t i = 0; i < T0.size(); ++i)
        EXPECT_NEAR(d.tensions_N()[i], T0[i], 1e-9 * std::abs(T0[i]) + 1e-12);
    }
  }
  // The strut's coils stay closed: zero elongation, tension below the blocked force.
  DynamicsOptions o;
  o.elements = 8;
  BeamDynamics d(strut, o);
  ASSERT_TRUE(d.initialize(rod::Loads::from_model(strut)).converged());
  EXPECT_LT(std::abs(d.elongations_m()[0]), 1e-10 * strut.length_m);
}

// A voltage step on the circular manipulator (time constant shortened to 0.17 s, damped): the
// thermal state follows the closed-form step response, the rod settles to the FE static solve at
// the steady temperature.
TEST(BeamDynamicsTca, VoltageStepFollowsTheThermalResponseAndSettlesToTheStaticSolve) {
  const rod::RodModel m = voltage_step_manipulator(1000.0);
  const tca::ThermalParameters& th = m.actuators[0].drive.electric[0].thermal;
  const tca::SteadyTemperature ss =
      tca::steady_temperature(th, tca::ElectricInput::kVoltage, kVoltage_V);
  ASSERT_TRUE(ss.exists);
  const double tau = th.time_constant_s(), T_amb = th.ambient_K;
  DynamicsOptions o;
  o.elements = 8;
  o.dt_s = 5e-3;
  // The static FE solve on the same mesh at the steady temperature.
  Options so;
  so.elements = o.elements;
  so.tolerance_rel = 1e-12;
  State st;
  const Summary sum = solve(m, rod::Loads::at_time(m, 1.0), so, st);
  ASSERT_TRUE(sum.converged()) << sum.message;

  BeamDynamics d(m, o);
  ASSERT_TRUE(d.initialize(rod::Loads::from_model(m)).converged());
  EXPECT_NEAR(d.segment_temperatures_K()[0][0], T_amb, 1e-12);
  const Eigen::Vector3d p0 = d.tip_position_W_m();
  const int n_steps = 400;  // 2 s, 12 time constants
  double err_at[3] = {0, 0, 0};
  for (int k = 1; k <= n_steps; ++k) {
    const double t = k * o.dt_s;
    const BeamDynamicsSummary s = d.step(rod::Loads::at_time(m, t));
    ASSERT_TRUE(s.converged()) << "t = " << t << ": " << s.message;
    // [Yip2017] lumped step response T(t) = T_amb + (T_ss - T_amb) (1 - exp(-t / tau)).
    const double T_cf = T_amb + (ss.temperature_K - T_amb) * (1.0 - std::exp(-t / tau));
    ASSERT_NEAR(d.segment_temperatures_K()[0][0], T_cf, kThermalRoundOff_K) << "t = " << t;
    const double err = (d.tip_position_W_m() - st.p_W_m.back()).norm();
    if (k == 100) err_at[0] = err;
    if (k == 200) err_at[1] = err;
    if (k == n_steps) err_at[2] = err;
  }
  const double travel = (st.p_W_m.back() - p0).norm();
  std::printf("tip travel %.4e m; |tip - FE static| at 0.5, 1, 2 s: %.3e %.3e %.3e m\n", travel,
              err_at[0], err_at[1], err_at[2]);
  EXPECT_LT(err_at[1], 0.5 * err_at[0]);
  EXPECT_LT(err_at[2], 0.5 * err_at[1]);
  // The thermal remainder exp(-12) of the travel, and the bending mode's decay.
  EXPECT_LT(err_at[2], 1e-4 * travel);
  EXPECT_NEAR(d.tensions_N()[0], st.tensions_N[0], 1e-4 * std::abs(st.tensions_N[0]));
}

// The trajectory file of a TCA: one temperature column per TCA (per segment of a segmented
// one), written in degC from the drive's temperatures.
TEST(BeamDynamicsTca, TrajectoryCarriesTheTemperatures) {
  {
    const rod::RodModel m = voltage_step_manipulator(1000.0);
    DynamicsOptions o;
    o.elements = 4;
    o.dt_s = 5e-3;
    method::DynamicSolver d(m, o);
    std::ostringstream os;
    const rod::TrajectoryOutcome s = method::write_trajectory(
        d, m, [&m](double t) { return rod::Loads::at_time(m, t); }, 2, 1, os);
    ASSERT_TRUE(s.ok) << s.message;
    std::istringstream is(os.str());
    std::string header, row0, row1, row2;
    std::getline(is, header);
    std::getline(is, row0);
    std::getline(is, row1);
    std::getline(is, row2);
    EXPECT_EQ(header,
              "t_s,tip_x_m,tip_y_m,tip_z_m,kinetic_energy_J,tca_tension_N,tca_elongation_m,"
              "tca_temperature_degC");
    const auto last = [](const std::string& r) { return std::stod(r.substr(r.rfind(',') + 1)); };
    EXPECT_NEAR(last(row0), 25.0, 1e-9);  // ambient before the step
    const double T1 = units::K_to_degC(d.row().temperatures_K[0][0]);
    EXPECT_GT(last(row1), 25.0);
    EXPECT_NEAR(last(row2), T1, 1e-8);
  }
  {
    const rod::RodModel m = scenario_model(scenario_json("segmented-tca"));
    DynamicsOptions o;
    o.elements = 4;
    method::DynamicSolver d(m, o);
    std::ostringstream os;
    ASSERT_TRUE(method::write_trajectory(
                    d, m, [&m](double) { return rod::Loads::from_model(m); }, 1, 1, os)
                    .ok);
    EXPECT_NE(os.str().find("u-tca_0_temperature_degC,u-tca_1_temperature_degC\n0,"),
              std::string::npos);
    EXPECT_NE(os.str().find(",120.000000000,40.000000000\n"), std::string::npos) << os.str();
  }
}

// At the dynamic cross-check's tolerance (1e-12, validation/dynamic_crosscheck) the voltage step
// on the damped manipulator (1000 Pa s, dt 1 ms: the viscous stiffness c_e B is 56 times the
// elastic one) converges in a few Newton iterations per step: the round-off floor of the rows
// counts the viscous stresses (Discretization::round_off_floor with c_e B). Without that share
// the first step stalled near 1e-10 for 30 iterations.
TEST(BeamDynamicsTca, VoltageStepConvergesAtTheCrossCheckTolerance) {
  const rod::RodModel m = scenario_model(scenario_json("dynamic/manipulator-voltage-step"));
  /// Iterations per step seen: 2-3 (chord steps included); a stall runs to max_iterations.
  constexpr int kMaxIterationsPerStep = 8;
  for (const double dt : {1e-3, 2.5e-4}) {
    SCOPED_TRACE(dt);
    DynamicsOptions o;
    o.elements = 32;
    o.dt_s = dt;
    o.tolerance = 1e-12;
    BeamDynamics d(m, o);
    ASSERT_TRUE(d.initialize(rod::Loads::from_model(m)).converged());
    int most = 0;
    for (int k = 1; k <= 20; ++k) {
      const BeamDynamicsSummary s = d.step(rod::Loads::at_time(m, k * dt));
      ASSERT_TRUE(s.converged()) << "t = " << k * dt << ": " << s.message;
      most = std::max(most, s.iterations);
    }
    EXPECT_LE(most, kMaxIterationsPerStep);
    EXPECT_GT(d.segment_temperatures_K()[0][0], units::degC_to_K(25.0));  // heating
  }
}

// undo_step with an electric TCA: the TCA tension, the thermal state and the segment
// temperatures return bit for bit, and the repeated step, now at half the size, heats less.
TEST(BeamDynamicsTca, UndoStepRestoresTensionAndThermalState) {
  const rod::RodModel m = voltage_step_manipulator(1000.0, true);
  DynamicsOptions o;
  o.elements = 4;
  o.dt_s = 5e-3;
  BeamDynamics d(m, o);
  ASSERT_TRUE(d.initialize(rod::Loads::from_model(m)).converged());
  for (int k = 1; k <= 3; ++k) ASSERT_TRUE(d.step(rod::Loads::at_time(m, k * o.dt_s)).converged());
  const std::vector<double> T0 = d.tensions_N();
  const std::vector<std::vector<double>> temp0 = d.segment_temperatures_K();
  const double t0 = d.time_s();
  ASSERT_TRUE(d.step(rod::Loads::at_time(m, t0 + o.dt_s)).converged());
  const double heated_full = d.segment_temperatures_K()[0][0] - temp0[0][0];
  EXPECT_GT(heated_full, 0.0);
  EXPECT_NE(d.tensions_N(), T0);
  d.undo_step();
  EXPECT_EQ(d.tensions_N(), T0);
  EXPECT_EQ(d.segment_temperatures_K(), temp0);
  EXPECT_EQ(d.time_s(), t0);
  d.set_time_step(0.5 * o.dt_s);
  ASSERT_TRUE(d.step(rod::Loads::at_time(m, t0 + 0.5 * o.dt_s)).converged());
  const double heated_half = d.segment_temperatures_K()[0][0] - temp0[0][0];
  EXPECT_GT(heated_half, 0.4 * heated_full);
  EXPECT_LT(heated_half, 0.6 * heated_full);
}

}  // namespace
}  // namespace tcasim::beam_fe::testing
