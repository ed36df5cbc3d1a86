// `tcasim solve` and `tcasim sweep`: forward kinetostatics of one scenario.
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli_util.hpp"
#include "apps/commands.hpp"
#include "beam_fe/beam_fe.hpp"
#include "common/error.hpp"
#include "common/parallel.hpp"
#include "common/progress.hpp"
#include "common/units.hpp"
#include "cosserat/shooting.hpp"
#include "rod/loads.hpp"
#include "rod/result.hpp"
#include "rod/scenario.hpp"
#include "rod/vtk.hpp"
#include "study/options.hpp"
#include "study/sweep.hpp"

namespace tcasim::app {

namespace {

/// Exit code of a solve that ran but did not converge (the result file is still written).
constexpr int kExitNotConverged = 4;

using study::OptionNames;

/// The flags of the shooting integrator (absent when not given).
void add_integrator_flags(CLI::App* cmd, study::ShootingChoice& f) {
  auto* steps =
      cmd->add_option(
             "--steps", f.steps,
             fmt::format("cosserat: fixed steps of --scheme (even, in [2, {}]; default 100)",
                         study::kMaxSteps))
          ->check(fits_64_bits());
  auto* scheme = cmd->add_option("--scheme", f.scheme,
                                 "cosserat: fixed-step scheme, rk4 (default, the paper's), rk6 or "
                                 "rk8 (sixth and eighth order: far fewer steps for the same "
                                 "error)");
  auto* rtol = cmd->add_option(
      "--rtol", f.rtol,
      "cosserat: use SUNDIALS CVODE with this relative tolerance, in (0, 1) (default: fixed "
      "steps)");
  steps->excludes(rtol);
  scheme->excludes(rtol);
  cmd->add_flag("--no-planar", f.no_planar,
                "cosserat: solve a planar problem as a 3-D one (the same discretization, about "
                "twice the time; for cross-checks of the planar reduction)");
}

void add_fe_flags(CLI::App* cmd, study::FeChoice& f) {
  cmd->add_option(
         "--elements", f.elements,
         fmt::format("fe: number of elements (in [1, {}]; default 16)", study::kMaxElements))
      ->check(fits_64_bits());
  cmd->add_option("--order", f.order, "fe: Lagrange order of the elements, 1 or 2 (default 2)")
      ->check(fits_64_bits());
  cmd->add_option("--integration", f.integration,
                  "fe: Gauss rule, reduced (default, no locking) or full");
  cmd->add_option("--linear-solver", f.linear_solver, "fe: klu (default), umfpack or sparselu");
}

}  // namespace

void add_solve_command(CLI::App& app) {
  struct Flags {
    std::string scenario, method = "cosserat", out, vtk, shape_csv;
    study::ShootingChoice integrator;
    study::FeChoice fe;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand(
      "solve", "Forward kinetostatics: solve one scenario and write a result file");
  cmd->add_option("scenario", flags->scenario, "scenario file (tcasim.scenario/1)")->required();
  cmd->add_option("--method", flags->method,
                  "solver: cosserat (shooting, default) or fe (geometrically exact beam elements)");
  add_integrator_flags(cmd, flags->integrator);
  add_fe_flags(cmd, flags->fe);
  cmd->add_option("--out", flags->out, "result file (default: stdout)");
  cmd->add_option(
      "--vtk", flags->vtk,
      "also write the deformed centerline and actuator paths as VTK PolyData (FILE.vtp, ParaView)");
  cmd->add_option(
      "--shape-csv", flags->shape_csv,
      "also write the centerline and actuator paths as CSV (curve,actuator_id,s_m,x_m,y_m,z_m)");
  cmd->callback([flags] {
    study::check_method(flags->method, OptionNames::kFlags);
    const rod::RodModel model = rod::read_scenario(flags->scenario);
    const rod::Result result = method::solve(
        model,
        study::static_options(flags->method, flags->integrator, flags->fe, OptionNames::kFlags));
    rod::write_result(result, flags->out);
    if (!flags->vtk.empty()) rod::write_vtp(model, result, flags->vtk);
    if (!flags->shape_csv.empty()) rod::write_shape_csv(model, result, flags->shape_csv);
    if (!result.converged) {
      fmt::print(stderr, "tcasim solve: not converged: {}\n", result.message);
      throw CLI::RuntimeError(kExitNotConverged);
    }
  });
}

namespace {

using study::kDefaultSweepChunk;

/// One CSV row of a sweep point (the columns of the header in add_sweep_command); n_probes,
/// n_obstacles: the model's probe and obstacle counts.
std::string sweep_row(double value, const rod::Result& r, std::size_t n_probes,
                      std::size_t n_obstacles) {
  std::string row =
      fmt::format("{},{},{},{},{:.12e},{:.12e},{:.12e},{}", value, r.converged ? 1 : 0,
                  r.iterations, r.residual ? fmt::format("{:.6e}", *r.residual) : std::string(),
                  r.tip_position_W_m.x(), r.tip_position_W_m.y(), r.tip_position_W_m.z(),
                  r.bending_radius_m ? fmt::format("{:.12e}", *r.bending_radius_m) : std::string());
  for (const auto& a : r.actuators) {
    row += fmt::format(",{:.12e},{:.12e}", a.tension_N, a.elongation_m);
    if (a.is_tca) row += fmt::format(",{},{:.12e}", a.coils_closed ? 1 : 0, a.contact_force_N);
    for (const auto& seg : a.segments) {
      row +=
          fmt::format(",{},{:.12e}", seg.second.coils_closed ? 1 : 0, seg.second.contact_force_N);
    }
  }
  // Probes: the header's columns whether or not this point has a solution (empty cells then).
  for (std::size_t i = 0; i < n_probes; ++i) {
    if (i < r.probes.size()) {
      const Eigen::Vector3d& p = r.probes[i].position_W_m;
      row += fmt::format(",{:.12e},{:.12e},{:.12e}", p.x(), p.y(), p.z());
    } else {
      row += ",,,";
    }
  }
  // Obstacles: the resultant on the rod and whether it touches (empty cells without a result).
  for (std::size_t i = 0; i < n_obstacles; ++i) {
    if (i < r.contacts.size()) {
      const Eigen::Vector3d& f = r.contacts[i].force_W_N;
      row += fmt::format(",{:.12e},{:.12e},{:.12e},{}", f.x(), f.y(), f.z(),
                         r.contacts[i].in_contact() ? 1 : 0);
    } else {
      row += ",,,,";
    }
  }
  row += '\n';
  return row;
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  struct Flags {
    std::string scenario, actuator, temperatures, tensions, out, method = "cosserat", shard;
    long long jobs = 1;
    long long chunk = kDefaultSweepChunk;
    study::ShootingChoice integrator;
    study::FeChoice fe;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand("sweep",
                                 "Solve a scenario over a range of one actuator's temperature or "
                                 "tension (warm-started); CSV out");
  cmd->add_option("scenario", flags->scenario, "scenario file (tcasim.scenario/1)")->required();
  cmd->add_option("--actuator", flags->actuator, "name of the actuator to sweep")->required();
  auto* temps = cmd->add_option("--temperatures-degC", flags->temperatures,
                                "TCA temperatures START:STOP:STEP [degC] (every segment)");
  auto* tens = cmd->add_option("--tensions-N", flags->tensions,
                               "tensions START:STOP:STEP [N] (tension drive)");
  temps->excludes(tens);
  cmd->add_option("--method", flags->method,
                  "solver: cosserat (shooting, default) or fe (geometrically exact beam elements); "
                  "both warm-start each point from the previous one of its chunk");
  add_integrator_flags(cmd, flags->integrator);
  add_fe_flags(cmd, flags->fe);
  cmd->add_option("--jobs", flags->jobs,
                  fmt::format("threads solving chunks in parallel (1 to {}; default 1); the CSV "
                              "is the same, bit for bit, for every value",
                              kMaxJobs))
      ->check(fits_64_bits());
  cmd->add_option("--chunk", flags->chunk,
                  fmt::format("points per chunk (1 to {}; default {}): each chunk starts cold "
                              "and warm-starts its points in order; the unit of --jobs and "
                              "--shard",
                              study::kMaxSweepChunk, kDefaultSweepChunk))
      ->check(fits_64_bits());
  cmd->add_option("--shard", flags->shard,
                  "I/N: write only part I (0 to N-1) of N contiguous parts (whole chunks), with "
                  "the CSV header; the parts' rows in order are the full sweep's (job arrays)");
  cmd->add_option("--out", flags->out, "CSV file (default: stdout)");
  cmd->callback([flags] {
    study::check_method(flags->method, OptionNames::kFlags);
    study::check_sweep_jobs(flags->jobs, flags->chunk, OptionNames::kFlags);
    const Shard shard = flags->shard.empty() ? Shard{} : parse_shard(flags->shard, "--shard");
    const rod::RodModel model = rod::read_scenario(flags->scenario);
    std::size_t index = model.actuators.size();
    for (std::size_t i = 0; i < model.actuators.size(); ++i) {
      if (model.actuators[i].name == flags->actuator) index = i;
    }
    if (index == model.actuators.size()) {
      std::string names;
      for (const auto& a : model.actuators) names += (names.empty() ? "" : ", ") + a.name;
      throw InputError("--actuator", flags->actuator,
                       "names no actuator of the scenario (it has: " + names + ")");
    }
    const rod::Actuator& act = model.actuators[index];
    const bool by_temperature = !flags->temperatures.empty();
    if (!by_temperature && flags->tensions.empty()) {
      throw InputError("--temperatures-degC/--tensions-N", "(none)", "one of them is required");
    }
    if (by_temperature && act.drive.type != rod::Drive::Type::kTca) {
      throw InputError("--temperatures-degC", flags->temperatures,
                       "needs a TCA-driven actuator; '" + act.name + "' has a tension drive");
    }
    if (!by_temperature && act.drive.type != rod::Drive::Type::kTension) {
      throw InputError("--tensions-N", flags->tensions,
                       "needs a tension-driven actuator; '" + act.name + "' has a TCA drive");
    }
    const std::vector<double> values = by_temperature
                                           ? parse_range(flags->temperatures, "--temperatures-degC")
                                           : parse_range(flags->tensions, "--tensions-N");
    // The sweep with either method's options, validated here (before any thread starts).
    study::Sweep sweep;
    sweep.actuator = index;
    sweep.by_temperature = by_temperature;
    sweep.values = by_temperature
                       ? study::temperatures_K(values, "temperatures_degC", OptionNames::kFlags)
                       : values;
    sweep.method =
        study::static_options(flags->method, flags->integrator, flags->fe, OptionNames::kFlags);
    (void)method::StaticSolver(model, sweep.method);  // InputError for bad options

    // Chunks of --chunk points; this shard's part of them (all without --shard).
    const std::vector<IndexRange> chunks =
        fixed_chunks(values.size(), static_cast<std::size_t>(flags->chunk));
    const IndexRange mine = part_of(chunks.size(), static_cast<std::size_t>(shard.index),
                                    static_cast<std::size_t>(shard.count));
    const std::size_t first = mine.size() == 0 ? 0 : chunks[mine.begin].begin;
    const std::size_t points = mine.size() == 0 ? 0 : chunks[mine.end - 1].end - first;

    if (points == 0) {
      fmt::print(stderr,
                 "tcasim sweep: shard {}/{} holds no point (the sweep has {} chunk(s) of up to {} "
                 "points; a smaller --chunk gives more); writing the header only\n",
                 shard.index, shard.count, chunks.size(), flags->chunk);
    }
    Output out(flags->out);
    std::ostream& os = out.stream();
    fmt::print(os, "{},converged,iterations,residual,tip_x_m,tip_y_m,tip_z_m,bending_radius_m",
               by_temperature ? "temperature_degC" : "tension_N");
    for (const auto& a : model.actuators) {
      fmt::print(os, ",{0}_tension_N,{0}_elongation_m", a.name);
      // Coil contact of TCA drives in the solved state (per segment for a segmented TCA).
      if (a.drive.type == rod::Drive::Type::kTca)
        fmt::print(os, ",{0}_coils_closed,{0}_contact_force_N", a.name);
      if (a.drive.segmented) {
        for (std::size_t k = 1; k <= a.drive.segments.size(); ++k) {
          fmt::print(os, ",{0}_{1}_coils_closed,{0}_{1}_contact_force_N", a.name, k);
        }
      }
    }
    for (const auto& p : model.probes) fmt::print(os, ",{0}_x_m,{0}_y_m,{0}_z_m", p.name);
    for (const auto& o : model.obstacles) {
      fmt::print(os, ",{0}_force_x_N,{0}_force_y_N,{0}_force_z_N,{0}_in_contact", o.name);
    }
    fmt::print(os, "\n");

    // Long sweeps report progress on stderr: in place on a terminal, whole lines in a log.
    std::optional<ProgressReporter> progress;
    if (points >= 20) progress.emplace(stderr, "tcasim sweep", points);
    // Shared by the threads. A point's row goes to its own slot and the counts are atomic, so
    // no thread ever waits for another after a point: on a virtual machine a thread put to
    // sleep on a lock can take milliseconds to run again, which cost the two-thread sweep
    // about a tenth of its speed-up. The progress line is printed by whichever thread gets
    // `progress_mutex` without waiting (the last point's thread waits, so the final line is
    // printed once and last); whole chunks are written in order under `write_mutex`, once per
    // chunk.
    std::vector<std::string> rows(points);  // point k is rows[k - first]
    std::atomic<std::size_t> done{0};
    std::atomic<int> failures{0};
    std::mutex progress_mutex;
    const auto on_point = [&](std::size_t k, rod::Result&& r) {
      if (!r.converged) failures.fetch_add(1);
      rows[k - first] = sweep_row(values[k], r, model.probes.size(), model.obstacles.size());
      const std::size_t now_done = done.fetch_add(1) + 1;
      if (!progress) return;
      std::unique_lock<std::mutex> lock(progress_mutex, std::defer_lock);
      if (now_done == points) {  // the last point: its thread prints the final line
        lock.lock();
        progress->update(points);
        return;
      }
      if (!lock.try_lock()) return;
      // Read under the lock, so the reports never go back; the final line is left to the last
      // point's thread (once: a count already at the total is not reported here).
      const std::size_t now = done.load();
      if (now < points) progress->update(now);
    };
    std::mutex write_mutex;
    std::vector<char> chunk_done(mine.size(), 0);
    std::size_t next_chunk = 0;
    const auto on_chunk_done = [&](std::size_t c) {
      const std::lock_guard<std::mutex> lock(write_mutex);
      chunk_done[c - mine.begin] = 1;
      for (; next_chunk < mine.size() && chunk_done[next_chunk]; ++next_chunk) {
        const IndexRange written = chunks[mine.begin + next_chunk];
        for (std::size_t k = written.begin; k < written.end; ++k) {
          os << rows[k - first];
          std::string().swap(rows[k - first]);
        }
      }
    };
    study::solve_chunks(model, sweep, chunks, mine, static_cast<int>(flags->jobs), on_point,
                        on_chunk_done);
    out.commit();
    if (failures.load() > 0) {
      fmt::print(stderr,
                 "tcasim sweep: {} of {} points did not converge (converged = 0 in the CSV)\n",
                 failures.load(), points);
      throw CLI::RuntimeError(kExitNotConverged);
    }
  });
}

}  // namespace tcasim::app
