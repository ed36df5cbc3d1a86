// `tcasim simulate`: rod dynamics of one scenario over time (docs/scenario-format.md
// "Trajectory file"), by the shooting method (cosserat/dynamics.hpp) or the beam FE
// (beam_fe/dynamics.hpp, `--method fe`).
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli_util.hpp"
#include "apps/commands.hpp"
#include "beam_fe/dynamics.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "cosserat/dynamics.hpp"
#include "rod/loads.hpp"
#include "rod/result.hpp"
#include "rod/scenario.hpp"
#include "rod/trajectory.hpp"
#include "rod/vtk.hpp"

namespace tcasim::app {

namespace {

/// Exit code of a simulation whose time step failed (the rows before it are kept).
constexpr int kExitStepFailed = 4;
/// Time steps of one run: 1e8 steps are hours; beyond that the run only burns time.

/// One .vtp of the current state and its entry in the .pvd collection.
void write_vtk_frame(const rod::RodModel& model, const cosserat::RodDynamics& dyn,
                     const std::string& dir, int frame, std::string& pvd_entries) {
  rod::Result r;
  r.scenario = model.name;
  r.method = "cosserat";
  r.converged = true;
  const auto& grid = dyn.grid_states();
  const auto& grid_s = dyn.grid_s_m();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    r.centerline_s_m.push_back(grid_s[i]);
    r.centerline_p_W_m.push_back(grid[i].head<3>());
    r.centerline_R_WB.push_back(Eigen::Map<const Eigen::Matrix3d>(grid[i].data() + 3));
  }
  r.tip_position_W_m = dyn.tip_position_W_m();
  r.tip_R_WB = dyn.tip_rotation_W();
  const std::string name = fmt::format("frame_{:06d}.vtp", frame);
  rod::write_vtp(model, r, (std::filesystem::path(dir) / name).string());
  pvd_entries += fmt::format(
      "    <DataSet timestep=\"{:.9g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", dyn.time_s(), name);
}

void write_pvd(const std::string& dir, const std::string& entries) {
  const std::string path = (std::filesystem::path(dir) / "trajectory.pvd").string();
  std::ofstream f(path);
  f << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <Collection>\n"
    << entries << "  </Collection>\n</VTKFile>\n";
  if (!f) throw InputError("--vtk-series", path, "could not be written");
}

/// `--method fe`: the beam FE dynamics writes the same trajectory file.
void run_fe(const rod::RodModel& model, const beam_fe::DynamicsOptions& options,
            const beam_fe::LoadsAt& loads_at, long long n_steps, long long output_every,
            const std::string& out_path, const std::string& vtk_dir) {
  std::unique_ptr<beam_fe::BeamDynamics> dyn;
  try {
    dyn = std::make_unique<beam_fe::BeamDynamics>(model, options);
  } catch (const InputError& e) {
    if (e.key() == "dynamics.rho_inf") throw InputError("--rho-inf", e.value(), e.rule());
    if (e.key() == "elements" || e.key() == "order") {
      throw InputError("--" + e.key(), e.value(), e.rule());
    }
    throw;
  }
  std::string pvd;
  int frame = 0;
  if (!vtk_dir.empty()) std::filesystem::create_directories(vtk_dir);
  ProgressReporter progress(stderr, "tcasim simulate", static_cast<std::size_t>(n_steps), "steps");
  const auto after_row = [&](const beam_fe::BeamDynamics& d) {
    if (n_steps >= 1000) progress.update(static_cast<std::size_t>(d.time_s() / d.time_step_s()));
    if (vtk_dir.empty()) return;
    rod::Result r;
    r.scenario = model.name;
    r.method = "fe";
    r.converged = true;
    r.centerline_s_m = d.state().s_m;
    r.centerline_p_W_m = d.state().p_W_m;
    for (const auto& q : d.state().q_WB) r.centerline_R_WB.push_back(q.toRotationMatrix());
    r.tip_position_W_m = d.tip_position_W_m();
    r.tip_R_WB = d.tip_rotation_W();
    const std::string name = fmt::format("frame_{:06d}.vtp", frame++);
    rod::write_vtp(model, r, (std::filesystem::path(vtk_dir) / name).string());
    pvd += fmt::format("    <DataSet timestep=\"{:.9g}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                       d.time_s(), name);
  };
  Output out(out_path);
  const beam_fe::TrajectorySummary s = beam_fe::write_trajectory(
      *dyn, model, loads_at, n_steps, output_every, out.stream(), after_row);
  out.commit();
  if (!vtk_dir.empty()) write_pvd(vtk_dir, pvd);
  if (!s.ok) {
    fmt::print(stderr, "tcasim simulate: {}\n", s.message);
    throw CLI::RuntimeError(kExitStepFailed);
  }
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  struct Flags {
    std::string scenario, out, vtk_dir, method = "cosserat";
    double duration_s = 0.0, dt_s = 0.0, alpha = -0.2, viscosity = 0.0, tip_mass = 0.0;
    int output_every = 1, steps = 0, max_iterations = 30, elements = 16, order = 2;
    double rho_inf = 0.9;
    bool release_tip_load = false;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand(
      "simulate", "Rod dynamics from the static state at t = 0: a trajectory CSV over time");
  cmd->add_option("scenario", flags->scenario, "scenario file (tcasim.scenario/1)")->required();
  cmd->add_option("--duration-s", flags->duration_s, "simulated time T [s] (> 0)")->required();
  cmd->add_option("--dt-s", flags->dt_s, "time step [s] (> 0)")->required();
  cmd->add_option("--method", flags->method,
                  "solver: cosserat (shooting, BDF-alpha) or fe (beam elements, Lie-group "
                  "generalized-alpha)")
      ->check(CLI::IsMember({"cosserat", "fe"}));
  auto* alpha_flag = cmd->add_option(
      "--alpha", flags->alpha,
      "cosserat: BDF-alpha parameter in [-0.5, 0] (default -0.2; 0: BDF2, -0.5: trapezoidal)");
  auto* steps_flag =
      cmd->add_option("--steps", flags->steps,
                      "cosserat: RK4 steps along s (default: enough for the time step, >= 20)");
  auto* elements_flag =
      cmd->add_option("--elements", flags->elements, "fe: number of elements (default 16)");
  auto* order_flag =
      cmd->add_option("--order", flags->order, "fe: element order, 1 or 2 (default 2)");
  auto* rho_inf_flag = cmd->add_option(
      "--rho-inf", flags->rho_inf,
      "fe: generalized-alpha spectral radius at infinite frequency in [0, 1] (default 0.9; "
      "1: no numerical dissipation)");
  cmd->add_option("--output-every", flags->output_every, "write every K-th time step (default 1)");
  auto* viscosity_flag = cmd->add_option(
      "--viscosity-Pa-s", flags->viscosity,
      "Kelvin-Voigt viscosity of the body [Pa s], constant along s (default: the scenario's "
      "body.material.viscosity_Pa_s)");
  auto* tip_mass_flag =
      cmd->add_option("--tip-mass-kg", flags->tip_mass,
                      "point mass at the tip [kg] (default: the scenario's tip_mass_kg)");
  cmd->add_option("--max-iterations", flags->max_iterations,
                  "Newton iterations per time step (default 30)");
  cmd->add_flag("--release-tip-load", flags->release_tip_load,
                "the scenario's tip load acts at t = 0 only (released at t = 0+: a released "
                "cantilever)");
  cmd->add_option("--out", flags->out, "trajectory CSV file")->required();
  cmd->add_option("--vtk-series", flags->vtk_dir,
                  "also write DIR/trajectory.pvd with one .vtp per output time (ParaView)");
  cmd->callback([=] {
    const Flags& f = *flags;
    // A flag of the other method is refused, not ignored.
    const bool fe = f.method == "fe";
    for (const CLI::Option* o : {alpha_flag, steps_flag, elements_flag, order_flag, rho_inf_flag}) {
      const bool fe_flag = o == elements_flag || o == order_flag || o == rho_inf_flag;
      if (o->count() > 0 && fe_flag != fe) {
        throw InputError(o->get_name(), o->as<std::string>(),
                         fe_flag ? "applies to --method fe only (cosserat: --steps, --alpha)"
                                 : "applies to --method cosserat only (fe: --elements, --order, "
                                   "--rho-inf)");
      }
    }
    const long long n_steps_real = require_time_flags(f.duration_s, f.dt_s, f.alpha);
    require_count(f.output_every, "--output-every", 1, kMaxTimeSteps);
    if (f.steps != 0) require_count(f.steps, "--steps", 1, kMaxSteps);
    require(std::isfinite(f.viscosity) && f.viscosity >= 0.0, "--viscosity-Pa-s", f.viscosity,
            "must be >= 0");
    require(std::isfinite(f.tip_mass) && f.tip_mass >= 0.0, "--tip-mass-kg", f.tip_mass,
            "must be >= 0");
    const rod::RodModel model = rod::read_scenario(f.scenario);
    // The loads over time: the scenario's time profiles (tensions, temperatures, tip wrench)
    // at t; the static state at t = 0 takes them at t = 0 (docs/scenario-format.md "Time
    // profiles"). An electric drive's temperatures are the solver's thermal states.
    const bool release = f.release_tip_load;
    const cosserat::LoadsAt loads_at = [&model, release](double t) {
      rod::Loads l = t > 0.0 ? rod::Loads::at_time(model, t) : rod::Loads::from_model(model);
      if (release && t > 0.0) {
        l.tip_force_W_N.setZero();
        l.tip_moment_W_Nm.setZero();
      }
      return l;
    };
    require_count(f.max_iterations, "--max-iterations", 1, 1000);
    if (fe) {
      beam_fe::DynamicsOptions fo;
      fo.elements = f.elements;
      fo.order = f.order;
      fo.dt_s = f.dt_s;
      fo.rho_inf = f.rho_inf;
      fo.max_iterations = f.max_iterations;
      // The flag overrides the scenario's viscosity (a constant or a profile along s).
      if (viscosity_flag->count() > 0) fo.viscosity_Pa_s = f.viscosity;
      fo.tip_mass_kg = tip_mass_flag->count() > 0 ? f.tip_mass : model.tip_mass_kg;
      run_fe(model, fo, loads_at, n_steps_real, f.output_every, f.out,
             f.vtk_dir);
      return;
    }
    cosserat::DynamicsOptions o;
    o.dt_s = f.dt_s;
    o.alpha = f.alpha;
    o.steps = f.steps != 0 ? f.steps : cosserat::recommended_steps(model, o);
    // The flags override the scenario's keys only when given.
    if (viscosity_flag->count() > 0) o.viscosity_Pa_s = f.viscosity;
    if (tip_mass_flag->count() > 0) o.tip_mass_kg = f.tip_mass;
    o.max_iterations = f.max_iterations;
    std::unique_ptr<cosserat::RodDynamics> dyn_ptr;
    try {
      dyn_ptr = std::make_unique<cosserat::RodDynamics>(model, o);
    } catch (const InputError& e) {
      if (e.key() == "dynamics.steps") throw InputError("--steps", e.value(), e.rule());
      throw;
    }
    cosserat::RodDynamics& dyn = *dyn_ptr;

    Output out(f.out);
    std::ostream& os = out.stream();
    rod::write_trajectory_header(os, model);
    auto write_row = [&] {
      rod::write_trajectory_row(os, dyn.time_s(), dyn.tip_position_W_m(), dyn.kinetic_energy_J(),
                                dyn.tensions_N(), dyn.elongations_m(),
                                dyn.segment_temperatures_K(), dyn.probe_positions_W_m());
    };
    std::string pvd;
    int frame = 0;
    if (!f.vtk_dir.empty()) std::filesystem::create_directories(f.vtk_dir);

    const cosserat::DynamicsSummary init = dyn.initialize(loads_at(0.0));
    if (!init.converged()) {
      os << "# static initial state did not converge (" << cosserat::to_string(init.status)
         << "): " << init.message << '\n';
      out.commit();
      fmt::print(stderr, "tcasim simulate: the static state at t = 0 did not converge: {}\n",
                 init.message);
      throw CLI::RuntimeError(kExitStepFailed);
    }
    write_row();
    if (!f.vtk_dir.empty()) write_vtk_frame(model, dyn, f.vtk_dir, frame++, pvd);
    const long long n_steps = n_steps_real;
    ProgressReporter progress(stderr, "tcasim simulate", static_cast<std::size_t>(n_steps),
                              "steps");
    for (long long k = 1; k <= n_steps; ++k) {
      const double t_new = k * f.dt_s;
      const cosserat::DynamicsSummary s = dyn.step(loads_at(t_new));
      if (!s.converged()) {
        os << fmt::format("# time step to t = {:.9g} s failed ({}): {}\n", t_new,
                          cosserat::to_string(s.status), s.message);
        out.commit();
        if (!f.vtk_dir.empty()) write_pvd(f.vtk_dir, pvd);
        fmt::print(stderr, "tcasim simulate: time step to t = {:.9g} s failed: {}\n", t_new,
                   s.message);
        throw CLI::RuntimeError(kExitStepFailed);
      }
      if (k % f.output_every == 0 || k == n_steps) {
        write_row();
        if (!f.vtk_dir.empty()) write_vtk_frame(model, dyn, f.vtk_dir, frame++, pvd);
      }
      if (n_steps >= 1000) progress.update(static_cast<std::size_t>(k));
    }
    out.commit();
    if (!f.vtk_dir.empty()) write_pvd(f.vtk_dir, pvd);
  });
}

}  // namespace tcasim::app
