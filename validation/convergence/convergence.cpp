// validate_convergence: h-convergence of the beam FE (linear and quadratic elements) on every
// scenario of the suite, against the Cosserat shooting solution and against the FE's own
// Richardson extrapolation.
//
// What it checks
//   For each `tcasim.scenario/1` file in validation/scenarios/ (one a solver does not support
//   is listed as not run with the solvers' reason, and fails), the FE tip position at element
//   counts n0, 2 n0, 4 n0, ... (levels chosen inside the asymptotic range: coarser meshes are
//   pre-asymptotic, finer quadratic meshes reach the round-off floor), with Newton tolerances
//   tightened far below beam_fe's defaults (crosscheck.cpp tight_tolerances()) so the solver
//   error stays below the discretization error.
// Reference
//   Shooting with classical RK4 at a high step count (default 2048 steps); its own error is
//   estimated from a solve with half the steps (|p(N) - p(N/2)| / 15) and must lie far below
//   the finest FE error; CVODE at rtol 1e-12 is reported as a second opinion. Richardson:
//   order and extrapolated tip from the three finest FE levels.
// Gates (per scenario and order; brackets of the FE issue, two-sided)
//   1. every FE and reference solve converges;
//   2. every observed order against the shooting reference lies in [2 - 0.15, 2 + 0.15]
//      (linear) or [4 - 0.3, 4 + 0.3] (quadratic), over the asymptotic range: levels where
//      the error stopped falling at the FE's round-off floor (~eps nodes EA L^2/EI L,
//      crosscheck.hpp asymptotic_level_count) are reported as such, not gated; at least two
//      levels must lie above it;
//   3. the Richardson order of the three finest asymptotic levels lies in the same bracket;
//   4. the reference's estimated error is below 1 % of the finest asymptotic FE error.
//   and for the suite: every scenario found runs (at least the 17 shipped ones), each with
//   every order asked for.
// Usage
//   validate_convergence --out-dir out/convergence            (full: all suite scenarios)
//   validate_convergence --quick --out-dir /tmp/convergence   (fewer levels)
//   validate_convergence --scenario steel-4-tendon --order 2 --coarsest 8 --levels 6
//   /usr/bin/python3 scripts/plot_convergence.py out/convergence  (convergence.png)
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "crosscheck/crosscheck.hpp"
#include "rod/output_file.hpp"
#include "rod/scenario.hpp"
#include "validation/common/gates.hpp"

