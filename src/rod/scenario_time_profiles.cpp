// Scenario reader: time profiles (docs/scenario-format.md "Time profiles").
#include <fmt/format.h>

#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/internal/scenario_reading.hpp"

namespace tcasim::rod::scenario_detail {
namespace {

const std::vector<std::string> kProfileForms = {"{\"t_s\", \"values\"}", "step", "pwm", "sine"};

std::vector<double> number_array(const Obj& o, const std::string& k) {
  const json& v = o.required(k);
  if (!v.is_array()) {
    throw InputError(o.key(k), show(v),
                     fmt::format("must be an array of numbers, not {}", type_name(v)));
  }
  std::vector<double> out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    out.push_back(as_number(v[i], fmt::format("{}[{}]", o.key(k), i)));
  }
  return out;
}

}  // namespace

TimeProfile parse_time_profile(const json& v, const std::string& key) {
  if (v.is_number()) return TimeProfile::constant(as_number(v, key), key);
  if (!v.is_object()) {
    throw InputError(key, show(v),
                     fmt::format("must be a number or a time profile (an object: {})",
                                 fmt::join(kProfileForms, ", ")));
  }
  if (v.contains("t_s") || v.contains("values")) {
    const Obj o(v, key, {"t_s", "values"});
    return TimeProfile::table(number_array(o, "t_s"), number_array(o, "values"), key);
  }
  if (v.size() != 1) {
    throw InputError(key, show(v),
                     fmt::format("must be a time profile with exactly one of: {}",
                                 fmt::join(kProfileForms, ", ")));
  }
  const Obj outer(v, key, {"step", "pwm", "sine"});
  if (outer.has("step")) {
    const Obj o(outer.required("step"), outer.key("step"), {"t_s", "before", "after"});
    return TimeProfile::step(o.number("t_s"), o.number("before"), o.number("after"), key);
  }
  if (outer.has("pwm")) {
    const Obj o(outer.required("pwm"), outer.key("pwm"), {"period_s", "duty", "high", "low"});
    return TimeProfile::pwm(o.number("period_s"), o.number("duty"), o.number("high"),
                            o.number("low"), key);
  }
  const Obj o(outer.required("sine"), outer.key("sine"),
              {"mean", "amplitude", "frequency_Hz", "phase_deg"});
  const double phase_deg = o.optional_number("phase_deg").value_or(0.0);
  return TimeProfile::sine(o.number("mean"), o.number("amplitude"), o.number("frequency_Hz"),
                           units::deg_to_rad(phase_deg), key);
}

std::array<TimeProfile, 3> parse_profile_vector3(const Obj& o, const std::string& k) {
  const json& v = o.required(k);
  if (!v.is_array() || v.size() != 3) {
    throw InputError(o.key(k), show(v),
                     "must be an array of 3 components, each a number or a time profile");
  }
  std::array<TimeProfile, 3> out;
  for (std::size_t i = 0; i < 3; ++i) {
    out[i] = parse_time_profile(v[i], fmt::format("{}[{}]", o.key(k), i));
  }
  return out;
}

Eigen::Vector3d values_at(const std::array<TimeProfile, 3>& p, double t_s) {
  return Eigen::Vector3d(p[0].value(t_s), p[1].value(t_s), p[2].value(t_s));
}

}  // namespace tcasim::rod::scenario_detail
