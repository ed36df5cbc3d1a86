#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <type_traits>
#include <utility>

#include "common/error.hpp"
#include "method/dynamics.hpp"

namespace tcasim::method {

namespace {

/// The shooting method's dynamics and what only it knows (its grid and rows).
struct Shooting {
  cosserat::RodDynamics dyn;
  Shooting(const rod::RodModel& model, const cosserat::DynamicsOptions& options)
      : dyn(model, options) {}
  rod::TrajectoryRow row() const { return rod::trajectory_row_of(dyn, dyn.probe_positions_W_m()); }
  void shape(rod::Result& r) const {
    const auto& grid = dyn.grid_states();
    const auto& grid_s = dyn.grid_s_m();
    for (std::size_t i = 0; i < grid.size(); ++i) {
      r.centerline_s_m.push_back(grid_s[i]);
      r.centerline_p_W_m.push_back(grid[i].head<3>());
      r.centerline_R_WB.push_back(Eigen::Map<const Eigen::Matrix3d>(grid[i].data() + 3));
    }
  }
  int grid_size() const { return dyn.steps(); }
};

/// The beam FE's dynamics.
struct Fe {
  beam_fe::BeamDynamics dyn;
  Fe(const rod::RodModel& model, const beam_fe::DynamicsOptions& options) : dyn(model, options) {}
  rod::TrajectoryRow row() const { return beam_fe::trajectory_row(dyn); }
  void shape(rod::Result& r) const {
    r.centerline_s_m = dyn.state().s_m;
    r.centerline_p_W_m = dyn.state().p_W_m;
    for (const auto& q : dyn.state().q_WB) r.centerline_R_WB.push_back(q.toRotationMatrix());
  }
  int grid_size() const { return dyn.discretization().element_count(); }
};

template <class Summary>
StepSummary summary_of(const Summary& s) {
  StepSummary out;
  out.converged = s.converged();
  out.status = to_string(s.status);
  out.iterations = s.iterations;
  out.message = s.message;
  return out;
}

/// Calls f(method) with the method's dynamics for the adaptive-step interface
/// (set_time_step, local_error_m, error_order, undo_step).
/// The step-size calls of either method (cosserat::RodDynamics and beam_fe::BeamDynamics have
/// the same four: set_time_step, local_error_m, error_order, undo_step).
template <class Variant, class F>
auto with_adaptive_method(Variant& solver, F&& f) {
  return std::visit([&](auto& s) { return f(s.dyn); }, solver);
}

/// The static state at t = 0 of both time loops; false with the outcome's status and message.
bool initialize(DynamicSolver& solver, const rod::LoadsAt& loads_at, rod::TrajectoryOutcome& out) {
  const StepSummary init = solver.initialize(loads_at(0.0));
  if (init.converged) return true;
  out.status = init.status;
  out.message =
      fmt::format("static initial state did not converge ({}): {}", out.status, init.message);
  return false;
}

}  // namespace

struct DynamicSolver::Impl {
  const rod::RodModel& model;
  std::variant<Shooting, Fe> solver;
};

void DynamicSolver::set_time_step(double dt_s) {
  with_adaptive_method(impl_->solver, [&](auto& dyn) { dyn.set_time_step(dt_s); });
}

double DynamicSolver::local_error_m() const {
  return with_adaptive_method(impl_->solver, [](const auto& dyn) { return dyn.local_error_m(); });
}

int DynamicSolver::error_order() const {
  return with_adaptive_method(impl_->solver, [](const auto& dyn) { return dyn.error_order(); });
}

double DynamicSolver::min_time_step_s() const {
  return with_adaptive_method(impl_->solver, [](const auto& dyn) { return dyn.min_time_step_s(); });
}

void DynamicSolver::undo_step() {
  with_adaptive_method(impl_->solver, [](auto& dyn) { dyn.undo_step(); });
}

double DynamicSolver::rod_length_m() const { return impl_->model.length_m; }

const char* name(const DynamicOptions& options) {
  return std::holds_alternative<cosserat::DynamicsOptions>(options) ? "cosserat" : "fe";
}

DynamicSolver::DynamicSolver(const rod::RodModel& model, const DynamicOptions& options) {
  // Contact in dynamics (with friction and impacts) is not modelled yet: refuse rather than
  // let the rod pass through what it would touch.
  if (!model.obstacles.empty()) {
    throw DomainError(fmt::format(
        "rod dynamics: obstacles are not supported in dynamics yet (the scenario has {}, "
        "first \"{}\"); solve the statics with tcasim solve or sweep",
        model.obstacles.size(), model.obstacles.front().name));
  }
  if (const auto* o = std::get_if<cosserat::DynamicsOptions>(&options)) {
    impl_.reset(
        new Impl{model, std::variant<Shooting, Fe>(std::in_place_type<Shooting>, model, *o)});
  } else {
    impl_.reset(
        new Impl{model, std::variant<Shooting, Fe>(std::in_place_type<Fe>, model,
                                                   std::get<beam_fe::DynamicsOptions>(options))});
  }
}

DynamicSolver::~DynamicSolver() = default;

StepSummary DynamicSolver::initialize(const rod::Loads& loads) {
  return std::visit([&](auto& s) { return summary_of(s.dyn.initialize(loads)); }, impl_->solver);
}

StepSummary DynamicSolver::step(const rod::Loads& loads) {
  return std::visit([&](auto& s) { return summary_of(s.dyn.step(loads)); }, impl_->solver);
}

double DynamicSolver::time_s() const {
  return std::visit([](const auto& s) { return s.dyn.time_s(); }, impl_->solver);
}

double DynamicSolver::time_step_s() const {
  return std::visit([](const auto& s) { return s.dyn.time_step_s(); }, impl_->solver);
}

Eigen::Vector3d DynamicSolver::tip_position_W_m() const {
  return std::visit([](const auto& s) { return s.dyn.tip_position_W_m(); }, impl_->solver);
}

double DynamicSolver::kinetic_energy_J() const {
  return std::visit([](const auto& s) { return s.dyn.kinetic_energy_J(); }, impl_->solver);
}

double DynamicSolver::potential_energy_J() const {
  return std::visit([](const auto& s) { return s.dyn.potential_energy_J(); }, impl_->solver);
}

rod::TrajectoryRow DynamicSolver::row() const {
  return std::visit([](const auto& s) { return s.row(); }, impl_->solver);
}

rod::Result DynamicSolver::frame() const {
  rod::Result r;
  r.scenario = impl_->model.name;
  r.method = method();
  r.converged = true;
  std::visit(
      [&](const auto& s) {
        s.shape(r);
        r.tip_position_W_m = s.dyn.tip_position_W_m();
        r.tip_R_WB = s.dyn.tip_rotation_W();
      },
      impl_->solver);
  return r;
}

int DynamicSolver::grid_size() const {
  return std::visit([](const auto& s) { return s.grid_size(); }, impl_->solver);
}

const char* DynamicSolver::method() const {
  return std::holds_alternative<Shooting>(impl_->solver) ? "cosserat" : "fe";
}

rod::Loads loads_at(const rod::RodModel& model, double t_s, bool release_tip_load) {
  rod::Loads l = t_s > 0.0 ? rod::Loads::at_time(model, t_s) : rod::Loads::from_model(model);
  if (release_tip_load && t_s > 0.0) {
    l.tip_force_W_N.setZero();
    l.tip_moment_W_Nm.setZero();
  }
  return l;
}

rod::TrajectoryOutcome run(DynamicSolver& solver, const rod::LoadsAt& loads_at, long long steps,
                           long long output_every,
                           const std::function<void(const DynamicSolver&)>& on_output,
                           const std::function<void(long long)>& on_step) {
  rod::TrajectoryOutcome out;
  if (!initialize(solver, loads_at, out)) return out;
  on_output(solver);
  const double dt_s = solver.time_step_s();
  for (long long k = 1; k <= steps; ++k) {
    const double t_new = static_cast<double>(k) * dt_s;
    const StepSummary s = solver.step(loads_at(t_new));
    if (!s.converged) {
      out.status = s.status;
      out.message =
          fmt::format("time step to t = {:.9g} s failed ({}): {}", t_new, out.status, s.message);
      return out;
    }
    out.steps_done = k;
    if (k % output_every == 0 || k == steps) on_output(solver);
    if (on_step) on_step(k);
  }
  out.ok = true;
  return out;
}

std::vector<double> time_breakpoints(const rod::RodModel& model, double t_end_s) {
  std::vector<double> t;
  const auto add = [&](const TimeProfile& p) {
    if (p.is_constant()) return;
    for (const double b : p.breakpoints(0.0, t_end_s))
      if (b < t_end_s) t.push_back(b);
  };
  for (const rod::Actuator& a : model.actuators) {
    add(a.drive.tension_profile_N);
    for (const TimeProfile& p : a.drive.temperature_profiles_K) add(p);
    for (const rod::ElectricSegment& e : a.drive.electric) add(e.value);
  }
  for (const TimeProfile& p : model.tip_force_profile_W_N) add(p);
  for (const TimeProfile& p : model.tip_moment_profile_W_Nm) add(p);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

rod::TrajectoryOutcome run_adaptive(
    DynamicSolver& solver, const rod::LoadsAt& loads_at, double duration_s,
    const AdaptiveOptions& o,
    const std::function<void(const DynamicSolver&, double dt_s)>& on_output,
    const std::function<void(double t_s)>& on_step) {
  require(std::isfinite(duration_s) && duration_s > 0.0, "duration_s", duration_s, "must be > 0");
  require(o.rtol > 0.0 && o.rtol < 1.0, "rtol", o.rtol, "must be in (0, 1)");
  require(std::isfinite(o.atol_m) && o.atol_m >= 0.0, "atol_m", o.atol_m, "must be >= 0");
  require(std::isfinite(o.output_every_s) && o.output_every_s > 0.0, "output_every_s",
          o.output_every_s, "must be > 0");
  require(std::isfinite(o.dt_min_s) && o.dt_min_s > 0.0, "dt_min_s", o.dt_min_s, "must be > 0");
  require(o.dt_max_s >= o.dt_min_s, "dt_max_s", o.dt_max_s, "must be >= dt_min_s");
  require(std::isfinite(o.dt_initial_s) && o.dt_initial_s > 0.0, "dt_initial_s", o.dt_initial_s,
          "must be > 0");
  const int p = solver.error_order();
  // The shooting method's grid along s resolves steps down to its min_time_step_s: no step,
  // first or restart, is smaller (a step landing on an output time or a load jump may be, down
  // to the grid's floor: below it the run ends with a message).
  const double grid_floor = solver.min_time_step_s();
  const double dt_floor = std::max(o.dt_min_s, grid_floor);
  const double dt_start = std::max(o.dt_initial_s, dt_floor);
  const std::string floor_text =
      dt_floor > o.dt_min_s
          ? fmt::format(
                "the smallest step the shooting grid along s resolves, {:.3e} s (more "
                "steps along s allow smaller ones)",
                dt_floor)
          : fmt::format("dt_min_s = {:.3e} s", o.dt_min_s);
  rod::TrajectoryOutcome out;
  if (!initialize(solver, loads_at, out)) return out;
  on_output(solver, 0.0);

  // The times the steps land on: outputs (k T_out, and the end) and the profiles' jumps. A time
  // within a relative 1e-9 of a larger one is dropped (no sliver step between them).
  struct Event {
    double t;
    bool output;
    bool breakpoint;
  };
  std::vector<Event> events;
  const double n_out = std::floor(duration_s / o.output_every_s * (1.0 + 1e-12));
  for (double k = 1; k <= n_out; ++k) events.push_back({k * o.output_every_s, true, false});
  events.push_back({duration_s, true, false});
  for (const double b : o.breakpoints_s)
    if (b > 0.0 && b < duration_s) events.push_back({b, false, true});
  std::sort(events.begin(), events.end(),
            [](const Event& a, const Event& b) { return a.t < b.t || (a.t == b.t && a.output); });
  std::vector<Event> merged;
  for (const Event& e : events) {
    if (!merged.empty() && e.t - merged.back().t <= 1e-9 * e.t) {
      merged.back().output = merged.back().output || e.output;
      merged.back().breakpoint = merged.back().breakpoint || e.breakpoint;
      merged.back().t = std::max(merged.back().t, e.t);
      continue;
    }
    merged.push_back(e);
  }
  merged.back().t = duration_s;

  // err = local error / (atol + rtol L); new size dt clamp(0.9 err^(-1/(p+1)), 0.2, 5)
  // ([Hairer1993] II.4, the elementary controller).
  const double tol_m = o.atol_m + o.rtol * solver.rod_length_m();
  constexpr double kSafety = 0.9, kMinFactor = 0.2, kMaxFactor = 5.0, kNewtonCut = 0.25;
  const auto factor_of = [&](double err) {
    if (!(err > 0.0)) return kMaxFactor;
    return std::clamp(kSafety * std::pow(err, -1.0 / (p + 1)), kMinFactor, kMaxFactor);
  };
  double t = 0.0;
  double dt = std::min(dt_start, std::max(o.dt_max_s, dt_floor));
  std::size_t next = 0;
  bool after_rejection = false;  // no growth right after a rejection ([Hairer1993] II.4)
  // At t = 0 and after a breakpoint the loads jump while the methods' acceleration history is
  // that of before (the generalized-alpha a_n, BDF-alpha's history): an error of the first
  // steps' size in the velocities, which the position error estimate does not see and which
  // the history carries on, decaying by its spurious root per step (-0.73 at rho_inf 0.9). So
  // the run restarts there from dt_initial_s, growing at most kRestartGrowth per step for
  // kRestartSteps steps (docs/conventions.md "Variable time steps").
  constexpr double kRestartGrowth = 1.5;
  constexpr int kRestartSteps = 20;
  int since_restart = 0;
  const auto fail = [&](double t_new, std::string status, std::string message) {
    out.status = std::move(status);
    out.message =
        fmt::format("time step to t = {:.9g} s failed ({}): {}", t_new, out.status, message);
    return out;
  };
  while (next < merged.size()) {
    const double target = merged[next].t;
    const double remaining = target - t;
    // Land on the target: the whole remainder when the step reaches it, half of it when less
    // than two steps remain (no sliver step before the target).
    bool landing = remaining <= dt;
    double h = landing ? remaining : remaining < 2.0 * dt ? 0.5 * remaining : dt;
    // Not below the floor where the remainder allows: then the whole remainder at once (a
    // landing like any other).
    if (!landing && h < dt_floor && remaining <= 2.0 * dt_floor) {
      landing = true;
      h = remaining;
    }
    const double t_new = landing ? target : t + h;
    if (h < dt_floor && !landing) {
      return fail(t_new, "dt-min",
                  fmt::format("the step size {:.3e} s is below {}", h, floor_text));
    }
    if (h < grid_floor) {
      return fail(t_new, "dt-min",
                  fmt::format("the step {:.3e} s to the next output or load jump is below {} "
                              "(or move output times and profile jumps farther apart)",
                              h, floor_text));
    }
    if (out.steps_done + out.steps_rejected + out.steps_failed >= o.max_steps) {
      return fail(t_new, "max-steps", fmt::format("{} steps taken", o.max_steps));
    }
    solver.set_time_step(h);
    const StepSummary s = solver.step(loads_at(t_new));
    if (!s.converged) {
      solver.undo_step();
      ++out.steps_failed;
      dt = kNewtonCut * h;
      if (dt < dt_floor) {
        return fail(t_new, s.status,
                    fmt::format("{} (step size {:.3e} s, the next {:.3e} s < {})", s.message, h, dt,
                                floor_text));
      }
      continue;
    }
    const double local_m = solver.local_error_m();
    const double err = local_m / tol_m;
    double factor = after_rejection ? std::min(factor_of(err), 1.0) : factor_of(err);
    if (since_restart < kRestartSteps) factor = std::min(factor, kRestartGrowth);
    after_rejection = !(err <= 1.0);
    if (!(err <= 1.0)) {
      solver.undo_step();
      ++out.steps_rejected;
      dt = h * std::min(factor, kSafety);
      if (dt < dt_floor) {
        if (h > dt_floor) {
          dt = dt_floor;  // one more try at the floor
          continue;
        }
        return fail(t_new, "dt-min",
                    fmt::format("error estimate {:.3e} m above the tolerance {:.3e} m at step size "
                                "{:.3e} s; the next {:.3e} s < {}",
                                local_m, tol_m, h, dt, floor_text));
      }
      continue;
    }
    t = t_new;
    ++out.steps_done;
    // A step shortened to land keeps the proposal for the next one, unless its own error asks
    // for less.
    const bool shortened = h < dt;
    dt = std::min(shortened ? std::max(dt, h * factor) : h * factor, o.dt_max_s);
    if (shortened && factor < 1.0) dt = std::min(dt, h * factor);
    dt = std::max(dt, dt_floor);
    if (on_step) on_step(t);
    ++since_restart;
    if (landing) {
      if (merged[next].output) on_output(solver, h);
      if (!merged[next].output || merged[next].breakpoint) {
        since_restart = 0;
        dt = std::min(dt, dt_start);
      }
      ++next;
    }
  }
  out.ok = true;
  return out;
}

rod::TrajectoryOutcome write_trajectory(DynamicSolver& solver, const rod::RodModel& model,
                                        const rod::LoadsAt& loads_at, long long steps,
                                        long long output_every, std::ostream& os) {
  rod::write_trajectory_header(os, model);
  const rod::TrajectoryOutcome o =
      run(solver, loads_at, steps, output_every,
          [&](const DynamicSolver& s) { rod::write_trajectory_row(os, s.row()); });
  if (!o.ok) os << "# " << o.message << '\n';
  return o;
}

}  // namespace tcasim::method
