// Scenario reader: lumped thermal parameters of TCAs (`tcas.<id>.thermal`), shipped thermal
// data sets (data/thermal/*.json) and electric drives (docs/scenario-format.md
// "Electro-thermal TCAs").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "common/data_dir.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/internal/scenario_reading.hpp"
#include "rod/json_file.hpp"

namespace tcasim::rod::scenario_detail {
namespace {

inline const std::string kThermalSchema = "tcasim.thermal/1";

/// Per metre of fiber: a shipped thermal data set.
struct ThermalPerLength {
  double heat_capacity_J_K_m = 0.0;
  double conductance_W_K_m = 0.0;
  double resistance_ohm_m = 0.0;
  double resistance_temperature_coefficient_1_K = 0.0;
};

/// A data-set value: {"value": x, "source": "..."} (each value names its source).
double sourced_value(const Obj& o, const std::string& k) {
  const Obj v(o.required(k), o.key(k), {"value", "source", "comment"});
  (void)v.nonempty_string("source");
  (void)v.optional_string("comment");
  return v.number("value");
}

ThermalPerLength load_thermal_data(const std::string& name, const std::string& key) {
  const std::filesystem::path file = shipped_data_file("thermal", "thermal data set", name, key);
  const json doc = read_json_file(file.string(), key);
  const std::string prefix = file.string() + ":";
  (void)peek_choice(doc, prefix, "schema", {kThermalSchema});
  const Obj o(doc, prefix,
              {"schema", "name", "comment", "source", "heat_capacity_J_K_m", "conductance_W_K_m",
               "resistance_ohm_m", "resistance_temperature_coefficient_1_K"});
  (void)o.optional_string("name");
  (void)o.optional_string("comment");
  (void)o.nonempty_string("source");
  ThermalPerLength t;
  t.heat_capacity_J_K_m = sourced_value(o, "heat_capacity_J_K_m");
  t.conductance_W_K_m = sourced_value(o, "conductance_W_K_m");
  t.resistance_ohm_m = sourced_value(o, "resistance_ohm_m");
  t.resistance_temperature_coefficient_1_K =
      sourced_value(o, "resistance_temperature_coefficient_1_K");
  require(t.heat_capacity_J_K_m > 0.0, o.key("heat_capacity_J_K_m.value"), t.heat_capacity_J_K_m,
          "must be positive");
  require(t.conductance_W_K_m > 0.0, o.key("conductance_W_K_m.value"), t.conductance_W_K_m,
          "must be positive");
  require(t.resistance_ohm_m > 0.0, o.key("resistance_ohm_m.value"), t.resistance_ohm_m,
          "must be positive");
  return t;
}

tca::ThermalParameters parse_thermal(const json& j, const std::string& path, const tca::Tca& t) {
  const Obj o(j, path,
              {"data", "heat_capacity_J_K", "conductance_W_K", "ambient_degC", "resistance_ohm",
               "resistance_temperature_coefficient_1_K", "source", "comment"});
  (void)o.optional_string("source");
  (void)o.optional_string("comment");
  tca::ThermalParameters p;
  const bool from_data = o.has("data");
  if (from_data) {
    // Whole-TCA values from per-metre values times the fiber length l.
    const ThermalPerLength d = load_thermal_data(o.nonempty_string("data"), o.key("data"));
    const double l = t.parameters().fiber_length_m;
    p.heat_capacity_J_K = d.heat_capacity_J_K_m * l;
    p.conductance_W_K = d.conductance_W_K_m * l;
    p.resistance_ohm = d.resistance_ohm_m * l;
    p.resistance_temperature_coefficient_1_K = d.resistance_temperature_coefficient_1_K;
  }
  // Without `data` every value is required; with it, a value given here replaces the data
  // set's (e.g. a conductance measured for a TCA embedded in silicone).
  const auto value = [&](const std::string& k, double& out) {
    if (from_data && !o.has(k)) return;
    out = o.number(k);
  };
  value("heat_capacity_J_K", p.heat_capacity_J_K);
  value("conductance_W_K", p.conductance_W_K);
  value("resistance_ohm", p.resistance_ohm);
  value("resistance_temperature_coefficient_1_K", p.resistance_temperature_coefficient_1_K);
  require(p.heat_capacity_J_K > 0.0, o.key("heat_capacity_J_K"), p.heat_capacity_J_K,
          "must be positive");
  require(p.conductance_W_K > 0.0, o.key("conductance_W_K"), p.conductance_W_K, "must be positive");
  require(p.resistance_ohm > 0.0, o.key("resistance_ohm"), p.resistance_ohm, "must be positive");
  p.ambient_K = above_absolute_zero_K(o.number("ambient_degC"), o.key("ambient_degC"));
  const tca::Material& m = t.material();
  require(p.ambient_K >= m.min_temperature_K && p.ambient_K <= m.max_temperature_K,
          o.key("ambient_degC"), units::K_to_degC(p.ambient_K),
          fmt::format("is outside the valid range [{:.10g}, {:.10g}] degC of material '{}'",
                      units::K_to_degC(m.min_temperature_K), units::K_to_degC(m.max_temperature_K),
                      m.name));
  return p;
}

}  // namespace

std::map<std::string, tca::ThermalParameters> parse_tca_thermals(
    const json& tcas, const std::string& path,
    const std::map<std::string, std::shared_ptr<const tca::Tca>>& parsed) {
  std::map<std::string, tca::ThermalParameters> out;
  if (!tcas.is_object()) return out;  // parse_tcas has refused it already
  for (auto it = tcas.begin(); it != tcas.end(); ++it) {
    if (!it.value().is_object() || !it.value().contains("thermal")) continue;
    const auto t = parsed.find(it.key());
    if (t == parsed.end()) continue;
    const std::string key = join_path(join_path(path, it.key()), "thermal");
    out.emplace(it.key(), parse_thermal(it.value().at("thermal"), key, *t->second));
  }
  return out;
}

ElectricSegment parse_electric(const json& j, const std::string& path, const std::string& tca_id,
                               double fraction, const RodModel& model, double& steady_K) {
  const auto th = model.tca_thermal.find(tca_id);
  if (th == model.tca_thermal.end()) {
    throw InputError(fmt::format("tcas.{}.thermal", tca_id), "(missing)",
                     fmt::format("is required by the electric drive {}", path));
  }
  const Obj o(j, path, {"voltage_V", "current_A", "power_W"});
  const int given = o.has("voltage_V") + o.has("current_A") + o.has("power_W");
  if (given != 1) {
    throw InputError(path, show(j), "must give exactly one of voltage_V, current_A, power_W");
  }
  ElectricSegment e;
  e.input = o.has("voltage_V")   ? tca::ElectricInput::kVoltage
            : o.has("current_A") ? tca::ElectricInput::kCurrent
                                 : tca::ElectricInput::kPower;
  const std::string k = tca::key_name(e.input);
  const std::string key = o.key(k);
  e.value = parse_time_profile(o.required(k), key);
  if (e.input == tca::ElectricInput::kPower) {
    require(e.value.min_value() >= 0.0, key, e.value.min_value(),
            "must be >= 0 at all times (a Joule power cannot be negative)");
  }
  e.thermal = th->second.fraction(fraction);

  // The static solve uses the steady temperature of the input at t = 0.
  const double u0 = e.value.value(0.0);
  const tca::SteadyTemperature s = tca::steady_temperature(e.thermal, e.input, u0);
  if (!s.exists) throw InputError(key, fmt::format("{} at t = 0", format_value(u0)), s.reason);
  const tca::Material& m = model.tcas.at(tca_id)->material();
  require(s.temperature_K >= m.min_temperature_K && s.temperature_K <= m.max_temperature_K, key,
          fmt::format("{} at t = 0", format_value(u0)),
          fmt::format("gives the steady temperature {:.6g} degC, outside the valid range "
                      "[{:.10g}, {:.10g}] degC of material '{}'",
                      units::K_to_degC(s.temperature_K), units::K_to_degC(m.min_temperature_K),
                      units::K_to_degC(m.max_temperature_K), m.name));
  steady_K = s.temperature_K;
  return e;
}

}  // namespace tcasim::rod::scenario_detail
