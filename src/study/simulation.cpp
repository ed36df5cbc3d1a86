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
  if (o.rtol) {
    const method::AdaptiveOptions ao = adaptive_options(model, o);
    return method::run_adaptive(
        dyn, loads_at, o.duration_s, ao,
        [&](const method::DynamicSolver& d, double dt_s) {
          if (hooks.on_row) {
            rod::TrajectoryRow row = d.row();
            row.dt_s = dt_s;
            hooks.on_row(row);
          }
          if (hooks.on_frame) hooks.on_frame(d.frame());
        },
        [&](double t_s) {
          if (hooks.on_step) {
            const auto done = static_cast<long long>(std::floor(t_s / *o.output_every_s));
            hooks.on_step(std::min(done, n_steps), n_steps);
          }
        });
  }
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

/// The adaptive options' rules; returns the number of output rows after t = 0.
long long check_adaptive_options(const SimulationOptions& o, OptionNames style) {
  const auto name = [style](const char* key) { return option_name(key, style); };
  const std::string with =
      fmt::format("cannot be given with {} (adaptive time steps)", name("rtol"));
  if (o.dt_s != 0.0) throw InputError(name("dt_s"), fmt::format("{}", o.dt_s), with);
  if (o.output_every != 1) {
    throw InputError(name("output_every"), fmt::format("{}", o.output_every),
                     fmt::format("{}; use {}", with, name("output_every_s")));
  }
  require(std::isfinite(o.duration_s) && o.duration_s > 0.0, name("duration_s"), o.duration_s,
          "must be > 0");
  require(*o.rtol > 0.0 && *o.rtol < 1.0, name("rtol"), *o.rtol, "must be in (0, 1)");
  if (o.atol_m) {
    require(std::isfinite(*o.atol_m) && *o.atol_m >= 0.0, name("atol_m"), *o.atol_m,
            "must be >= 0");
  }
  if (!o.output_every_s) {
    throw InputError(name("output_every_s"), "missing",
                     fmt::format("is required with {}", name("rtol")));
  }
  const double T_out = *o.output_every_s;
  require(std::isfinite(T_out) && T_out > 0.0 && T_out <= o.duration_s, name("output_every_s"),
          T_out, fmt::format("must be in (0, {} = {}]", name("duration_s"), o.duration_s));
  const double rows = std::ceil(o.duration_s / T_out * (1.0 - 1e-12));
  require(rows <= kMaxTimeSteps, name("output_every_s"), T_out,
          fmt::format("must give at most {} rows over {}", kMaxTimeSteps, name("duration_s")));
  require(o.alpha >= -0.5 && o.alpha <= 0.0, name("alpha"), o.alpha, "must be in [-0.5, 0]");
  return static_cast<long long>(rows);
}

long long check_simulation_options(const SimulationOptions& o, OptionNames style) {
  const auto name = [style](const char* key) { return option_name(key, style); };
  check_method(o.method, style);
  long long n_steps = 0;
  if (o.rtol) {
    n_steps = check_adaptive_options(o, style);
  } else {
    for (const auto& [key, given] : {std::pair{"atol_m", o.atol_m.has_value()},
                                     std::pair{"output_every_s", o.output_every_s.has_value()}}) {
      if (given) {
        throw InputError(name(key), "given", fmt::format("applies with {} only", name("rtol")));
      }
    }
    n_steps = check_time_options(o.duration_s, o.dt_s, o.alpha, style);
    require_count(o.output_every, name("output_every"), 1, kMaxTimeSteps);
  }
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

namespace {
/// The first step of adaptive steps [s], also the restart after a jump of the loads (small: the
/// start error of the velocities is of its size; growth 1.5 per step reaches 1e-3 T in 17
/// steps); the fixed step otherwise.
/// The shooting method's grid along s with adaptive steps resolves steps of output period / this.
constexpr double kAdaptiveGridSteps = 20.0;
double first_step_s(const SimulationOptions& o) {
  return o.rtol ? std::min(*o.output_every_s, 1e-6 * o.duration_s) : o.dt_s;
}
}  // namespace

method::AdaptiveOptions adaptive_options(const rod::RodModel& model, const SimulationOptions& o) {
  method::AdaptiveOptions a;
  a.rtol = *o.rtol;
  a.atol_m = o.atol_m.value_or(0.0);
  a.output_every_s = *o.output_every_s;
  // The first step: the controller corrects it within a few steps (factor 0.2 down, 5 up).
  a.dt_initial_s = first_step_s(o);
  a.dt_min_s = 1e-12 * o.duration_s;
  a.breakpoints_s = method::time_breakpoints(model, o.duration_s);
  a.max_steps = kMaxTimeSteps;
  return a;
}

method::DynamicOptions dynamic_options(const rod::RodModel& model, const SimulationOptions& o) {
  // The options replace the scenario's viscosity (a constant or a profile along s) and tip
  // mass only when given, in both methods.
  if (o.method == "fe") {
    beam_fe::DynamicsOptions fo;
    fo.elements = static_cast<int>(o.elements);
    fo.order = static_cast<int>(o.order);
    fo.dt_s = first_step_s(o);
    fo.rho_inf = o.rho_inf;
    fo.max_iterations = static_cast<int>(o.max_iterations);
    fo.viscosity_Pa_s = o.viscosity_Pa_s;
    fo.tip_mass_kg = o.tip_mass_kg;
    return fo;
  }
  cosserat::DynamicsOptions co;
  // Adaptive: the grid along s is sized for steps of a twentieth of the output period (or of
  // the run); the solver then resolves steps down to about half that (min_time_step_s), and
  // run_adaptive takes none smaller. --steps sets a finer grid for smaller steps.
  co.dt_s = o.rtol ? std::min(*o.output_every_s, o.duration_s) / kAdaptiveGridSteps : o.dt_s;
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
