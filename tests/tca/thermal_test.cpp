// Lumped electro-thermal TCA model (tca/thermal.hpp): the closed-form step response, steady
// temperatures, runaway, derivatives, and the orders of the time steppers against a fine
// RK4 reference for a temperature-dependent resistance.
#include "tca/thermal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "support/convergence.hpp"

namespace tcasim::tca {
namespace {

/// Closed forms evaluated in double precision (a few operations on O(100 K) values).
constexpr double kRoundOff = 1e-12;
/// Central differences with step 1e-4 K on smooth laws: truncation ~1e-8 relative.
constexpr double kFiniteDifference = 1e-7;
/// Half-width of the two-sided order bracket of the time steppers.
constexpr double kOrderTolerance = 0.15;

/// A TCA of tau = C / hA = 3.43 s (the corrected silver-nylon data set, l = 0.175 m).
ThermalParameters silver_nylon(double alpha_R = 0.0) {
  ThermalParameters p;
  p.heat_capacity_J_K = 0.0546;
  p.conductance_W_K = 0.0159;
  p.ambient_K = 298.15;
  p.resistance_ohm = 8.0;
  p.resistance_temperature_coefficient_1_K = alpha_R;
  return p;
}

/// RK4 with n steps of dT/dt = f(T, u) over [0, t_end] for a constant drive u.
double rk4(const ThermalParameters& p, ElectricInput in, double u, double T0, double t_end, int n) {
  const double h = t_end / n;
  double T = T0;
  const auto f = [&](double x) { return heating_rate(p, in, u, x).dT_dt_K_s; };
  for (int i = 0; i < n; ++i) {
    const double k1 = f(T), k2 = f(T + 0.5 * h * k1), k3 = f(T + 0.5 * h * k2), k4 = f(T + h * k3);
    T += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return T;
}

double march(const ThermalParameters& p, ElectricInput in, double u, double T0, double t_end, int n,
             ThermalScheme scheme) {
  double T = T0;
  for (int i = 0; i < n; ++i) {
    const ThermalStep s = thermal_step(p, in, u, u, T, t_end / n, scheme);
    EXPECT_TRUE(s.converged) << s.message;
    T = s.temperature_K;
  }
  return T;
}

TEST(Thermal, ExactStepReproducesTheClosedFormStepResponse) {
  // [notes] T(t) = T_amb + (P / hA) (1 - exp(-t hA / C)) for constant P.
  const ThermalParameters p = silver_nylon();
  const double P = 0.8;
  for (double t : {0.1, 1.0, 3.43, 10.0, 40.0}) {
    const double exact =
        p.ambient_K +
        P / p.conductance_W_K * (1.0 - std::exp(-t * p.conductance_W_K / p.heat_capacity_J_K));
    EXPECT_NEAR(march(p, ElectricInput::kPower, P, p.ambient_K, t, 1, ThermalScheme::kExact), exact,
                kRoundOff * exact);
    // Many exact steps compose to the same answer.
    EXPECT_NEAR(march(p, ElectricInput::kPower, P, p.ambient_K, t, 37, ThermalScheme::kExact),
                exact, kRoundOff * exact);
  }
  // Voltage drive with alpha_R = 0 is a constant power v^2 / R0.
  const double v = 2.0;
  const double P_v = v * v / p.resistance_ohm;
  const double exact = p.ambient_K + P_v / p.conductance_W_K * (1.0 - std::exp(-1.0));
  EXPECT_NEAR(march(p, ElectricInput::kVoltage, v, p.ambient_K, p.time_constant_s(), 1,
                    ThermalScheme::kExact),
              exact, kRoundOff * exact);
}

TEST(Thermal, ExactStepOfACurrentDriveMatchesAFineReference) {
  const ThermalParameters p = silver_nylon(4e-3);  // R grows 0.4 %/K: linear law
  const double i = 0.2, t_end = 8.0;
  const double ref = rk4(p, ElectricInput::kCurrent, i, p.ambient_K, t_end, 20000);
  EXPECT_NEAR(march(p, ElectricInput::kCurrent, i, p.ambient_K, t_end, 3, ThermalScheme::kExact),
              ref, 1e-10 * ref);
}

TEST(Thermal, SteppersConvergeAtTheirOrderForATemperatureDependentResistance) {
  // Voltage drive with alpha_R != 0: P = v^2 / R(T) is nonlinear in T; the reference is RK4
  // with a step 1e-4 tau (error ~ 1e-16 tau^-4 h^4 relative: far below the errors measured).
  for (double alpha_R : {4e-3, -1.5e-3}) {
    SCOPED_TRACE(alpha_R);
    const ThermalParameters p = silver_nylon(alpha_R);
    const double v = 2.5, t_end = 5.0;
    const double ref = rk4(p, ElectricInput::kVoltage, v, p.ambient_K, t_end, 50000);
    std::vector<double> h, e_be, e_tr;
    for (int n : {10, 20, 40, 80}) {
      h.push_back(t_end / n);
      e_be.push_back(std::abs(march(p, ElectricInput::kVoltage, v, p.ambient_K, t_end, n,
                                    ThermalScheme::kBackwardEuler) -
                              ref));
      e_tr.push_back(std::abs(
          march(p, ElectricInput::kVoltage, v, p.ambient_K, t_end, n, ThermalScheme::kTrapezoidal) -
          ref));
    }
    std::cout << "backward Euler, alpha_R = " << alpha_R << "\n"
              << test_support::convergence_table(h, e_be) << "trapezoidal\n"
              << test_support::convergence_table(h, e_tr);
    test_support::ExpectOrderInBracket(h, e_be, 1.0, kOrderTolerance);
    test_support::ExpectOrderInBracket(h, e_tr, 2.0, kOrderTolerance);
  }
}

TEST(Thermal, ExactSchemeRefusesANonlinearVoltageLaw) {
  EXPECT_THROW((void)thermal_step(silver_nylon(1e-3), ElectricInput::kVoltage, 1, 1, 300, 0.1,
                                  ThermalScheme::kExact),
               DomainError);
}

TEST(Thermal, SteadyTemperatureZeroesTheRightHandSide) {
  for (double alpha_R : {0.0, 4e-3, -1.5e-3}) {
    const ThermalParameters p = silver_nylon(alpha_R);
    for (auto [in, u] : {std::pair{ElectricInput::kVoltage, 2.5},
                         {ElectricInput::kCurrent, 0.2},
                         {ElectricInput::kPower, 0.7},
                         {ElectricInput::kVoltage, -2.5}}) {
      SCOPED_TRACE(std::string(key_name(in)) + " alpha_R " + std::to_string(alpha_R));
      const SteadyTemperature s = steady_temperature(p, in, u);
      ASSERT_TRUE(s.exists) << s.reason;
      EXPECT_GT(s.temperature_K, p.ambient_K);
      const double P = joule_power(p, in, u, s.temperature_K).power_W;
      // Residual of the balance relative to the power: round-off only.
      EXPECT_NEAR(P - p.conductance_W_K * (s.temperature_K - p.ambient_K), 0.0, kRoundOff * P);
      // The implicit steppers settle to it.
      const double T = march(p, in, u, p.ambient_K, 60.0 * p.time_constant_s(), 60,
                             ThermalScheme::kBackwardEuler);
      EXPECT_NEAR(T, s.temperature_K, 1e-9 * s.temperature_K);
    }
  }
  const ThermalParameters p = silver_nylon(4e-3);
  EXPECT_EQ(steady_temperature(p, ElectricInput::kVoltage, 0.0).temperature_K, p.ambient_K);
}

TEST(Thermal, RunawayHasNoSteadyTemperatureAndSaysWhy) {
  const ThermalParameters p = silver_nylon(4e-3);
  // i^2 R0 alpha_R >= hA: i >= sqrt(hA / (R0 alpha_R)) = 0.7050 A.
  const double i_crit = std::sqrt(p.conductance_W_K / (p.resistance_ohm * 4e-3));
  EXPECT_TRUE(steady_temperature(p, ElectricInput::kCurrent, 0.99 * i_crit).exists);
  const SteadyTemperature s = steady_temperature(p, ElectricInput::kCurrent, 1.01 * i_crit);
  EXPECT_FALSE(s.exists);
  EXPECT_NE(s.reason.find("runaway"), std::string::npos);
  // Voltage drive with alpha_R < 0: none once 1 + 4 alpha_R v^2 / (R0 hA) < 0.
  const ThermalParameters n = silver_nylon(-1.5e-3);
  const double v_crit = std::sqrt(n.resistance_ohm * n.conductance_W_K / (4.0 * 1.5e-3));
  EXPECT_TRUE(steady_temperature(n, ElectricInput::kVoltage, 0.99 * v_crit).exists);
  const SteadyTemperature sv = steady_temperature(n, ElectricInput::kVoltage, 1.01 * v_crit);
  EXPECT_FALSE(sv.exists);
  EXPECT_NE(sv.reason.find("runaway"), std::string::npos);
  // Alpha_R > 0 voltage drive always has one (the power falls as R rises).
  EXPECT_TRUE(steady_temperature(p, ElectricInput::kVoltage, 100.0).exists);
}

TEST(Thermal, AnalyticDerivativesMatchFiniteDifferences) {
  const double hT = 1e-4;
  for (double alpha_R : {4e-3, -1.5e-3}) {
    const ThermalParameters p = silver_nylon(alpha_R);
    for (auto [in, u] : {std::pair{ElectricInput::kVoltage, 2.5},
                         {ElectricInput::kCurrent, 0.2},
                         {ElectricInput::kPower, 0.7}}) {
      const double T = 340.0;
      const double fd =
          (heating_rate(p, in, u, T + hT).dT_dt_K_s - heating_rate(p, in, u, T - hT).dT_dt_K_s) /
          (2 * hT);
      const double an = heating_rate(p, in, u, T).d_dT_1_s;
      EXPECT_NEAR(an, fd, kFiniteDifference * std::abs(an)) << key_name(in);
      for (ThermalScheme sc : {ThermalScheme::kBackwardEuler, ThermalScheme::kTrapezoidal}) {
        const double dt = 0.7;
        const auto step = [&](double T0) {
          return thermal_step(p, in, u, u, T0, dt, sc).temperature_K;
        };
        const double fd1 = (step(T + hT) - step(T - hT)) / (2 * hT);
        const ThermalStep s = thermal_step(p, in, u, u, T, dt, sc);
        EXPECT_NEAR(s.dT1_dT0, fd1, kFiniteDifference) << key_name(in);
      }
    }
  }
}

TEST(Thermal, ASegmentTakesItsFractionOfCapacityConductanceAndResistance) {
  const ThermalParameters p = silver_nylon(4e-3);
  const ThermalParameters s = p.fraction(0.25);
  EXPECT_EQ(s.heat_capacity_J_K, 0.25 * p.heat_capacity_J_K);
  EXPECT_EQ(s.conductance_W_K, 0.25 * p.conductance_W_K);
  EXPECT_EQ(s.resistance_ohm, 0.25 * p.resistance_ohm);
  EXPECT_EQ(s.time_constant_s(), p.time_constant_s());
  // The same current heats a segment like the whole TCA; a voltage v across a quarter
  // heats it like 4 v across the whole.
  EXPECT_NEAR(steady_temperature(s, ElectricInput::kCurrent, 0.3).temperature_K,
              steady_temperature(p, ElectricInput::kCurrent, 0.3).temperature_K, kRoundOff * 400);
  EXPECT_NEAR(steady_temperature(s, ElectricInput::kVoltage, 0.6).temperature_K,
              steady_temperature(p, ElectricInput::kVoltage, 2.4).temperature_K, kRoundOff * 400);
}

TEST(Thermal, NonPositiveResistanceIsADomainError) {
  const ThermalParameters p = silver_nylon(-5e-3);  // R = 0 at T_amb + 200 K
  EXPECT_THROW((void)p.resistance_ohm_at(p.ambient_K + 200.0), DomainError);
  EXPECT_THROW((void)joule_power(p, ElectricInput::kVoltage, 1.0, p.ambient_K + 250.0),
               DomainError);
  // A power drive does not use R.
  EXPECT_NO_THROW((void)joule_power(p, ElectricInput::kPower, 1.0, p.ambient_K + 250.0));
}

TEST(Thermal, ImplicitStepReportsASingularRunawayStep) {
  // Current drive beyond runaway: BE with dt = 1 / k' makes 1 - dt f' = 0.
  const ThermalParameters p = silver_nylon(4e-3);
  const double i = 1.0;
  const double k = (i * i * p.resistance_ohm * 4e-3 - p.conductance_W_K) / p.heat_capacity_J_K;
  ASSERT_GT(k, 0.0);
  const ThermalStep s = thermal_step(p, ElectricInput::kCurrent, i, i, p.ambient_K, 1.0 / k,
                                     ThermalScheme::kBackwardEuler);
  EXPECT_FALSE(s.converged);
  EXPECT_FALSE(s.message.empty());
}

}  // namespace
}  // namespace tcasim::tca
