// Scenario reader: profiles along the body (docs/scenario-format.md "Profiles along the body").
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "rod/internal/scenario_reading.hpp"
#include "rod/profile.hpp"

namespace tcasim::rod::scenario_detail {
namespace {

const char* rule_text(ValueRule rule) {
  switch (rule) {
    case ValueRule::kPositive:
      return "must be positive";
    case ValueRule::kNonNegative:
      return "must not be negative";
    case ValueRule::kAny:
      break;
  }
  return "";
}

void check_value(double x, const std::string& key, ValueRule rule) {
  if (rule == ValueRule::kPositive) require(x > 0.0, key, x, rule_text(rule));
  if (rule == ValueRule::kNonNegative) require(x >= 0.0, key, x, rule_text(rule));
}

std::vector<double> number_array(const Obj& o, const std::string& k) {
  const json& v = o.required(k);
  if (!v.is_array() || v.size() < 2) {
    throw InputError(o.key(k), show(v), "must be an array of at least two numbers");
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    out.push_back(as_number(v[i], fmt::format("{}[{}]", o.key(k), i)));
  }
  return out;
}

}  // namespace

Profile parse_profile(const json& v, const std::string& key, double length_m, ValueRule rule) {
  if (v.is_number()) {
    const double x = as_number(v, key);
    check_value(x, key, rule);
    return Profile(x);
  }
  if (!v.is_object()) {
    throw InputError(key, show(v),
                     fmt::format("must be a number or a profile {{\"s_m\": [...], \"values\": "
                                 "[...]}}, not {}",
                                 type_name(v)));
  }
  const Obj o(v, key, {"s_m", "values"});
  std::vector<double> s = number_array(o, "s_m");
  std::vector<double> values = number_array(o, "values");
  require(values.size() == s.size(), o.key("values"), show(o.required("values")),
          fmt::format("must have as many entries as s_m ({}, it has {})", s.size(), values.size()));
  // The ends must be 0 and L; a few units of round-off in a typed L are snapped to it.
  const double snap = 1e-12 * length_m;
  require(std::abs(s.front()) <= snap, o.key("s_m") + "[0]", s.front(), "must be 0 (the base)");
  s.front() = 0.0;
  require(std::abs(s.back() - length_m) <= snap, fmt::format("{}[{}]", o.key("s_m"), s.size() - 1),
          s.back(), fmt::format("must equal body.length_m = {} (the tip)", format_value(length_m)));
  s.back() = length_m;
  for (std::size_t i = 1; i < s.size(); ++i) {
    const std::string ki = fmt::format("{}[{}]", o.key("s_m"), i);
    require(s[i] >= s[i - 1], ki, s[i],
            fmt::format("must not be below the s before it ({}): s never decreases",
                        format_value(s[i - 1])));
    if (i >= 2) {
      require(s[i] != s[i - 2], ki, s[i],
              "appears a third time: a repeated s is one jump (left value, right value)");
    }
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    check_value(values[i], fmt::format("{}[{}]", o.key("values"), i), rule);
  }
  return Profile(std::move(s), std::move(values));
}

Profile parse_profile_key(const Obj& o, const std::string& k, double length_m, ValueRule rule) {
  return parse_profile(o.required(k), o.key(k), length_m, rule);
}

}  // namespace tcasim::rod::scenario_detail
