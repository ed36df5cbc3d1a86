#pragma once
/// Models of the FE dynamics' TCA tests (tests/beam_fe/dynamics_tca_test.cpp and its slow
/// counterpart).
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "rod/model.hpp"
#include "rod/scenario.hpp"
#include "tca/thermal.hpp"

namespace tcasim::beam_fe::testing {

/// Voltage of the step: a steady 90 degC on validation/scenarios/circular-manipulator-voltage.json.
inline constexpr double kVoltage_V = 0.714;

/// The scenario file validation/scenarios/<name>.json as JSON.
inline nlohmann::json scenario_json(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios";
  std::ifstream in(dir / (name + ".json"));
  return nlohmann::json::parse(in);
}

/// A model from JSON with the scenario directory as its base (for data files).
inline rod::RodModel scenario_model(const nlohmann::json& j) {
  const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios";
  return rod::parse_scenario(j, dir.string());
}

/// circular-manipulator-voltage.json with the voltage switched on at t = 0+ (ambient before),
/// Kelvin-Voigt damping of `viscosity_Pa_s`, the heat capacity divided by 20 (time constant
/// 0.17 s instead of 3.43 s) and, unless `r_of_t`, a constant resistance (as
/// tests/cosserat/dynamics_tca_test.cpp).
inline rod::RodModel voltage_step_manipulator(double viscosity_Pa_s, bool r_of_t = false) {
  nlohmann::json j = scenario_json("circular-manipulator-voltage");
  j["actuators"][0]["drive"]["electric"] = {
      {"voltage_V", {{"step", {{"t_s", 0.0}, {"before", 0.0}, {"after", kVoltage_V}}}}}};
  j["body"]["material"]["viscosity_Pa_s"] = viscosity_Pa_s;
  rod::RodModel m = scenario_model(j);
  tca::ThermalParameters& th = m.actuators[0].drive.electric[0].thermal;
  th.heat_capacity_J_K /= 20.0;
  if (!r_of_t) th.resistance_temperature_coefficient_1_K = 0.0;
  return m;
}

}  // namespace tcasim::beam_fe::testing
