// Thermal states of electric TCA drives over time (rod/electric_thermal.hpp).
#include "rod/electric_thermal.hpp"

#include <fmt/format.h>

#include "tca/thermal.hpp"

namespace tcasim::rod {

void ElectricThermalStates::reset(const RodModel& model, const Loads& loads) {
  temperatures_K_.assign(model.actuators.size(), {});
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    const Drive& drive = model.actuators[i].drive;
    if (drive.type != Drive::Type::kTca || !drive.is_electric()) continue;
    for (const tca::Segment& sg : loads.actuators.at(i).segments) {
      temperatures_K_[i].push_back(sg.temperature_K);
    }
  }
}

bool ElectricThermalStates::advance(const RodModel& model, double t_s, double dt_s,
                                    std::string& message) {
  std::vector<std::vector<double>> next = temperatures_K_;
  for (std::size_t i = 0; i < next.size(); ++i) {
    const Drive& drive = model.actuators[i].drive;
    for (std::size_t k = 0; k < next[i].size(); ++k) {
      const ElectricSegment& es = drive.electric[k];
      const bool linear = es.input != tca::ElectricInput::kVoltage ||
                          es.thermal.resistance_temperature_coefficient_1_K == 0.0;
      const tca::ThermalStep ts = tca::thermal_step(
          es.thermal, es.input, es.value.right_limit(t_s), es.value.value(t_s + dt_s), next[i][k],
          dt_s, linear ? tca::ThermalScheme::kExact : tca::ThermalScheme::kTrapezoidal);
      if (!ts.converged) {
        message = fmt::format("the thermal step of actuator '{}' segment {} failed: {}",
                              model.actuators[i].name, k, ts.message);
        return false;
      }
      next[i][k] = ts.temperature_K;
    }
  }
  temperatures_K_ = std::move(next);
  return true;
}

void ElectricThermalStates::apply(std::vector<std::vector<tca::Segment>>& segments) const {
  for (std::size_t i = 0; i < temperatures_K_.size() && i < segments.size(); ++i) {
    for (std::size_t k = 0; k < temperatures_K_[i].size() && k < segments[i].size(); ++k) {
      segments[i][k].temperature_K = temperatures_K_[i][k];
    }
  }
}

}  // namespace tcasim::rod
