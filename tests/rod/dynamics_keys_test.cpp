// Scenario keys of the dynamics extension that statics reads (docs/scenario-format.md "Time
// profiles", "Electro-thermal TCAs", `tip_mass_kg`): profiles evaluated at t = 0 by a static
// solve and at any t by Loads::at_time, TCA thermal blocks and shipped thermal data sets,
// electric drives at their steady temperature, and a named error for every rule.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/loads.hpp"
#include "rod/scenario.hpp"
#include "support/input_error.hpp"

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

/// Closed forms evaluated in double precision.
constexpr double kRoundOff = 1e-12;

/// The paper's circular manipulator with a thermal block on its TCA.
json base() {
  return json::parse(R"({
  "schema": "tcasim.scenario/1",
  "name": "dynamics-keys",
  "body": {
    "length_m": 0.040,
    "section": {"shape": "circle", "diameter_m": 0.008},
    "material": {"youngs_modulus_Pa": 37.8e3, "poisson_ratio": 0.5, "density_kg_m3": 1040}
  },
  "gravity_m_s2": [0, 0, -9.81],
  "tcas": {
    "tca": {
      "kind": "extension", "coiled_length_m": 0.040, "pitch_angle_deg": 15,
      "outer_diameter_m": 0.0017, "twist_turns": 76.4, "material": "silver-nylon-sun2022",
      "thermal": {"heat_capacity_J_K": 0.05, "conductance_W_K": 0.0125, "ambient_degC": 25,
                  "resistance_ohm": 0.8, "resistance_temperature_coefficient_1_K": 0.002,
                  "source": "test values"}
    }
  },
  "actuators": [
    {"name": "a", "routing": {"type": "straight", "offset_m": [0.003, 0.0]},
     "drive": {"type": "tca", "tca": "tca", "temperature_degC": 90}},
    {"name": "b", "routing": {"type": "straight", "offset_m": [-0.003, 0.0]},
     "drive": {"type": "tension", "tension_N": 0.01}}
  ]
})");
}

void expect_rejected(const json& doc, const std::string& key, const std::string& rule_part) {
  test_support::expect_input_error([&] { (void)parse_scenario(doc); }, key, rule_part);
}

TEST(DynamicsKeys, ProfilesAreEvaluatedAtZeroForStaticsAndAtAnyTimeByAtTime) {
  json doc = base();
  doc["actuators"][0]["drive"]["temperature_degC"] = {{"t_s", {0.0, 10.0}},
                                                      {"values", {30.0, 130.0}}};
  doc["actuators"][1]["drive"]["tension_N"] = {
      {"step", {{"t_s", 0.0}, {"before", 0.0}, {"after", 0.02}}}};
  doc["tip_load"] = {
      {"force_N",
       {0.0, {{"sine", {{"mean", 1e-3}, {"amplitude", 5e-4}, {"frequency_Hz", 0.25}}}}, 0.0}},
      {"moment_Nm",
       {{{"pwm", {{"period_s", 2.0}, {"duty", 0.5}, {"high", 1e-5}, {"low", 0.0}}}}, 0.0, 0.0}}};
  const RodModel m = parse_scenario(doc);
  const Loads l0 = Loads::from_model(m);
  EXPECT_EQ(l0.actuators[0].segments[0].temperature_K, units::degC_to_K(30.0));
  EXPECT_EQ(l0.actuators[1].tension_N, 0.0);  // step at t0 = 0: `before`
  EXPECT_EQ(l0.tip_force_W_N.y(), 1e-3);
  EXPECT_EQ(l0.tip_moment_W_Nm.x(), 0.0);  // PWM at t = 0: `low`
  const Loads same = Loads::at_time(m, 0.0);
  EXPECT_EQ(same.actuators[0].segments[0].temperature_K, l0.actuators[0].segments[0].temperature_K);
  EXPECT_EQ(same.tip_force_W_N, l0.tip_force_W_N);
  const Loads l1 = Loads::at_time(m, 1.0);
  EXPECT_NEAR(l1.actuators[0].segments[0].temperature_K, units::degC_to_K(40.0), kRoundOff * 400);
  EXPECT_EQ(l1.actuators[1].tension_N, 0.02);
  EXPECT_NEAR(l1.tip_force_W_N.y(), 1.5e-3, kRoundOff);
  EXPECT_EQ(l1.tip_moment_W_Nm.x(), 1e-5);
  EXPECT_EQ(Loads::at_time(m, 1.5).tip_moment_W_Nm.x(), 0.0);
}

TEST(DynamicsKeys, ConstantValuesGiveTheSameModelAsPlainNumbers) {
  const RodModel plain = parse_scenario(base());
  json doc = base();
  doc["actuators"][0]["drive"]["temperature_degC"] = {{"t_s", {0.0}}, {"values", {90.0}}};
  const RodModel table = parse_scenario(doc);
  EXPECT_EQ(plain.actuators[0].drive.segments[0].temperature_K,
            table.actuators[0].drive.segments[0].temperature_K);
  EXPECT_EQ(plain.actuators[0].drive.segments[0].temperature_K, units::degC_to_K(90.0));
  EXPECT_EQ(plain.tip_mass_kg, 0.0);
}

