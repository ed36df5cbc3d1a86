#include <fmt/format.h>

#include <ostream>
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

}  // namespace

struct DynamicSolver::Impl {
  const rod::RodModel& model;
  std::variant<Shooting, Fe> solver;
};

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
  const StepSummary init = solver.initialize(loads_at(0.0));
  if (!init.converged) {
    out.status = init.status;
    out.message =
        fmt::format("static initial state did not converge ({}): {}", out.status, init.message);
    return out;
  }
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
