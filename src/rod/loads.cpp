#include "rod/loads.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"

namespace tcasim::rod {

Loads Loads::from_model(const RodModel& model) {
  Loads a;
  a.tip_force_W_N = model.tip_force_W_N;
  a.tip_moment_W_Nm = model.tip_moment_W_Nm;
  a.gravity_W_m_s2 = model.gravity_W_m_s2;
  a.actuators.reserve(model.actuators.size());
  for (const Actuator& act : model.actuators) {
    ActuatorLoad d;
    d.tension_N = act.drive.tension_N;
    d.segments = act.drive.segments;
    a.actuators.push_back(std::move(d));
  }
  return a;
}

Loads Loads::at_time(const RodModel& model, double t_s) {
  Loads a = from_model(model);
  for (int c = 0; c < 3; ++c) {
    const std::size_t k = static_cast<std::size_t>(c);
    if (!model.tip_force_profile_W_N[k].is_constant())
      a.tip_force_W_N[c] = model.tip_force_profile_W_N[k].value(t_s);
    if (!model.tip_moment_profile_W_Nm[k].is_constant())
      a.tip_moment_W_Nm[c] = model.tip_moment_profile_W_Nm[k].value(t_s);
  }
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    const Drive& d = model.actuators[i].drive;
    ActuatorLoad& load = a.actuators[i];
    if (d.type == Drive::Type::kTension) {
      if (!d.tension_profile_N.is_constant()) load.tension_N = d.tension_profile_N.value(t_s);
      continue;
    }
    for (std::size_t k = 0; k < load.segments.size(); ++k) {
      if (k < d.temperature_profiles_K.size() && !d.temperature_profiles_K[k].is_constant()) {
        load.segments[k].temperature_K = d.temperature_profiles_K[k].value(t_s);
      }
      if (k < d.electric.size() && !d.electric[k].value.is_constant()) {
        const ElectricSegment& e = d.electric[k];
        const double u = e.value.value(t_s);
        const tca::SteadyTemperature st = tca::steady_temperature(e.thermal, e.input, u);
        if (!st.exists) {
          throw DomainError("actuator '" + model.actuators[i].name + "' segment " +
                            std::to_string(k) + ": " + tca::key_name(e.input) + " = " +
                            format_value(u) + " at t = " + format_value(t_s) + " s " + st.reason);
        }
        load.segments[k].temperature_K = st.temperature_K;
      }
    }
  }
  return a;
}

void Loads::set_temperature_K(std::size_t index, double t_K) {
  require(index < actuators.size(), "loads.actuators index", static_cast<double>(index),
          "must be < the number of actuators");
  for (tca::Segment& seg : actuators[index].segments) seg.temperature_K = t_K;
}

void Loads::set_segment_temperatures_K(std::size_t index, const std::vector<double>& t_K) {
  require(index < actuators.size(), "loads.actuators index", static_cast<double>(index),
          "must be < the number of actuators");
  std::vector<tca::Segment>& segs = actuators[index].segments;
  require(t_K.size() == segs.size(), "loads.actuators[" + std::to_string(index) + "] temperatures",
          static_cast<double>(t_K.size()),
          "must give one temperature per segment (" + std::to_string(segs.size()) + ")");
  for (std::size_t k = 0; k < segs.size(); ++k) segs[k].temperature_K = t_K[k];
}

void Loads::set_tension_N(std::size_t index, double tension_N) {
  require(index < actuators.size(), "loads.actuators index", static_cast<double>(index),
          "must be < the number of actuators");
  actuators[index].tension_N = tension_N;
}

void Loads::validate(const RodModel& model) const {
  if (actuators.size() != model.actuators.size()) {
    throw_input_error(
        "loads.actuators", static_cast<double>(actuators.size()),
        "must have one entry per model actuator (" + std::to_string(model.actuators.size()) + ")");
  }
  if (!(load_scale >= 0.0 && load_scale <= 1.0)) {
    throw_input_error("loads.load_scale", load_scale, "must be in [0, 1]");
  }
  if (!tip_force_W_N.allFinite() || !tip_moment_W_Nm.allFinite() || !gravity_W_m_s2.allFinite()) {
    throw_input_error("loads tip_force_W_N/tip_moment_W_Nm/gravity_W_m_s2", "(not finite)",
                      "must be finite");
  }
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    const std::string key = "loads.actuators[" + std::to_string(i) + "]";
    if (model.actuators[i].drive.type == Drive::Type::kTca) {
      if (actuators[i].segments.empty())
        throw_input_error(key + ".segments", 0.0, "must not be empty for a TCA drive");
      for (const tca::Segment& seg : actuators[i].segments) {
        require(std::isfinite(seg.temperature_K), key + ".segments temperature_K",
                seg.temperature_K, "must be finite");
      }
    } else {
      require(std::isfinite(actuators[i].tension_N), key + ".tension_N", actuators[i].tension_N,
              "must be finite");
    }
  }
}

Loads Loads::applied(const RodModel& model) const {
  if (load_scale == 1.0) return *this;
  Loads a = *this;
  const double s = load_scale;
  a.load_scale = 1.0;
  a.tip_force_W_N *= s;
  a.tip_moment_W_Nm *= s;
  a.gravity_W_m_s2 *= s;
  for (std::size_t i = 0; i < a.actuators.size() && i < model.actuators.size(); ++i) {
    a.actuators[i].tension_N *= s;
    const Drive& drive = model.actuators[i].drive;
    if (drive.type != Drive::Type::kTca || !drive.tca) continue;
    const double t_ref = drive.tca->material().reference_temperature_K;
    for (tca::Segment& seg : a.actuators[i].segments)
      seg.temperature_K = t_ref + s * (seg.temperature_K - t_ref);
  }
  return a;
}

double characteristic_force_N(const RodModel& model, const Loads& loads) {
  return characteristic_force_N(model, loads, model.tip_mass_kg);
}

double characteristic_force_N(const RodModel& model, const Loads& loads, double tip_mass_kg) {
  if (loads.load_scale != 1.0)
    return characteristic_force_N(model, loads.applied(model), tip_mass_kg);
  const Loads& a = loads;  // no copy: called once per solve by both solvers
  const double L = model.length_m;
  const Eigen::Vector3d K_omega = model.bending_torsion_stiffness();
  const double EI = std::min(K_omega.x(), K_omega.y());
  const Eigen::Vector3d tip_force =
      tip_mass_kg == 0.0 ? a.tip_force_W_N
                         : Eigen::Vector3d(a.tip_force_W_N + tip_mass_kg * a.gravity_W_m_s2);
  double load = std::max(tip_force.norm(), a.tip_moment_W_Nm.norm() / L);
  load = std::max(load, model.mass_per_length_kg_m(0.0) * a.gravity_W_m_s2.norm() * L);
  for (std::size_t i = 0; i < model.actuators.size() && i < a.actuators.size(); ++i) {
    const Actuator& act = model.actuators[i];
    if (act.drive.type == Drive::Type::kTension)
      load = std::max(load, act.count * std::abs(a.actuators[i].tension_N));
  }
  return std::max(EI / (L * L), load);
}

Eigen::Vector3d tip_force_with_weight_W_N(const RodModel& model, const Loads& loads) {
  if (model.tip_mass_kg == 0.0) return loads.tip_force_W_N;
  return loads.tip_force_W_N + model.tip_mass_kg * loads.gravity_W_m_s2;
}

}  // namespace tcasim::rod
