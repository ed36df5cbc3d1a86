#include "study/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "beam_fe/dynamics.hpp"
#include "common/error.hpp"
#include "cosserat/dynamics.hpp"
#include "rod/loads.hpp"

namespace tcasim::study {

namespace {

rod::TrajectoryRow cosserat_row(const cosserat::RodDynamics& d) {
  return rod::trajectory_row_of(d, d.probe_positions_W_m());
}

rod::Result cosserat_frame(const rod::RodModel& model, const cosserat::RodDynamics& d) {
  rod::Result r;
  r.scenario = model.name;
  r.method = "cosserat";
  r.converged = true;
  const auto& grid = d.grid_states();
  const auto& grid_s = d.grid_s_m();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    r.centerline_s_m.push_back(grid_s[i]);
    r.centerline_p_W_m.push_back(grid[i].head<3>());
    r.centerline_R_WB.push_back(Eigen::Map<const Eigen::Matrix3d>(grid[i].data() + 3));
  }
  r.tip_position_W_m = d.tip_position_W_m();
  r.tip_R_WB = d.tip_rotation_W();
  return r;
}

rod::Result fe_frame(const rod::RodModel& model, const beam_fe::BeamDynamics& d) {
  rod::Result r;
  r.scenario = model.name;
  r.method = "fe";
  r.converged = true;
  r.centerline_s_m = d.state().s_m;
  r.centerline_p_W_m = d.state().p_W_m;
  for (const auto& q : d.state().q_WB) r.centerline_R_WB.push_back(q.toRotationMatrix());
  r.tip_position_W_m = d.tip_position_W_m();
  r.tip_R_WB = d.tip_rotation_W();
  return r;
}

/// The loop for one dynamics object: rows and frames to the hooks.
template <class Dyn, class RowOf, class FrameOf>
rod::TrajectoryOutcome run(Dyn& dyn, const rod::RodModel& model, const SimulationOptions& o,
                           long long n_steps, const SimulationHooks& hooks, RowOf row_of,
                           FrameOf frame_of) {
  // The loads over time: the scenario's time profiles (tensions, temperatures, tip wrench)
  // at t; the static state at t = 0 takes them at t = 0 (docs/scenario-format.md "Time
  // profiles"). An electric drive's temperatures are the solver's thermal states.
  const bool release = o.release_tip_load;
  const std::function<rod::Loads(double)> loads_at = [&model, release](double t) {
    rod::Loads l = t > 0.0 ? rod::Loads::at_time(model, t) : rod::Loads::from_model(model);
    if (release && t > 0.0) {
      l.tip_force_W_N.setZero();
      l.tip_moment_W_Nm.setZero();
    }
    return l;
  };
  return rod::run_trajectory(
      dyn, loads_at, o.dt_s, n_steps, o.output_every, row_of,
      [&](const rod::TrajectoryRow& row) {
        if (hooks.on_row) hooks.on_row(row);
        if (hooks.on_frame) hooks.on_frame(frame_of(model, dyn));
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

rod::TrajectoryOutcome simulate(const rod::RodModel& model, const SimulationOptions& o,
                                const SimulationHooks& hooks, OptionNames style) {
  const long long n_steps = check_simulation_options(o, style);
  if (o.method == "fe") {
    beam_fe::DynamicsOptions fo;
    fo.elements = static_cast<int>(o.elements);
    fo.order = static_cast<int>(o.order);
    fo.dt_s = o.dt_s;
    fo.rho_inf = o.rho_inf;
    fo.max_iterations = static_cast<int>(o.max_iterations);
    // The option overrides the scenario's viscosity (a constant or a profile along s).
    if (o.viscosity_Pa_s) fo.viscosity_Pa_s = *o.viscosity_Pa_s;
    fo.tip_mass_kg = o.tip_mass_kg.value_or(model.tip_mass_kg);
    std::unique_ptr<beam_fe::BeamDynamics> dyn;
    try {
      dyn = std::make_unique<beam_fe::BeamDynamics>(model, fo);
    } catch (const InputError& e) {
      rethrow_under_option_name(e, style);
    }
    return run(*dyn, model, o, n_steps, hooks, beam_fe::trajectory_row, fe_frame);
  }
  cosserat::DynamicsOptions co;
  co.dt_s = o.dt_s;
  co.alpha = o.alpha;
  co.steps = o.steps ? static_cast<int>(*o.steps) : cosserat::recommended_steps(model, co);
  // The options override the scenario's keys only when given.
  if (o.viscosity_Pa_s) co.viscosity_Pa_s = *o.viscosity_Pa_s;
  if (o.tip_mass_kg) co.tip_mass_kg = *o.tip_mass_kg;
  co.max_iterations = static_cast<int>(o.max_iterations);
  std::unique_ptr<cosserat::RodDynamics> dyn;
  try {
    dyn = std::make_unique<cosserat::RodDynamics>(model, co);
  } catch (const InputError& e) {
    rethrow_under_option_name(e, style);
  }
  return run(*dyn, model, o, n_steps, hooks, cosserat_row, cosserat_frame);
}

}  // namespace tcasim::study
