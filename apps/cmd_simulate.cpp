// `tcasim simulate`: rod dynamics of one scenario over time (docs/scenario-format.md
// "Trajectory file"), by the shooting method (cosserat/dynamics.hpp) or the beam FE
// (beam_fe/dynamics.hpp, `--method fe`).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli_util.hpp"
#include "apps/commands.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "rod/result.hpp"
#include "rod/scenario.hpp"
#include "rod/trajectory.hpp"
#include "rod/vtk.hpp"
#include "study/simulation.hpp"

namespace tcasim::app {

namespace {

/// Exit code of a simulation whose time step failed (the rows before it are kept).
constexpr int kExitStepFailed = 4;

void write_pvd(const std::string& dir, const std::string& entries) {
  const std::string path = (std::filesystem::path(dir) / "trajectory.pvd").string();
  std::ofstream f(path);
  f << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <Collection>\n"
    << entries << "  </Collection>\n</VTKFile>\n";
  if (!f) throw InputError("--vtk-series", path, "could not be written");
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  struct Flags {
    std::string scenario, out, vtk_dir;
    // The options of study::simulate; the flags write into them directly.
    study::SimulationOptions o;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand(
      "simulate", "Rod dynamics from the static state at t = 0: a trajectory CSV over time");
  cmd->add_option("scenario", flags->scenario, "scenario file (tcasim.scenario/1)")->required();
  study::SimulationOptions& opts = flags->o;  // bound to the flags
  cmd->add_option("--duration-s", opts.duration_s, "simulated time T [s] (> 0)")->required();
  // Exactly one of the two time-step modes: fixed steps (--dt-s) or error-controlled ones
  // (--rtol, with --output-every-s).
  auto* dt_flag = cmd->add_option("--dt-s", opts.dt_s, "fixed time step [s] (> 0); or --rtol");
  auto* rtol_flag = cmd->add_option(
      "--rtol", opts.rtol,
      "adaptive time steps instead of --dt-s (fe only so far): relative tolerance in (0, 1) of "
      "each step's local error estimate, per rod length; steps are rejected and retried "
      "smaller, grown where the motion is smooth, and land on the output times and the jumps "
      "of the scenario's time profiles; the trajectory gets a dt_s column");
  cmd->add_option("--atol-m", opts.atol_m,
                  "with --rtol: absolute tolerance of the local error [m] (>= 0, default 0); "
                  "a step is accepted when its error <= atol + rtol L");
  cmd->add_option("--output-every-s", opts.output_every_s,
                  "with --rtol (required): a row every this many seconds, in (0, duration]");
  cmd->add_option("--method", opts.method,
                  "solver: cosserat (shooting, BDF-alpha) or fe (beam elements, Lie-group "
                  "generalized-alpha)");
  auto* alpha_flag = cmd->add_option(
      "--alpha", opts.alpha,
      "cosserat: BDF-alpha parameter in [-0.5, 0] (default -0.2; 0: BDF2, -0.5: trapezoidal)");
  auto* steps_flag =
      cmd->add_option("--steps", opts.steps,
                      fmt::format("cosserat: RK4 steps along s, in [1, {}] (default: enough for "
                                  "the time step, >= 20)",
                                  study::kMaxSteps))
          ->check(fits_64_bits());
  auto* elements_flag =
      cmd->add_option(
             "--elements", opts.elements,
             fmt::format("fe: number of elements, in [1, {}] (default 16)", study::kMaxElements))
          ->check(fits_64_bits());
  auto* order_flag = cmd->add_option("--order", opts.order, "fe: element order, 1 or 2 (default 2)")
                         ->check(fits_64_bits());
  auto* rho_inf_flag = cmd->add_option(
      "--rho-inf", opts.rho_inf,
      "fe: generalized-alpha spectral radius at infinite frequency in [0, 1] (default 0.9; "
      "1: no numerical dissipation)");
  cmd->add_option("--output-every", opts.output_every, "write every K-th time step (default 1)")
      ->check(fits_64_bits());
  cmd->add_option(
      "--viscosity-Pa-s", opts.viscosity_Pa_s,
      "Kelvin-Voigt viscosity of the body [Pa s], constant along s (default: the scenario's "
      "body.material.viscosity_Pa_s)");
  cmd->add_option("--tip-mass-kg", opts.tip_mass_kg,
                  "point mass at the tip [kg] (default: the scenario's tip_mass_kg)");
  cmd->add_option("--max-iterations", opts.max_iterations,
                  fmt::format("Newton iterations per time step, in [1, {}] (default 30)",
                              study::kMaxNewtonIterations))
      ->check(fits_64_bits());
  cmd->add_flag("--release-tip-load", opts.release_tip_load,
                "the scenario's tip load acts at t = 0 only (released at t = 0+: a released "
                "cantilever)");
  cmd->add_option("--out", flags->out, "trajectory CSV file")->required();
  cmd->add_option("--vtk-series", flags->vtk_dir,
                  "also write DIR/trajectory.pvd with one .vtp per output time (ParaView)");
  cmd->callback([=] {
    const Flags& f = *flags;
    const study::SimulationOptions& o = f.o;
    study::check_method(o.method, study::OptionNames::kFlags);
    // A flag of the other method is refused, not ignored.
    std::vector<study::GivenOption> given;
    for (const auto& [flag, key] :
         {std::pair{alpha_flag, "alpha"}, std::pair{steps_flag, "steps"},
          std::pair{elements_flag, "elements"}, std::pair{order_flag, "order"},
          std::pair{rho_inf_flag, "rho_inf"}}) {
      if (flag->count() > 0) given.push_back({key, flag->as<std::string>()});
    }
    study::refuse_other_method_options(o.method, given, study::OptionNames::kFlags);
    require_one_time_step_mode(dt_flag->count() > 0,
                               dt_flag->count() > 0 ? dt_flag->as<std::string>() : "",
                               rtol_flag->count() > 0);
    const bool adaptive = rtol_flag->count() > 0;
    const long long n_steps = study::check_simulation_options(o, study::OptionNames::kFlags);
    const rod::RodModel model = rod::read_scenario(f.scenario);

    Output out(f.out);
    std::ostream& os = out.stream();
    // The header with the first row (or the failure line): a run refused before it starts (the
    // shooting method with --rtol) writes nothing.
    bool header_written = false;
    const auto header = [&] {
      if (!header_written) rod::write_trajectory_header(os, model, adaptive);
      header_written = true;
    };
    std::string pvd;
    int frame = 0;
    study::SimulationHooks hooks;
    double row_t_s = 0.0;  // the time of the row a frame belongs to (on_row comes first)
    hooks.on_row = [&](const rod::TrajectoryRow& row) {
      header();
      rod::write_trajectory_row(os, row);
      row_t_s = row.t_s;
    };
    if (!f.vtk_dir.empty()) {
      std::filesystem::create_directories(f.vtk_dir);
      hooks.on_frame = [&](const rod::Result& r) {
        const std::string name = fmt::format("frame_{:06d}.vtp", frame++);
        rod::write_vtp(model, r, (std::filesystem::path(f.vtk_dir) / name).string());
        pvd += fmt::format("    <DataSet timestep=\"{:.9g}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                           row_t_s, name);
      };
    }
    ProgressReporter progress(stderr, "tcasim simulate", static_cast<std::size_t>(n_steps),
                              adaptive ? "output periods" : "steps");
    long long last_done = -1;
    hooks.on_step = [&progress, &last_done, adaptive](long long k, long long n) {
      // Adaptive: the outputs done, once each (many steps share one output period).
      if (adaptive && k != last_done) progress.update(static_cast<std::size_t>(k));
      if (!adaptive && n >= 1000) progress.update(static_cast<std::size_t>(k));
      last_done = k;
    };
    const rod::TrajectoryOutcome s = study::simulate(model, o, hooks, study::OptionNames::kFlags);
    header();
    if (!s.ok) os << "# " << s.message << '\n';
    out.commit();
    if (adaptive) {
      fmt::print(stderr,
                 "tcasim simulate: {} time steps accepted, {} rejected by the error test, {} "
                 "retried after a failed Newton iteration\n",
                 s.steps_done, s.steps_rejected, s.steps_failed);
    }
    if (!f.vtk_dir.empty()) write_pvd(f.vtk_dir, pvd);
    if (!s.ok) {
      fmt::print(stderr, "tcasim simulate: {}\n", s.message);
      throw CLI::RuntimeError(kExitStepFailed);
    }
  });
}

}  // namespace tcasim::app
