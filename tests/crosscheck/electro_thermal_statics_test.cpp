// Statics of the dynamics extension's keys in both solvers: a tip mass is a tip weight m g,
// and an electric drive solves at its steady temperature (validation/scenarios/
// circular-manipulator-voltage.json).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/units.hpp"
#include "crosscheck/crosscheck.hpp"
#include "rod/scenario.hpp"

namespace tcasim::crosscheck {
namespace {

using json = nlohmann::json;

/// Two solves of the same discrete equations whose inputs differ by round-off (m g typed vs
/// computed, a temperature through degC and back): tip agreement relative to L.
constexpr double kSameProblem = 1e-10;
/// RK4 steps of the shooting solves and their Newton tolerance.
constexpr int kSteps = 64;
constexpr double kNewtonTolerance = 1e-12;

json read(const std::string& name) {
  const std::filesystem::path file =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios" / name;
  std::ifstream in(file);
  return json::parse(in);
}

void expect_same_tip(const rod::RodModel& a, const rod::RodModel& b) {
  const Run sa = solve_shooting_rk4(a, kSteps, kNewtonTolerance);
  const Run sb = solve_shooting_rk4(b, kSteps, kNewtonTolerance);
  ASSERT_TRUE(sa.converged && sb.converged) << sa.status << " / " << sb.status;
  const double L = a.length_m;
  EXPECT_LT((sa.result.tip_position_W_m - sb.result.tip_position_W_m).norm(), kSameProblem * L);
  const Run fa = solve_fe(a, FeSettings{});
  const Run fb = solve_fe(b, FeSettings{});
  ASSERT_TRUE(fa.converged && fb.converged) << fa.status << " / " << fb.status;
  EXPECT_LT((fa.result.tip_position_W_m - fb.result.tip_position_W_m).norm(), kSameProblem * L);
}

TEST(ElectroThermalStatics, TipMassIsATipWeightInBothSolvers) {
  json doc = read("circular-manipulator.json");
  const double m = 0.002;
  json with_mass = doc;
  with_mass["tip_mass_kg"] = m;
  json with_force = doc;
  with_force["tip_load"] = {{"force_N", {0.0, 0.0, m * -9.81}}};
  const rod::RodModel a = rod::parse_scenario(with_mass);
  const rod::RodModel b = rod::parse_scenario(with_force);
  expect_same_tip(a, b);
  // And the mass matters: 2 g is comparable to the body's own weight (2.1 g).
  const crosscheck::Run none =
      solve_shooting_rk4(rod::parse_scenario(doc), kSteps, kNewtonTolerance);
  const crosscheck::Run heavy = solve_shooting_rk4(a, kSteps, kNewtonTolerance);
  ASSERT_TRUE(none.converged && heavy.converged);
  EXPECT_GT((none.result.tip_position_W_m - heavy.result.tip_position_W_m).norm(),
            1e-3 * a.length_m);
}

TEST(ElectroThermalStatics, ElectricDriveSolvesAsTheTemperatureDriveAtTheSteadyTemperature) {
  const json doc = read("circular-manipulator-voltage.json");
  const rod::RodModel el = rod::parse_scenario(doc);
  const double T_K = el.actuators[0].drive.segments[0].temperature_K;
  // hA (T - T_amb) = v^2 / R0 with alpha_R = 0 in the shipped data set.
  const tca::ThermalParameters& p = el.tca_thermal.at("manipulator-tca");
  EXPECT_NEAR(T_K - p.ambient_K, 0.714 * 0.714 / (p.resistance_ohm * p.conductance_W_K), 1e-10);
  EXPECT_NEAR(units::K_to_degC(T_K), 90.0, 0.05);  // the documented design point
  json by_temperature = doc;
  by_temperature["actuators"][0]["drive"].erase("electric");
  by_temperature["actuators"][0]["drive"]["temperature_degC"] = units::K_to_degC(T_K);
  expect_same_tip(el, rod::parse_scenario(by_temperature));
}

}  // namespace
}  // namespace tcasim::crosscheck
