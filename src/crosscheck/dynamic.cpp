#include "crosscheck/dynamic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <variant>

#include "common/error.hpp"
#include "method/dynamics.hpp"
#include "study/simulation.hpp"

namespace tcasim::crosscheck {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Output times of two runs are the same time when within this fraction of the duration (they
/// are integer multiples of their steps, exact up to round-off).
constexpr double kTimeMatch = 1e-9;
/// Richardson in dt at ratio 2 for a second-order scheme: 2^2 - 1.
constexpr double kRichardsonDenominator = 3.0;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Whole time steps of the run and the output stride.
struct TimeGrid {
  long long steps = 0;
  long long every = 1;
};

TimeGrid time_grid(const DynamicSettings& s) {
  require(std::isfinite(s.duration_s) && s.duration_s > 0.0, "duration_s", s.duration_s,
          "must be > 0");
  if (s.rtol) return {};
  require(std::isfinite(s.dt_s) && s.dt_s > 0.0, "dt_s", s.dt_s, "must be > 0");
  require(std::isfinite(s.output_dt_s) && s.output_dt_s >= 0.0, "output_dt_s", s.output_dt_s,
          "must be >= 0");
  TimeGrid g;
  g.steps = std::llround(s.duration_s / s.dt_s);
  require(g.steps >= 1, "duration_s", s.duration_s, "must hold at least one time step dt_s");
  g.every = s.output_dt_s > 0.0 ? std::max(1LL, std::llround(s.output_dt_s / s.dt_s)) : 1;
  return g;
}

beam_fe::DynamicsOptions fe_options(const DynamicSettings& s) {
  beam_fe::DynamicsOptions o;
  o.elements = s.elements;
  o.order = s.order;
  o.dt_s = s.dt_s;
  o.rho_inf = s.rho_inf;
  o.tolerance = s.fe_tolerance;
  o.max_iterations = s.max_iterations;
  // viscosity_Pa_s and tip_mass_kg unset: the model's (as the shooting run's).
  return o;
}

/// The options of `method` in the settings (the viscosity and tip mass are the scenario's in
/// both methods).
/// The adaptive settings as `tcasim simulate --rtol` options of `method` (one policy for the
/// first step, the breakpoints and the shooting grid: study/simulation.hpp).
study::SimulationOptions adaptive_simulation(DynamicMethod method, const DynamicSettings& s) {
  study::SimulationOptions o;
  o.method = to_string(method);
  o.duration_s = s.duration_s;
  o.rtol = s.rtol;
  o.atol_m = s.atol_m;
  o.output_every_s = s.output_dt_s;
  o.release_tip_load = s.release_tip_load;
  o.max_iterations = s.max_iterations;
  o.alpha = s.alpha;
  if (s.steps) o.steps = *s.steps;
  o.elements = s.elements;
  o.order = s.order;
  o.rho_inf = s.rho_inf;
  return o;
}

method::DynamicOptions dynamic_options(const rod::RodModel& model, DynamicMethod method,
                                       const DynamicSettings& s) {
  if (s.rtol) {
    study::SimulationOptions so = adaptive_simulation(method, s);
    study::check_simulation_options(so, study::OptionNames::kPython);
    method::DynamicOptions o = study::dynamic_options(model, so);
    // The tightened Newton tolerances of the cross-check, as at fixed steps.
    if (auto* co = std::get_if<cosserat::DynamicsOptions>(&o)) co->tolerance = s.shooting_tolerance;
    if (auto* fo = std::get_if<beam_fe::DynamicsOptions>(&o)) fo->tolerance = s.fe_tolerance;
    return o;
  }
  if (method == DynamicMethod::kFe) return fe_options(s);
  cosserat::DynamicsOptions o;
  o.dt_s = s.dt_s;
  o.alpha = s.alpha;
  o.tolerance = s.shooting_tolerance;
  o.max_iterations = s.max_iterations;
  o.steps = s.steps ? *s.steps : cosserat::recommended_steps(model, o);
  return o;
}

}  // namespace

const char* to_string(DynamicMethod m) { return m == DynamicMethod::kShooting ? "cosserat" : "fe"; }

std::string fe_dynamics_unsupported(const rod::RodModel& model) {
  try {
    DynamicSettings s;
    s.elements = 1;
    beam_fe::BeamDynamics probe(model, fe_options(s));
  } catch (const DomainError& e) {
    return e.what();
  }
  return {};
}

DynamicRun run_dynamics(const rod::RodModel& model, DynamicMethod method,
                        const DynamicSettings& s) {
  const TimeGrid g = time_grid(s);
  const bool release = s.release_tip_load;
  const rod::LoadsAt loads = [&model, release](double t) {
    return method::loads_at(model, t, release);
  };
  DynamicRun run;
  run.method = method;
  const auto t0 = std::chrono::steady_clock::now();
  method::DynamicSolver dyn(model, dynamic_options(model, method, s));
  run.grid_steps = dyn.grid_size();
  const auto record = [&run](const method::DynamicSolver& d) {
    run.t_s.push_back(d.time_s());
    run.tip_W_m.push_back(d.tip_position_W_m());
    run.kinetic_J.push_back(d.kinetic_energy_J());
    run.potential_J.push_back(d.potential_energy_J());
  };
  const rod::TrajectoryOutcome o =
      s.rtol
          ? method::run_adaptive(dyn, loads, s.duration_s,
                                 study::adaptive_options(model, adaptive_simulation(method, s)),
                                 [&record](const method::DynamicSolver& d, double) { record(d); })
          : method::run(dyn, loads, g.steps, g.every, record);
  run.ok = o.ok;
  run.steps_done = o.steps_done;
  run.steps_rejected = o.steps_rejected + o.steps_failed;
  run.message = o.message;
  run.wall_s = seconds_since(t0);
  return run;
}

namespace {

/// Calls f(i, j) for every pair of samples of a and b at the same time (both increasing).
template <class F>
void for_shared_times(const DynamicRun& a, const DynamicRun& b, F f) {
  if (a.t_s.empty() || b.t_s.empty()) return;
  const double tol = kTimeMatch * std::max({1.0, a.t_s.back(), b.t_s.back()});
  std::size_t j = 0;
  for (std::size_t i = 0; i < a.t_s.size(); ++i) {
    while (j < b.t_s.size() && b.t_s[j] < a.t_s[i] - tol) ++j;
    if (j == b.t_s.size()) return;
    if (std::abs(b.t_s[j] - a.t_s[i]) <= tol) f(i, j);
  }
}

}  // namespace

TrajectoryDifference trajectory_difference(const DynamicRun& a, const DynamicRun& b) {
  TrajectoryDifference d;
  d.max_m = -1.0;
  for_shared_times(a, b, [&](std::size_t i, std::size_t j) {
    const double e = (a.tip_W_m[i] - b.tip_W_m[j]).norm();
    ++d.shared;
    // A NaN position makes the difference NaN (a gate on it then fails).
    if (!(e <= d.max_m)) {
      d.max_m = e;
      d.at_t_s = a.t_s[i];
    }
  });
  if (d.shared == 0) d.max_m = kNaN;
  return d;
}

DynamicRun extrapolate_in_time(const DynamicRun& coarse, const DynamicRun& fine) {
  DynamicRun out;
  out.method = fine.method;
  out.ok = coarse.ok && fine.ok;
  out.message = !coarse.ok ? coarse.message : fine.message;
  out.grid_steps = fine.grid_steps;
  out.wall_s = coarse.wall_s + fine.wall_s;
  for_shared_times(fine, coarse, [&](std::size_t i, std::size_t j) {
    out.t_s.push_back(fine.t_s[i]);
    out.tip_W_m.push_back(fine.tip_W_m[i] +
                          (fine.tip_W_m[i] - coarse.tip_W_m[j]) / kRichardsonDenominator);
    out.kinetic_J.push_back(fine.kinetic_J[i]);
    out.potential_J.push_back(fine.potential_J[i]);
  });
  return out;
}

std::string dynamic_csv(const DynamicRun& reference, const std::vector<DynamicRun>& others,
                        const std::vector<std::string>& labels) {
  if (labels.size() != others.size()) {
    throw std::invalid_argument("dynamic_csv: one label per run");
  }
  std::string out = "t_s,shooting_tip_x_m,shooting_tip_y_m,shooting_tip_z_m";
  for (const auto& l : labels) {
    out += fmt::format(",{0}_tip_x_m,{0}_tip_y_m,{0}_tip_z_m,{0}_diff_m", l);
  }
  out += ",shooting_kinetic_J,shooting_potential_J";
  for (const auto& l : labels) out += fmt::format(",{0}_kinetic_J,{0}_potential_J", l);
  out += '\n';
  // Index of each other run's sample at each reference time (-1: none).
  std::vector<std::vector<long long>> at(others.size(),
                                         std::vector<long long>(reference.t_s.size(), -1));
  for (std::size_t k = 0; k < others.size(); ++k) {
    for_shared_times(reference, others[k],
                     [&](std::size_t i, std::size_t j) { at[k][i] = static_cast<long long>(j); });
  }
  for (std::size_t i = 0; i < reference.t_s.size(); ++i) {
    const Eigen::Vector3d& p = reference.tip_W_m[i];
    out += fmt::format("{:.9g},{:.12e},{:.12e},{:.12e}", reference.t_s[i], p.x(), p.y(), p.z());
    for (std::size_t k = 0; k < others.size(); ++k) {
      if (at[k][i] < 0) {
        out += ",nan,nan,nan,nan";
        continue;
      }
      const Eigen::Vector3d& q = others[k].tip_W_m[static_cast<std::size_t>(at[k][i])];
      out += fmt::format(",{:.12e},{:.12e},{:.12e},{:.6e}", q.x(), q.y(), q.z(), (q - p).norm());
    }
    out += fmt::format(",{:.9e},{:.9e}", reference.kinetic_J[i], reference.potential_J[i]);
    for (std::size_t k = 0; k < others.size(); ++k) {
      if (at[k][i] < 0) {
        out += ",nan,nan";
        continue;
      }
      const auto j = static_cast<std::size_t>(at[k][i]);
      out += fmt::format(",{:.9e},{:.9e}", others[k].kinetic_J[j], others[k].potential_J[j]);
    }
    out += '\n';
  }
  return out;
}

}  // namespace tcasim::crosscheck
