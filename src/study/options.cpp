#include "study/options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.hpp"
#include "common/units.hpp"
#include "tca/curve.hpp"

namespace tcasim::study {

std::string option_name(const std::string& key, OptionNames style) {
  if (style == OptionNames::kPython) return key;
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

void rethrow_under_option_name(const InputError& e, OptionNames style) {
  // The keys of the library's option structs that are the front ends' options by the same
  // name (cosserat::DynamicsOptions, beam_fe::DynamicsOptions, beam_fe::Options, the inverse's
  // temperature bound).
  static const char* const kOptionKeys[] = {
      "steps",       "elements",       "order",          "rho_inf",     "alpha",
      "dt_s",        "max_iterations", "viscosity_Pa_s", "tip_mass_kg", "max_temperature_degC",
      "integration", "linear_solver"};
  std::string key = e.key();
  const std::string prefix = "dynamics.";
  if (key.compare(0, prefix.size(), prefix) == 0) key = key.substr(prefix.size());
  for (const char* option : kOptionKeys) {
    if (key == option) throw InputError(option_name(key, style), e.value(), e.rule());
  }
  throw e;
}

void require_count(long long value, const std::string& name, long long lo, long long hi) {
  // The value as an integer (a double would round counts beyond 2^53).
  if (value < lo || value > hi) {
    throw InputError(name, fmt::format("{}", value),
                     fmt::format("must be an integer in [{}, {}]", lo, hi));
  }
}

void refuse_other_method_options(const std::string& method, const std::vector<GivenOption>& given,
                                 OptionNames style) {
  const auto name = [style](const char* key) { return option_name(key, style); };
  const auto method_is = [style](const char* m) {
    return style == OptionNames::kFlags ? fmt::format("--method {}", m)
                                        : fmt::format("method=\"{}\"", m);
  };
  for (const GivenOption& g : given) {
    const bool fe_option = g.key == "elements" || g.key == "order" || g.key == "rho_inf";
    const bool shooting_option = g.key == "steps" || g.key == "alpha";
    if (fe_option && method != "fe") {
      throw InputError(option_name(g.key, style), g.value,
                       fmt::format("applies to {} only (cosserat: {}, {})", method_is("fe"),
                                   name("steps"), name("alpha")));
    }
    if (shooting_option && method == "fe") {
      throw InputError(option_name(g.key, style), g.value,
                       fmt::format("applies to {} only (fe: {}, {}, {})", method_is("cosserat"),
                                   name("elements"), name("order"), name("rho_inf")));
    }
  }
}

void check_method(const std::string& method, OptionNames style) {
  require(method == "cosserat" || method == "fe", option_name("method", style), method,
          "must be cosserat or fe");
}

cosserat::Options shooting_options(const ShootingChoice& c, OptionNames style) {
  const auto name = [style](const char* key) { return option_name(key, style); };
  cosserat::Options o;
  const std::string scheme = c.scheme.value_or("rk4");
  require(scheme == "rk4" || scheme == "rk6" || scheme == "rk8", name("scheme"), scheme,
          "must be rk4, rk6 or rk8");
  if (c.rtol && (c.steps || c.scheme)) {
    throw InputError(name("rtol"), format_value(*c.rtol),
                     fmt::format("excludes {} and {} (CVODE chooses its own steps)", name("steps"),
                                 name("scheme")));
  }
  o.integrator.method = scheme == "rk8"   ? ode::Method::kRk8
                        : scheme == "rk6" ? ode::Method::kRk6
                                          : ode::Method::kRk4;
  if (c.rtol) {
    require(*c.rtol > 0.0 && *c.rtol < 1.0, name("rtol"), *c.rtol, "must be in (0, 1)");
    o.integrator.method = ode::Method::kCvode;
    o.integrator.relative_tolerance = *c.rtol;
    o.integrator.absolute_tolerance = *c.rtol * 1e-3;
  } else if (c.steps) {
    if (*c.steps < 2 || *c.steps > kMaxSteps || *c.steps % 2 != 0) {
      throw InputError(name("steps"), fmt::format("{}", *c.steps),
                       fmt::format("must be an even number in [2, {}]", kMaxSteps));
    }
    o.integrator.steps = static_cast<int>(*c.steps);
  }
  // RK8's coarse level: 2 steps are about as accurate as RK6's 4 (its Jacobians start the
  // warm steps of sweeps).
  if (o.integrator.method == ode::Method::kRk8) o.coarse_steps = 2;
  o.planar_reduction = !c.no_planar;
  return o;
}

beam_fe::Options fe_options(const FeChoice& c, OptionNames style) {
  const auto name = [style](const char* key) { return option_name(key, style); };
  require_count(c.elements, name("elements"), 1, kMaxElements);
  if (c.order != 1 && c.order != 2) {
    throw InputError(name("order"), fmt::format("{}", c.order), "must be 1 or 2");
  }
  beam_fe::Options o;
  o.elements = static_cast<int>(c.elements);
  o.order = static_cast<int>(c.order);
  // beam_fe's parsers name the keys in snake_case (the Python names).
  try {
    o.integration = beam_fe::parse_integration(c.integration);
    o.linear_solver = beam_fe::parse_linear_solver(c.linear_solver);
  } catch (const InputError& e) {
    rethrow_under_option_name(e, style);
  }
  return o;
}

method::StaticOptions static_options(const std::string& method, const ShootingChoice& shooting,
                                     const FeChoice& fe, OptionNames style) {
  check_method(method, style);
  if (method == "fe") return fe_options(fe, style);
  return shooting_options(shooting, style);
}

void check_sweep_jobs(long long jobs, long long chunk, OptionNames style) {
  require_count(jobs, option_name("jobs", style), 1, kMaxJobs);
  require_count(chunk, option_name("chunk", style), 1, kMaxSweepChunk);
}

std::vector<double> temperatures_K(const std::vector<double>& temperatures_degC,
                                   const std::string& key, OptionNames style) {
  std::vector<double> out;
  out.reserve(temperatures_degC.size());
  for (const double t : temperatures_degC) {
    require(std::isfinite(t) && t > -units::kZeroCelsius_K, option_name(key, style), t,
            "must be above absolute zero (-273.15 degC)");
    out.push_back(units::degC_to_K(t));
  }
  return out;
}

double tca_tension_N(const std::optional<double>& tension_N, const std::optional<double>& load_g,
                     OptionNames style) {
  const std::string tension_name = option_name("tension_N", style);
  const std::string load_name = option_name("load_g", style);
  if (!tension_N && !load_g) {
    throw InputError(tension_name, "(missing)",
                     fmt::format("is required unless {} is given (give exactly one)", load_name));
  }
  if (tension_N && load_g) {
    throw InputError(tension_name, format_value(*tension_N),
                     fmt::format("excludes {} (give exactly one)", load_name));
  }
  if (load_g) {
    require(std::isfinite(*load_g) && *load_g >= 0.0, load_name, *load_g,
            "must be >= 0 (a hanging mass)");
    return tca::hanging_load_tension_N(units::g_to_kg(*load_g));
  }
  require(std::isfinite(*tension_N), tension_name, *tension_N, "must be finite");
  return *tension_N;
}

double max_temperature_K(const std::optional<double>& t_degC, OptionNames style) {
  if (!t_degC) return std::numeric_limits<double>::quiet_NaN();
  require(std::isfinite(*t_degC) && *t_degC > -units::kZeroCelsius_K,
          option_name("max_temperature_degC", style), *t_degC, "must be above absolute zero");
  return units::degC_to_K(*t_degC);
}

void check_grasp_options(double mass_g, double friction, long long fingers, OptionNames style) {
  require(std::isfinite(mass_g) && mass_g > 0.0, option_name("mass_g", style), mass_g,
          "must be > 0");
  require(std::isfinite(friction) && friction > 0.0, option_name("friction", style), friction,
          "must be > 0");
  if (fingers < 1 || fingers > std::numeric_limits<int>::max()) {
    throw InputError(option_name("fingers", style), fmt::format("{}", fingers),
                     fmt::format("must be an integer in [1, {}]", std::numeric_limits<int>::max()));
  }
}

std::vector<std::string> split_list(const std::string& text, char delimiter,
                                    const std::string& name, const std::string& rule) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(delimiter, start);
    items.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (!items[k].empty()) continue;
    if (items.size() == 1) throw InputError(name, "\"\"", rule + ", not an empty text");
    const char* where = k == 0 ? "a leading" : k + 1 == items.size() ? "a trailing" : "a doubled";
    throw InputError(name, text,
                     fmt::format("{}: item {} of {} is empty ({} '{}')", rule, k + 1, items.size(),
                                 where, delimiter));
  }
  return items;
}

std::vector<int> actuator_indices(const rod::RodModel& model, const std::string& names,
                                  const std::string& name) {
  std::vector<int> out;
  if (names.empty()) {
    for (int i = 0; i < static_cast<int>(model.actuators.size()); ++i) out.push_back(i);
    return out;
  }
  std::string all;
  for (const auto& a : model.actuators) all += (all.empty() ? "" : ", ") + a.name;
  for (const std::string& item :
       split_list(names, ',', name, "must be comma-separated actuator names")) {
    int found = -1;
    for (int i = 0; i < static_cast<int>(model.actuators.size()); ++i) {
      if (model.actuators[i].name == item) found = i;
    }
    require(found >= 0, name, names,
            "names an actuator the scenario does not have: '" + item + "' (it has: " + all + ")");
    require(std::find(out.begin(), out.end(), found) == out.end(), name, names,
            "names actuator '" + item + "' twice");
    out.push_back(found);
  }
  return out;
}

}  // namespace tcasim::study
