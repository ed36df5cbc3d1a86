// `tcasim compare` and `tcasim converge`: the FE against the shooting solver on one scenario
// (the implementation is shared with validate_crosscheck / validate_convergence:
// crosscheck/crosscheck.hpp); `tcasim compare --dynamic`: the two dynamics methods over time
// (shared with validate_dynamic_crosscheck: crosscheck/dynamic.hpp).
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli_util.hpp"
#include "apps/commands.hpp"
#include "common/error.hpp"
#include "crosscheck/crosscheck.hpp"
#include "crosscheck/dynamic.hpp"
#include "rod/scenario.hpp"
#include "study/simulation.hpp"

namespace tcasim::app {

namespace {

namespace xc = tcasim::crosscheck;

/// Exit code when a solve did not converge (the table is still written).
constexpr int kExitNotConverged = 4;

void progress(const std::string& what) { fmt::print(stderr, "  {}\n", what); }

/// Parses "A,B,C" into integers in [1, max]; `flag` names the option in messages.
std::vector<int> parse_counts(const std::string& text, const std::string& flag, int max) {
  std::vector<int> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    std::size_t used = 0;
    int v = 0;
    try {
      v = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || v < 1 || v > max) {
      throw InputError(flag, text,
                       fmt::format("must be a comma-separated list of integers in [1, {}]", max));
    }
    out.push_back(v);
    start = end + 1;
  }
  return out;
}

/// Loads a scenario (both solvers solve every valid one).
rod::RodModel load_supported(const std::string& path) { return rod::read_scenario(path); }

/// --reference-steps: the RK4 reference halves its steps for its error estimate.
void require_reference_steps(int steps) {
  require(steps >= 4 && steps <= kMaxSteps && steps % 4 == 0, "--reference-steps", steps,
          fmt::format("must be a multiple of 4 in [4, {}] (steps and steps / 2 even)", kMaxSteps));
}

void print_reference(std::FILE* f, const xc::Reference& ref, int steps) {
  fmt::print(
      f, "reference: shooting RK4 {} steps ({:.3f} s), estimated error {:.2e} m (vs {} steps{})",
      steps, ref.rk4.time_s, ref.self_error_m, steps / 2,
      ref.rk4.result.contacts.empty() ? " / 15" : ", contact resolved to the grid: first order");
  if (ref.cvode) fmt::print(f, "; CVODE - RK4 {:.2e} m", ref.cvode_difference_m);
  fmt::print(f, "\n");
}

/// `tcasim compare --dynamic`: one shooting run against the FE on each mesh; the per-time CSV
/// to `out` (stdout when empty), the summary (max tip difference over time) to stderr.
/// The flags are those of `tcasim simulate` (its options and rules, study/simulation.hpp;
/// the static comparison's --elements and --orders give the FE meshes).
void compare_dynamic(const rod::RodModel& model, const study::SimulationOptions& f,
                     const std::vector<int>& elements, const std::vector<int>& orders,
                     const std::string& out_path) {
  const long long n_steps = study::check_simulation_options(f, study::OptionNames::kFlags);
  xc::DynamicSettings s;
  s.duration_s = f.duration_s;
  if (f.rtol) {
    // Adaptive: both methods land on the output times k --output-every-s, compared there.
    s.rtol = f.rtol;
    s.atol_m = f.atol_m.value_or(0.0);
    s.output_dt_s = *f.output_every_s;
  } else {
    s.dt_s = f.dt_s;
    s.output_dt_s = static_cast<double>(f.output_every) * f.dt_s;
  }
  s.release_tip_load = f.release_tip_load;
  // Checked above: a given --steps is >= 1 (DynamicSettings' 0 is its own "recommended").
  if (f.steps) s.steps = static_cast<int>(*f.steps);
  s.alpha = f.alpha;
  s.rho_inf = f.rho_inf;
  s.max_iterations = static_cast<int>(f.max_iterations);
  // Refused before the shooting run spends its time.
  const std::string unsupported = xc::fe_dynamics_unsupported(model);
  if (!unsupported.empty()) throw DomainError(unsupported);
  progress(model.name + ": shooting dynamics");
  xc::DynamicRun shooting;
  try {
    shooting = xc::run_dynamics(model, xc::DynamicMethod::kShooting, s);
  } catch (const InputError& e) {
    study::rethrow_under_option_name(e, study::OptionNames::kFlags);
  }
  std::vector<xc::DynamicRun> fe;
  std::vector<std::string> labels;
  for (const int order : orders) {
    for (const int n : elements) {
      s.order = order;
      s.elements = n;
      progress(fmt::format("{}: FE dynamics, order {}, {} elements", model.name, order, n));
      fe.push_back(xc::run_dynamics(model, xc::DynamicMethod::kFe, s));
      labels.push_back(fmt::format("fe_p{}_n{}", order, n));
    }
  }
  Output out(out_path);
  out.stream() << xc::dynamic_csv(shooting, fe, labels);
  out.commit();
  if (f.rtol) {
    fmt::print(stderr,
               "{}: {} s, adaptive steps rtol {} atol {} m, output every {} s ({} rows); "
               "shooting: {} RK4 steps along s, {} steps ({} retried), {:.3f} s{}\n",
               model.name, f.duration_s, *f.rtol, s.atol_m, *f.output_every_s, n_steps,
               shooting.grid_steps, shooting.steps_done, shooting.steps_rejected, shooting.wall_s,
               shooting.ok ? "" : "; FAILED: " + shooting.message);
  } else {
    fmt::print(stderr,
               "{}: {} s at dt {} s ({} steps); shooting: {} RK4 steps along s, {:.3f} s{}\n",
               model.name, f.duration_s, f.dt_s, n_steps, shooting.grid_steps, shooting.wall_s,
               shooting.ok ? "" : "; FAILED: " + shooting.message);
  }
  fmt::print(stderr, "  {:>5} {:>8} {:>14} {:>11} {:>9} {:>8} {:>8}\n", "order", "elements",
             "max |dtip| [m]", "/ L", "at t [s]", "fe [s]", "fe steps");
  bool all = shooting.ok;
  std::size_t k = 0;
  for (const int order : orders) {
    for (const int n : elements) {
      const xc::DynamicRun& r = fe[k++];
      const xc::TrajectoryDifference d = xc::trajectory_difference(r, shooting);
      fmt::print(stderr, "  {:>5} {:>8} {:>14.4e} {:>11.3e} {:>9.4f} {:>8.3f} {:>8}{}\n", order, n,
                 d.max_m, d.max_m / model.length_m, d.at_t_s, r.wall_s, r.steps_done,
                 r.ok ? "" : "  FAILED: " + r.message);
      all = all && r.ok;
    }
  }
  if (!all) {
    fmt::print(stderr,
               "tcasim compare --dynamic: a run failed (the CSV holds the times before it)\n");
    throw CLI::RuntimeError(kExitNotConverged);
  }
}

}  // namespace

