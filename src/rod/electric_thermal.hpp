#pragma once
/// The thermal states of a model's electrically driven TCAs over time (docs/conventions.md
/// "TCAs in rod dynamics"): per actuator and segment the temperature of the lumped law
/// (tca/thermal.hpp), advanced step by step with the drive's time profile. The temperatures do
/// not depend on the mechanics, so a dynamics solver advances them first and then solves its
/// step at the new temperatures.
#include <string>
#include <vector>

#include "rod/loads.hpp"
#include "rod/model.hpp"

namespace tcasim::rod {

class ElectricThermalStates {
 public:
  /// The states start at the loads' segment temperatures of each electric drive (the steady
  /// temperatures of the inputs at t = 0 for Loads::from_model); other actuators have none.
  void reset(const RodModel& model, const Loads& loads);
  /// Advances every state from t_s to t_s + dt_s: the input's right limit at t_s and its value
  /// at t_s + dt_s (tca::thermal_step), exact where the law is linear in T (a power or current
  /// drive, or alpha_R = 0), else the trapezoidal rule. False, with the states unchanged and
  /// `message` saying which segment failed and why, when a step does not converge.
  bool advance(const RodModel& model, double t_s, double dt_s, std::string& message);
  /// Replaces the segment temperatures of every electric drive in `segments` (per actuator,
  /// as Loads::actuators[i].segments) by the states.
  void apply(std::vector<std::vector<tca::Segment>>& segments) const;
  /// Per actuator, its states [K] (empty unless the drive is electric).
  const std::vector<std::vector<double>>& temperatures_K() const { return temperatures_K_; }

 private:
  std::vector<std::vector<double>> temperatures_K_;
};

}  // namespace tcasim::rod