namespace {

namespace xc = tcasim::crosscheck;

/// The reference must resolve the finest FE error: its estimated error below this fraction of it.
constexpr double kReferenceFraction = 0.01;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"h-convergence of the beam FE (orders 1 and 2) on the scenario suite"};
  bool quick = false;
  std::string out_dir = "convergence-out";
  std::string scenario_dir = TCASIM_SCENARIO_DIR;
  std::vector<std::string> only;
  int only_order = 0;
  int coarsest = 0;
  int levels = 0;
  xc::ReferenceSettings ref_settings;
  app.add_flag("--quick", quick, "fewer levels (seconds)");
  app.add_option("--out-dir", out_dir, "output folder for CSV files");
  app.add_option("--scenario-dir", scenario_dir, "folder with the suite's scenario files");
  app.add_option("--scenario", only, "restrict to these scenario names (repeatable)");
  app.add_option("--order", only_order, "restrict to one order (1 or 2)")
      ->check(CLI::IsMember({1, 2}));
  app.add_option("--coarsest", coarsest, "override the coarsest element count (with --order)");
  app.add_option("--levels", levels, "override the number of levels (with --order)");
  app.add_option("--reference-steps", ref_settings.steps,
                 "RK4 steps of the shooting reference (multiple of 4)");
  app.add_option("--reference-tolerance", ref_settings.tolerance,
                 "Newton tolerance of the shooting reference (scaled residual)");
  CLI11_PARSE(app, argc, argv);

  try {
    const auto t_start = std::chrono::steady_clock::now();
    auto elapsed = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    };
    auto progress = [&](const std::string& what) {
      fmt::print("  [{:7.2f} s] {}\n", elapsed(), what);
      std::fflush(stdout);
    };
    std::filesystem::create_directories(out_dir);
    const std::vector<int> orders =
        only_order == 0 ? std::vector<int>{1, 2} : std::vector<int>{only_order};

    fmt::print("Step 1: suite ({})\n", scenario_dir);
    std::vector<std::pair<std::string, std::string>> skipped;
    const std::vector<tcasim::rod::RodModel> models = xc::load_suite(scenario_dir, only, skipped);
    const std::size_t expected = xc::expected_scenarios(
        scenario_dir, only,
        only.empty() && scenario_dir == TCASIM_SCENARIO_DIR ? xc::kShippedSuiteScenarios : 1);

    fmt::print("Step 2: shooting references (RK4 {} and {} steps, CVODE rtol {:.0e})\n",
               ref_settings.steps, ref_settings.steps / 2, ref_settings.cvode_rtol);
    std::vector<xc::Reference> references;
    tcasim::rod::AtomicOutput ref_csv(out_dir + "/reference.csv", "reference csv");
    ref_csv << "scenario,steps,tip_x_m,tip_y_m,tip_z_m,self_error_m,cvode_diff_m,rk4_time_s,cvode_"
               "time_s,converged\n";
    for (const auto& model : models) {
      progress(model.name + ": reference");
      references.push_back(xc::shooting_reference(model, ref_settings));
      const auto& r = references.back();
      const auto& p = r.rk4.result.tip_position_W_m;
      fmt::print(
          "    tip ({:.12f}, {:.12f}, {:.12f}) m; self error {:.2e} m; CVODE - RK4 {:.2e} m; "
          "{:.3f} s\n",
          p.x(), p.y(), p.z(), r.self_error_m, r.cvode_difference_m, r.rk4.time_s);
      fmt::print(ref_csv, "{},{},{:.15e},{:.15e},{:.15e},{:.6e},{:.6e},{:.6e},{:.6e},{}\n",
                 model.name, ref_settings.steps, p.x(), p.y(), p.z(), r.self_error_m,
                 r.cvode_difference_m, r.rk4.time_s, r.cvode ? r.cvode->time_s : 0.0,
                 r.converged() ? 1 : 0);
    }
    ref_csv.commit();

    fmt::print(
        "Step 3: FE studies (Newton tolerances abs {:.0e}, rel {:.0e}, plus beam_fe's round-off "
        "floor)\n",
        xc::tight_tolerances().tolerance_abs, xc::tight_tolerances().tolerance_rel);
    tcasim::rod::AtomicOutput csv(out_dir + "/convergence.csv", "convergence csv");
    csv << xc::convergence_csv_header();
    struct Entry {
      std::string scenario;
      xc::ConvergenceStudy study;
      double reference_error_m;
      bool reference_converged;
    };
    std::vector<Entry> entries;
    for (std::size_t m = 0; m < models.size(); ++m) {
      for (int order : orders) {
        const xc::StudyLevels d = xc::study_levels(models[m].name, order, quick);
        if (!d.reason.empty())
          fmt::print("  {} order {}: levels {} x {}: {}\n", models[m].name, order, d.coarsest,
                     d.count, d.reason);
        xc::FeSettings tol = xc::tight_tolerances();
        tol.order = order;
        const auto elements = xc::refinement_levels(coarsest > 0 ? coarsest : d.coarsest,
                                                    levels > 0 ? levels : d.count);
        entries.push_back({models[m].name,
                           xc::convergence_study(models[m], references[m], tol, elements, progress),
                           references[m].self_error_m, references[m].converged()});
        csv << xc::convergence_csv_rows(models[m].name, entries.back().study);
      }
    }
    csv.commit();

    fmt::print("Step 4: tables (error = |p_fe(L) - p_shooting(L)|)\n");
    for (const auto& e : entries) {
      fmt::print("{} / order {}:\n{}", e.scenario, e.study.order, xc::convergence_table(e.study));
    }

    fmt::print("Step 5: gates\n");
    tcasim::validation::Gates gates("validate_convergence");
    gates.expect_count("scenarios", models.size(), expected);
    gates.expect_count("studies (scenario x order)", entries.size(), expected * orders.size());
    for (const auto& [name, why] : skipped) gates.not_run(name, why);
    for (const auto& e : entries) {
      const std::string label = fmt::format("{} / order {}", e.scenario, e.study.order);
      const xc::OrderBracket b = xc::order_bracket(e.study.order);
      int failed = 0;
      for (const auto& l : e.study.levels) failed += l.fe.converged ? 0 : 1;
      gates.check(label + ": every solve converges", failed == 0 && e.reference_converged,
                  fmt::format("{} FE solves failed; reference {}", failed,
                              e.reference_converged ? "ok" : "failed"),
                  "0");
      // Orders only over the asymptotic range: levels where refinement stopped helping at the
      // FE's round-off floor are reported, not gated (their "order" is round-off).
      const std::size_t asymptotic = static_cast<std::size_t>(e.study.asymptotic_levels);
      gates.check(label + ": at least two levels above the round-off floor", asymptotic >= 2,
                  fmt::format("{} of {} levels", asymptotic, e.study.levels.size()), ">= 2");
      for (std::size_t i = 1; i < e.study.levels.size(); ++i) {
        const auto& l = e.study.levels[i];
        const std::string what = fmt::format("{}: observed order vs shooting, {} -> {} elements",
                                             label, e.study.levels[i - 1].elements, l.elements);
        if (i < asymptotic) {
          gates.within(what, l.observed_order, b.lo(), b.hi());
        } else {
          gates.check(
              what + " (round-off floor)", true,
              fmt::format("order {:.3f}, error {:.2e} m at the floor", l.observed_order, l.error_m),
              "not gated (refinement stopped helping)");
        }
      }
      if (asymptotic >= 3) {
        gates.within(label + ": Richardson order (three finest asymptotic levels)",
                     e.study.richardson.order, b.lo(), b.hi());
      } else {
        gates.check(label + ": Richardson order", true, "fewer than three asymptotic levels",
                    "not gated (round-off floor)");
      }
      const double finest = e.study.levels[std::max<std::size_t>(asymptotic, 1) - 1].error_m;
      gates.at_most(label + ": reference error estimate vs 1 % of the finest FE error",
                    e.reference_error_m, kReferenceFraction * finest, "m");
    }
    gates.write_csv(out_dir);
    fmt::print("Wrote {0}/convergence.csv, {0}/reference.csv and gates.csv ({1:.1f} s)\n", out_dir,
               elapsed());
    return gates.finish();
  } catch (const std::exception& e) {
    fmt::print(stderr, "validate_convergence: error: {}\n", e.what());
    return 2;
  }
}
