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
  check_method(o.method, style);
  const long long n_steps = check_time_options(o.duration_s, o.dt_s, o.alpha, style);
  require_count(o.output_every, name("output_every"), 1, kMaxTimeSteps);
  if (o.steps) require_count(*o.steps, name("steps"), 1, kMaxSteps);
  require_count(o.elements, name("elements"), 1, kMaxElements);
  if (o.order != 1 && o.order != 2) {
    throw InputError(name("order"), fmt::format("{}", o.order), "must be 1 or 2");
  }
  require(o.rho_inf >= 0.0 && o.rho_inf <= 1.0, name("rho_inf"), o.rho_inf, "must be in [0, 1]");
  if (o.viscosity_Pa_s) {
    require(std::isfinite(*o.viscosity_Pa_s) && *o.viscosity_Pa_s >= 0.0, name("viscosity_Pa_s"),
            *o.viscosity_Pa_s, "must be >= 0");
  }
  if (o.tip_mass_kg) {
    require(std::isfinite(*o.tip_mass_kg) && *o.tip_mass_kg >= 0.0, name("tip_mass_kg"),
            *o.tip_mass_kg, "must be >= 0");
  }
  require_count(o.max_iterations, name("max_iterations"), 1, kMaxNewtonIterations);
  return n_steps;
}

method::DynamicOptions dynamic_options(const rod::RodModel& model, const SimulationOptions& o) {
  // The options replace the scenario's viscosity (a constant or a profile along s) and tip
  // mass only when given, in both methods.
  if (o.method == "fe") {
    beam_fe::DynamicsOptions fo;
    fo.elements = static_cast<int>(o.elements);
    fo.order = static_cast<int>(o.order);
    fo.dt_s = o.dt_s;
    fo.rho_inf = o.rho_inf;
    fo.max_iterations = static_cast<int>(o.max_iterations);
    fo.viscosity_Pa_s = o.viscosity_Pa_s;
    fo.tip_mass_kg = o.tip_mass_kg;
    return fo;
  }
  cosserat::DynamicsOptions co;
  co.dt_s = o.dt_s;
  co.alpha = o.alpha;
  co.steps = o.steps ? static_cast<int>(*o.steps) : cosserat::recommended_steps(model, co);
  co.viscosity_Pa_s = o.viscosity_Pa_s;
  co.tip_mass_kg = o.tip_mass_kg;
  co.max_iterations = static_cast<int>(o.max_iterations);
  return co;
}

rod::TrajectoryOutcome simulate(const rod::RodModel& model, const SimulationOptions& o,
                                const SimulationHooks& hooks, OptionNames style) {
  const long long n_steps = check_simulation_options(o, style);
  std::unique_ptr<method::DynamicSolver> dyn;
  try {
    dyn = std::make_unique<method::DynamicSolver>(model, dynamic_options(model, o));
  } catch (const InputError& e) {
    rethrow_under_option_name(e, style);
  }
  return run(*dyn, model, o, n_steps, hooks);
}

}  // namespace tcasim::study