void add_compare_command(CLI::App& app) {
  struct Flags {
    std::string scenario, elements = "16,32,64,128", orders = "2,1", out;
    xc::ReferenceSettings reference;
    bool default_tolerances = false;
    bool dynamic = false;
    study::SimulationOptions dyn;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand("compare",
                                 "Cross-check: FE at increasing refinement against the shooting "
                                 "solution (tip, rotation, tension); --dynamic: the two dynamics "
                                 "methods over time (max tip difference)");
  cmd->add_option("scenario", flags->scenario, "scenario file (tcasim.scenario/1)")->required();
  auto* elements_flag =
      cmd->add_option("--elements", flags->elements,
                      "FE element counts, comma-separated (default 16,32,64,128; --dynamic: 32)");
  auto* orders_flag = cmd->add_option("--orders", flags->orders,
                                      "FE orders, comma-separated (default 2,1; --dynamic: 2)");
  auto* reference_flag = cmd->add_option("--reference-steps", flags->reference.steps,
                                         "RK4 steps of the shooting reference (default 2048)");
  auto* tolerances_flag = cmd->add_flag(
      "--default-tolerances", flags->default_tolerances,
      "FE Newton at beam_fe's default tolerances (default: tightened, as the validation)");
  cmd->add_flag("--dynamic", flags->dynamic,
                "compare the dynamics (tcasim simulate's two methods) from the static state at "
                "t = 0: per-time CSV, max tip difference over time on stderr");
  study::SimulationOptions& d = flags->dyn;
  const std::vector<CLI::Option*> dynamic_flags = {
      cmd->add_option("--duration-s", d.duration_s, "--dynamic: simulated time T [s] (> 0)"),
      cmd->add_option("--dt-s", d.dt_s,
                      "--dynamic: time step of both methods [s] (> 0); or --rtol"),
      cmd->add_option("--rtol", d.rtol,
                      "--dynamic: adaptive time steps in both methods instead of --dt-s (as "
                      "tcasim simulate --rtol): relative tolerance of the local error per rod "
                      "length, in (0, 1)"),
      cmd->add_option("--atol-m", d.atol_m,
                      "--dynamic with --rtol: absolute tolerance of the local error [m] (>= 0, "
                      "default 0)"),
      cmd->add_option("--output-every-s", d.output_every_s,
                      "--dynamic with --rtol (required): compare every this many seconds, in "
                      "(0, duration]"),
      cmd->add_option("--steps", d.steps,
                      fmt::format("--dynamic: shooting RK4 steps along s, in [1, {}] (default: "
                                  "enough for the time step)",
                                  kMaxSteps))
          ->check(fits_64_bits()),
      cmd->add_option("--alpha", d.alpha,
                      "--dynamic: shooting BDF-alpha parameter in [-0.5, 0] (default -0.2)"),
      cmd->add_option("--rho-inf", d.rho_inf,
                      "--dynamic: FE generalized-alpha spectral radius in [0, 1] (default 0.9)"),
      cmd->add_option("--output-every", d.output_every,
                      "--dynamic: write every K-th time step (default 1)")
          ->check(fits_64_bits()),
      cmd->add_option("--max-iterations", d.max_iterations,
                      "--dynamic: Newton iterations per time step (default 30)")
          ->check(fits_64_bits()),
      cmd->add_flag("--release-tip-load", d.release_tip_load,
                    "--dynamic: the scenario's tip load acts at t = 0 only (a released "
                    "cantilever)")};
  cmd->add_option("--out", flags->out, "CSV file (default: stdout)");
  cmd->callback([=] {
    // A flag of the other mode is refused, not ignored.
    for (const CLI::Option* o : dynamic_flags) {
      if (o->count() > 0 && !flags->dynamic) {
        throw InputError(o->get_name(), o->as<std::string>(), "applies to --dynamic only");
      }
    }
    for (const CLI::Option* o : {reference_flag, tolerances_flag}) {
      if (o->count() > 0 && flags->dynamic) {
        throw InputError(o->get_name(), o->as<std::string>(),
                         "applies to the static comparison only (without --dynamic)");
      }
    }
    if (flags->dynamic) {
      const CLI::Option* duration_flag = dynamic_flags[0];
      const CLI::Option* dt_flag = dynamic_flags[1];
      const CLI::Option* rtol_flag = dynamic_flags[2];
      if (duration_flag->count() == 0) {
        throw InputError("--duration-s", "(missing)", "is required with --dynamic");
      }
      // Exactly one time-step mode, as in tcasim simulate; the other rules (--output-every-s
      // with --rtol, --atol-m and --output-every only with their mode) are
      // study::check_simulation_options'.
      require_one_time_step_mode(dt_flag->count() > 0,
                                 dt_flag->count() > 0 ? dt_flag->as<std::string>() : "",
                                 rtol_flag->count() > 0);
      const std::vector<int> elements = parse_counts(
          elements_flag->count() > 0 ? flags->elements : "32", "--elements", kMaxElements);
      const std::vector<int> orders =
          parse_counts(orders_flag->count() > 0 ? flags->orders : "2", "--orders", 2);
      const rod::RodModel model = load_supported(flags->scenario);
      compare_dynamic(model, flags->dyn, elements, orders, flags->out);
      return;
    }
    require_reference_steps(flags->reference.steps);
    const rod::RodModel model = load_supported(flags->scenario);
    const std::vector<int> elements = parse_counts(flags->elements, "--elements", kMaxElements);
    const std::vector<int> orders = parse_counts(flags->orders, "--orders", 2);
    std::vector<xc::FeSettings> meshes;
    for (int order : orders) {
      require(order == 1 || order == 2, "--orders", order, "must be 1 or 2");
      for (int n : elements) {
        xc::FeSettings s = flags->default_tolerances ? xc::FeSettings{} : xc::tight_tolerances();
        s.order = order;
        s.elements = n;
        meshes.push_back(s);
      }
    }
    progress(model.name + ": shooting reference");
    const xc::Reference ref = xc::shooting_reference(model, flags->reference);
    const auto rows = xc::cross_check(model, ref, meshes, progress);
    print_reference(stderr, ref, flags->reference.steps);
    Output out(flags->out);
    out.stream() << xc::crosscheck_csv_header();
    bool all = ref.converged();
    for (const auto& r : rows) {
      out.stream() << xc::crosscheck_csv_row(r, ref, flags->reference.steps);
      all = all && r.converged;
    }
    out.commit();
    if (!all) {
      fmt::print(stderr, "tcasim compare: a solve did not converge (converged = 0 in the CSV)\n");
      throw CLI::RuntimeError(kExitNotConverged);
    }
  });
}

void add_converge_command(CLI::App& app) {
  struct Flags {
    std::string scenario, out;
    int order = 2;
    int levels = 4;
    int coarsest = 0;
    xc::ReferenceSettings reference;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand("converge",
                                 "h-convergence of the FE: error vs shooting and vs Richardson "
                                 "extrapolation, observed orders");
  cmd->add_option("scenario", flags->scenario, "scenario file (tcasim.scenario/1)")->required();
  cmd->add_option("--order", flags->order, "FE order, 1 or 2 (default 2)")
      ->check(CLI::IsMember({1, 2}));
  cmd->add_option("--levels", flags->levels,
                  "number of meshes, each twice as fine (>= 3; default 4)");
  cmd->add_option(
      "--coarsest", flags->coarsest,
      "elements of the coarsest mesh (default: the validation's choice for this scenario)");
  cmd->add_option("--reference-steps", flags->reference.steps,
                  "RK4 steps of the shooting reference (default 2048)");
  cmd->add_option("--out", flags->out, "CSV file (default: stdout; the table goes to stderr)");
  cmd->callback([flags] {
    require_reference_steps(flags->reference.steps);
    require(flags->levels >= 3, "--levels", flags->levels,
            "must be >= 3 (Richardson needs three meshes)");
    require_count(flags->coarsest, "--coarsest", 0, kMaxElements);
    const rod::RodModel model = load_supported(flags->scenario);
    const int coarsest = flags->coarsest > 0
                             ? flags->coarsest
                             : xc::study_levels(model.name, flags->order, false).coarsest;
    // The finest mesh has coarsest 2^(levels - 1) elements.
    long long finest = coarsest;
    for (int k = 1; k < flags->levels && finest <= kMaxElements; ++k) finest *= 2;
    require(finest <= kMaxElements, "--levels", flags->levels,
            fmt::format("must keep the finest mesh, {} x 2^(levels - 1) elements, <= {}", coarsest,
                        kMaxElements));
    xc::FeSettings tol = xc::tight_tolerances();
    tol.order = flags->order;
    progress(model.name + ": shooting reference");
    const xc::Reference ref = xc::shooting_reference(model, flags->reference);
    const xc::ConvergenceStudy study = xc::convergence_study(
        model, ref, tol, xc::refinement_levels(coarsest, flags->levels), progress);
    print_reference(stderr, ref, flags->reference.steps);
    const xc::OrderBracket b = xc::order_bracket(flags->order);
    // With obstacles the contact points are the nodes: a contact zone's ends are resolved to
    // the mesh, and what depends on them converges at about first order.
    const std::string expected =
        model.obstacles.empty()
            ? fmt::format("expected order {} +- {}", b.expected, b.tolerance)
            : fmt::format(
                  "expected order {} +- {} without contact; about 1 where the contact "
                  "ends, resolved to the nodes, move it",
                  b.expected, b.tolerance);
    fmt::print(stderr, "{} / order {} (position at s = {} m; {}):\n{}", model.name, flags->order,
               study.measured_s_m, expected, xc::convergence_table(study));
    Output out(flags->out);
    out.stream() << xc::convergence_csv_header() << xc::convergence_csv_rows(model.name, study);
    out.commit();
    if (!study.converged() || !ref.converged()) {
      fmt::print(stderr, "tcasim converge: a solve did not converge (converged = 0 in the CSV)\n");
      throw CLI::RuntimeError(kExitNotConverged);
    }
  });
}

}  // namespace tcasim::app
