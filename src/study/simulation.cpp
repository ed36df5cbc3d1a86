#include "study/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/error.hpp"
#include "method/dynamics.hpp"
#include "rod/loads.hpp"

namespace tcasim::study {

namespace {

/// RK4 steps along s (as apps/cli_util.hpp kMaxSteps).
constexpr int kMaxSteps = 100000;

void require_count(long long value, const std::string& key, OptionNames style, long long lo,
                   long long hi) {
  require(value >= lo && value <= hi, option_name(key, style), static_cast<double>(value),
          fmt::format("must be an integer in [{}, {}]", lo, hi));
}

/// An InputError of a dynamics constructor under the option's name.
[[noreturn]] void rethrow_named(const InputError& e, OptionNames style) {
  std::string key = e.key();
  if (key.rfind("dynamics.", 0) == 0) key = key.substr(9);
  if (key == "steps" || key == "rho_inf" || key == "elements" || key == "order") {
    throw InputError(option_name(key, style), e.value(), e.rule());
  }
  throw e;
}

/// The time loop for one solver: rows and frames to the hooks.
rod::TrajectoryOutcome run(method::DynamicSolver& dyn, const rod::RodModel& model,
                           const SimulationOptions& o, long long n_steps,
                           const SimulationHooks& hooks) {
  const bool release = o.release_tip_load;
  const rod::LoadsAt loads_at = [&model, release](double t) {
    return method::loads_at(model, t, release);
  };
  return method::run(
      dyn, loads_at, n_steps, o.output_every,
      [&](const method::DynamicSolver& d) {
        if (hooks.on_row) hooks.on_row(d.row());
        if (hooks.on_frame) hooks.on_frame(d.frame());
      },
      [&](long long k) {
        if (hooks.on_step) hooks.on_step(k, n_steps);
      });
}

}  // namespace

std::string option_name(const std::string& key, OptionNames style) {
  if (style == OptionNames::kPython) return key;
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

long long check_time_options(double duration_s, double dt_s, double alpha, OptionNames style) {
  const auto name = [style](const char* key) { return option_name(key, style); };
  require(std::isfinite(duration_s) && duration_s > 0.0, name("duration_s"), duration_s,
          "must be > 0");
  require(std::isfinite(dt_s) && dt_s > 0.0, name("dt_s"), dt_s, "must be > 0");
  const double n_steps = std::round(duration_s / dt_s);
  require(n_steps >= 1 && n_steps <= kMaxTimeSteps, name("duration_s"), duration_s,
          fmt::format("must be between 1 and {} time steps of {}", kMaxTimeSteps, name("dt_s")));
  require(alpha >= -0.5 && alpha <= 0.0, name("alpha"), alpha, "must be in [-0.5, 0]");
  return static_cast<long long>(n_steps);
}

long long check_simulation_options(const SimulationOptions& o, OptionNames style) {
  const auto name = [style](const char* key) { return option_name(key, style); };
  require(o.method == "cosserat" || o.method == "fe", name("method"), o.method,
          "must be cosserat or fe");
  const long long n_steps = check_time_options(o.duration_s, o.dt_s, o.alpha, style);
  require_count(o.output_every, "output_every", style, 1, kMaxTimeSteps);
  if (o.steps != 0) require_count(o.steps, "steps", style, 1, kMaxSteps);
  if (o.viscosity_Pa_s) {
    require(std::isfinite(*o.viscosity_Pa_s) && *o.viscosity_Pa_s >= 0.0, name("viscosity_Pa_s"),
            *o.viscosity_Pa_s, "must be >= 0");
  }
  if (o.tip_mass_kg) {
    require(std::isfinite(*o.tip_mass_kg) && *o.tip_mass_kg >= 0.0, name("tip_mass_kg"),
            *o.tip_mass_kg, "must be >= 0");
  }
  require_count(o.max_iterations, "max_iterations", style, 1, 1000);
  return n_steps;
}

method::DynamicOptions dynamic_options(const rod::RodModel& model, const SimulationOptions& o) {
  // The options replace the scenario's viscosity (a constant or a profile along s) and tip
  // mass only when given, in both methods.
  if (o.method == "fe") {
    beam_fe::DynamicsOptions fo;
    fo.elements = o.elements;
    fo.order = o.order;
    fo.dt_s = o.dt_s;
    fo.rho_inf = o.rho_inf;
    fo.max_iterations = o.max_iterations;
    fo.viscosity_Pa_s = o.viscosity_Pa_s;
    fo.tip_mass_kg = o.tip_mass_kg;
    return fo;
  }
  cosserat::DynamicsOptions co;
  co.dt_s = o.dt_s;
  co.alpha = o.alpha;
  co.steps = o.steps != 0 ? o.steps : cosserat::recommended_steps(model, co);
  co.viscosity_Pa_s = o.viscosity_Pa_s;
  co.tip_mass_kg = o.tip_mass_kg;
  co.max_iterations = o.max_iterations;
  return co;
}

rod::TrajectoryOutcome simulate(const rod::RodModel& model, const SimulationOptions& o,
                                const SimulationHooks& hooks, OptionNames style) {
  const long long n_steps = check_simulation_options(o, style);
  std::unique_ptr<method::DynamicSolver> dyn;
  try {
    dyn = std::make_unique<method::DynamicSolver>(model, dynamic_options(model, o));
  } catch (const InputError& e) {
    rethrow_named(e, style);
  }
  return run(*dyn, model, o, n_steps, hooks);
}

}  // namespace tcasim::study