TEST(DynamicsKeys, TemperatureProfilesStayInsideTheMaterialRange) {
  json doc = base();
  doc["actuators"][0]["drive"]["temperature_degC"] = {
      {"sine", {{"mean", 100.0}, {"amplitude", 70.0}, {"frequency_Hz", 1.0}}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC", "outside the valid range");
  doc["actuators"][0]["drive"]["temperature_degC"] = {
      {"pwm", {{"period_s", 1.0}, {"duty", 0.3}, {"high", 150.0}, {"low", 25.0}}}};
  EXPECT_NO_THROW((void)parse_scenario(doc));
}

TEST(DynamicsKeys, MalformedProfilesNameTheirKeyPath) {
  json doc = base();
  auto& t = doc["actuators"][0]["drive"]["temperature_degC"];
  t = {{"t_s", {0.0, 2.0, 1.0}}, {"values", {30, 40, 50}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC.t_s[2]", "strictly increasing");
  t = {{"t_s", {0.0, 2.0}}, {"values", {30}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC.values", "as many entries");
  t = {{"pwm", {{"period_s", -1.0}, {"duty", 0.5}, {"high", 30}, {"low", 30}}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC.pwm.period_s", "positive");
  t = {{"pwm", {{"period_s", 1.0}, {"duty", 2}, {"high", 30}, {"low", 30}}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC.pwm.duty", "[0, 1]");
  t = {{"pwm", {{"period_s", 1.0}, {"high", 30}, {"low", 30}}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC.pwm.duty", "required");
  t = {{"sine", {{"mean", 50}, {"amplitude", 1}, {"frequency_Hz", -2}}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC.sine.frequency_Hz", ">= 0");
  t = {{"ramp", {{"t_s", 1}}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC.ramp", "not an allowed key");
  t = {{"step", {{"t_s", 0}, {"before", 30}, {"after", 40}}},
       {"sine", {{"mean", 50}, {"amplitude", 1}, {"frequency_Hz", 1}}}};
  expect_rejected(doc, "actuators[0].drive.temperature_degC", "exactly one");
  t = "hot";
  expect_rejected(doc, "actuators[0].drive.temperature_degC", "a number or a time profile");
  doc = base();
  doc["tip_load"] = {{"force_N", {0, 0}}};
  expect_rejected(doc, "tip_load.force_N", "array of 3");
  doc["tip_load"] = json::parse(R"({"force_N": [0, {"step": {"t_s": 0, "before": 0}}, 0]})");
  expect_rejected(doc, "tip_load.force_N[1].step.after", "required");
}

TEST(DynamicsKeys, TipMassIsReadAndMustNotBeNegative) {
  json doc = base();
  doc["tip_mass_kg"] = 0.002;
  const RodModel m = parse_scenario(doc);
  EXPECT_EQ(m.tip_mass_kg, 0.002);
  const Loads l = Loads::from_model(m);
  const Eigen::Vector3d F = tip_force_with_weight_W_N(m, l);
  EXPECT_NEAR(F.z(), -0.002 * 9.81, kRoundOff);
  doc["tip_mass_kg"] = -1e-3;
  expect_rejected(doc, "tip_mass_kg", ">= 0");
}

TEST(DynamicsKeys, ElectricDriveSolvesAtItsSteadyTemperature) {
  json doc = base();
  auto& d = doc["actuators"][0]["drive"];
  d.erase("temperature_degC");
  d["electric"] = {{"voltage_V", 0.8}};
  const RodModel m = parse_scenario(doc);
  const Drive& drive = m.actuators[0].drive;
  ASSERT_TRUE(drive.is_electric());
  // hA x (1 + alpha_R x) = v^2 / R0 -> x = 2 q / (1 + sqrt(1 + 4 alpha_R q)), q = v^2 / (R0 hA)
  const double q = 0.64 / (0.8 * 0.0125);
  const double x = 2.0 * q / (1.0 + std::sqrt(1.0 + 4.0 * 0.002 * q));
  EXPECT_NEAR(drive.segments[0].temperature_K, units::degC_to_K(25.0) + x, kRoundOff * 400);
  EXPECT_EQ(drive.electric[0].input, tca::ElectricInput::kVoltage);
  EXPECT_EQ(drive.electric[0].thermal.heat_capacity_J_K, 0.05);
  // A step from 0 V: ambient at t = 0, the steady temperature of 0.8 V afterwards.
  d["electric"] = {{"voltage_V", {{"step", {{"t_s", 0}, {"before", 0}, {"after", 0.8}}}}}};
  const RodModel s = parse_scenario(doc);
  EXPECT_EQ(s.actuators[0].drive.segments[0].temperature_K, units::degC_to_K(25.0));
  EXPECT_NEAR(Loads::at_time(s, 0.1).actuators[0].segments[0].temperature_K,
              m.actuators[0].drive.segments[0].temperature_K, kRoundOff * 400);
}

TEST(DynamicsKeys, SegmentedElectricDriveGivesEachSegmentItsShare) {
  json doc = base();
  auto& d = doc["actuators"][0]["drive"];
  d.erase("temperature_degC");
  d["segments"] = {{{"fraction", 0.25}, {"electric", {{"current_A", 1.0}}}},
                   {{"fraction", 0.75}, {"electric", {{"power_W", 0.3}}}}};
  const RodModel m = parse_scenario(doc);
  const Drive& drive = m.actuators[0].drive;
  ASSERT_EQ(drive.electric.size(), 2u);
  EXPECT_EQ(drive.electric[0].thermal.conductance_W_K, 0.25 * 0.0125);
  EXPECT_EQ(drive.electric[1].thermal.resistance_ohm, 0.75 * 0.8);
  // Current: x = i^2 R0 / (hA - i^2 R0 alpha_R) (the fraction cancels).
  const double x0 = 0.8 / (0.0125 - 0.8 * 0.002);
  EXPECT_NEAR(drive.segments[0].temperature_K, units::degC_to_K(25.0) + x0, kRoundOff * 400);
  // Power: x = p / (f hA).
  EXPECT_NEAR(drive.segments[1].temperature_K, units::degC_to_K(25.0) + 0.3 / (0.75 * 0.0125),
              kRoundOff * 400);
  d["segments"][1] = {{"fraction", 0.75}, {"temperature_degC", 50}};
  expect_rejected(doc, "actuators[0].drive.segments[1].temperature_degC", "same kind");
}

TEST(DynamicsKeys, ElectricDrivesRefuseRunawayRangeAndMissingThermalData) {
  json doc = base();
  auto& d = doc["actuators"][0]["drive"];
  d.erase("temperature_degC");
  // i^2 R0 alpha_R = 4 * 0.8 * 0.002 = 0.0064 < hA; 9 A^2 -> 0.0144 >= hA = 0.0125.
  d["electric"] = {{"current_A", 3.0}};
  expect_rejected(doc, "actuators[0].drive.electric.current_A", "thermal runaway");
  d["electric"] = {{"power_W", 5.0}};  // 400 K above ambient
  expect_rejected(doc, "actuators[0].drive.electric.power_W", "outside the valid range");
  d["electric"] = {{"power_W", -0.1}};
  expect_rejected(doc, "actuators[0].drive.electric.power_W", ">= 0");
  d["electric"] = {{"power_W", 0.1}, {"current_A", 0.1}};
  expect_rejected(doc, "actuators[0].drive.electric", "exactly one");
  d["electric"] = {{"power_W", 0.1}};
  d["temperature_degC"] = 50;
  expect_rejected(doc, "actuators[0].drive.electric", "exactly one");
  d.erase("temperature_degC");
  json no_thermal = doc;
  no_thermal["tcas"]["tca"].erase("thermal");
  expect_rejected(no_thermal, "tcas.tca.thermal", "required by the electric drive");
  json bad = doc;
  bad["tcas"]["tca"]["thermal"]["conductance_W_K"] = 0.0;
  expect_rejected(bad, "tcas.tca.thermal.conductance_W_K", "positive");
  bad = doc;
  bad["tcas"]["tca"]["thermal"].erase("resistance_ohm");
  expect_rejected(bad, "tcas.tca.thermal.resistance_ohm", "required");
  bad = doc;
  bad["tcas"]["tca"]["thermal"]["ambient_degC"] = 0.0;
  expect_rejected(bad, "tcas.tca.thermal.ambient_degC", "valid range");
}

TEST(DynamicsKeys, ShippedThermalDataScaleWithFiberLengthAndAcceptOverrides) {
  json doc = base();
  doc["tcas"]["tca"]["thermal"] = {{"data", "silver-nylon-sun2022"}, {"ambient_degC", 25}};
  const RodModel m = parse_scenario(doc);
  const double l = m.tcas.at("tca")->parameters().fiber_length_m;
  const tca::ThermalParameters& p = m.tca_thermal.at("tca");
  EXPECT_NEAR(p.heat_capacity_J_K, 0.31227870799654045 * l, kRoundOff);
  EXPECT_NEAR(p.resistance_ohm, 3.5 * l, kRoundOff);
  // The corrected TCA-TRO time constant rho c_p r_t / (6 h).
  EXPECT_NEAR(p.time_constant_s(), 1127.0 * 2000.0 * 0.21e-3 / (6.0 * 23.0), 1e-12);
  doc["tcas"]["tca"]["thermal"]["conductance_W_K"] = 0.05;  // embedded in silicone
  EXPECT_EQ(parse_scenario(doc).tca_thermal.at("tca").conductance_W_K, 0.05);
  doc["tcas"]["tca"]["thermal"]["data"] = "no-such-set";
  expect_rejected(doc, "tcas.tca.thermal.data", "no shipped thermal data set");
  doc["tcas"]["tca"]["thermal"]["data"] = "../materials/silver-nylon-sun2022";
  expect_rejected(doc, "tcas.tca.thermal.data", "not a path");
}

}  // namespace
}  // namespace tcasim::rod
