// `tcasim compare` and `tcasim converge`: the FE against the shooting solver on one scenario
// (the implementation is shared with validate_crosscheck / validate_convergence:
// crosscheck/crosscheck.hpp).
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
#include "rod/scenario.hpp"

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
      f, "reference: shooting RK4 {} steps ({:.3f} s), estimated error {:.2e} m (vs {} steps / 15)",
      steps, ref.rk4.time_s, ref.self_error_m, steps / 2);
  if (ref.cvode) fmt::print(f, "; CVODE - RK4 {:.2e} m", ref.cvode_difference_m);
  fmt::print(f, "\n");
}

}  // namespace

void add_compare_command(CLI::App& app) {
  struct Flags {
    std::string scenario, elements = "16,32,64,128", orders = "2,1", out;
    xc::ReferenceSettings reference;
    bool default_tolerances = false;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand("compare",
                                 "Cross-check: FE at increasing refinement against the shooting "
                                 "solution (tip, rotation, tension)");
  cmd->add_option("scenario", flags->scenario, "scenario file (tcasim.scenario/1)")->required();
  cmd->add_option("--elements", flags->elements,
                  "FE element counts, comma-separated (default 16,32,64,128)");
  cmd->add_option("--orders", flags->orders, "FE orders, comma-separated (default 2,1)");
  cmd->add_option("--reference-steps", flags->reference.steps,
                  "RK4 steps of the shooting reference (default 2048)");
  cmd->add_flag(
      "--default-tolerances", flags->default_tolerances,
      "FE Newton at beam_fe's default tolerances (default: tightened, as the validation)");
  cmd->add_option("--out", flags->out, "CSV file (default: stdout)");
  cmd->callback([flags] {
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
    fmt::print(stderr, "{} / order {} (position at s = {} m; expected order {} +- {}):\n{}",
               model.name, flags->order, study.measured_s_m, b.expected, b.tolerance,
               xc::convergence_table(study));
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
