// validate_crosscheck: the two forward solvers (Cosserat shooting, geometrically exact beam
// FE) on every scenario of the suite, the FE at increasing refinement.
//
// What it checks
//   Both solvers discretize the same continuum problem (docs/conventions.md). For each
//   `tcasim.scenario/1` file in validation/scenarios/ (one a solver does not support is
//   listed as not run with the solvers' own reason, and fails), the FE with quadratic and
//   linear elements on refined meshes is compared with the shooting reference: tip position,
//   tip rotation, the largest string tension and elongation differences, with wall times.
//   Newton tolerances of the FE are tightened far below its defaults (crosscheck.cpp
//   tight_tolerances()).
// Reference
//   Shooting with classical RK4 at 2048 steps; its error is estimated from a solve with 1024
//   steps (|p(N) - p(N/2)| / 15) and reported with the CVODE (rtol 1e-12) difference.
// Gates (per scenario)
//   1. every solve converges;
//   2. FE (quadratic, finest mesh) vs shooting: max(tip, mid-point) position difference
//      <= 1e-9 L (the mid point matters where a tip constraint pins the tip);
//   3. the reference's own estimated error <= 1e-10 L (it cannot hide an FE error of 1e-9 L);
//   4. that difference shrinks by at least 10x from the coarsest to the finest quadratic mesh
//      (the two solutions approach each other, not just happen to agree on one mesh; theory
//      gives (128/16)^4 = 4096x until the reference's accuracy is reached).
//   5. tip rotation difference (finest quadratic mesh) <= 1e-9 rad, the angular counterpart
//      of gate 2;
//   6. largest string elongation difference <= 1e-9 r_max (r_max: the largest string offset;
//      an elongation is the offset times the bending it follows), and largest string tension
//      difference <= k_max 1e-9 r_max (k_max: the stiffest TCA's dF/d delta at the reference;
//      0 for prescribed tensions, which both solvers must reproduce exactly);
//   and for the suite: every scenario found runs (at least the 17 shipped ones); one that a
//   solver does not support is reported "not run" and fails.
// Usage
//   validate_crosscheck --out-dir out/crosscheck           (full)
//   validate_crosscheck --quick --out-dir /tmp/crosscheck  (fewer meshes)
//   /usr/bin/python3 scripts/plot_crosscheck.py out/crosscheck  (crosscheck.png)
#include "crosscheck/crosscheck.hpp"

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

#include "rod/output_file.hpp"
#include "rod/scenario.hpp"
#include "tca/tca.hpp"
#include "validation/common/gates.hpp"

namespace {

namespace xc = tcasim::crosscheck;

/// The gate: FE vs shooting at the finest mesh, relative to the body length.
constexpr double kAgreementOverL = 1e-9;
/// The reference must be an order of magnitude below the agreement gate.
constexpr double kReferenceOverL = 1e-10;
/// Smallest reduction of the difference from the coarsest to the finest quadratic mesh.
constexpr double kMinReduction = 10.0;
/// Tip rotation, FE (finest quadratic mesh) vs shooting [rad]: the angular counterpart of
/// kAgreementOverL. The tip position is the integral of the rotated tangent, p(L) = int R e3 ds,
/// so the FE's O(h^4) error shows in the rotation with the same relative size (a rotation error
/// d theta moves the tip by up to L d theta). Measured 2.7e-14..8.7e-11 rad (steel-4-tendon).
constexpr double kRotationBound_rad = 1e-9;
/// String elongation difference, relative to the largest string offset r from the centerline:
/// the string length is l = int |nu + omega x r + r'| ds (docs/conventions.md, "String
/// actuators"), so to first order dl = int (d nu_3 + (d omega x r) . e3) ds: the offset times
/// the integrated curvature error, a rotation error. Hence |de| <= r_max kRotationBound_rad
/// (the axial-strain part d nu_3 = dn / (E A) is far smaller).
/// Measured |de| / r_max 4.4e-14..8.8e-11 (steel-4-tendon); a TCA's tension follows its
/// elongation, dT = k de, so its bound is k_max times this one (measured at most 1.5 % of it).
constexpr double kElongationOverOffset = kRotationBound_rad;

/// The gated difference: tip or mid point, whichever is larger [m].
double position_difference(const xc::CrossCheckRow& r) {
  return std::fmax(r.diff.tip_m, r.diff.mid_m);
}

/// Largest distance of a string from the centerline, r_max [m] (straight offset, helix radius,
/// or a spline's largest listed offset).
double max_string_offset_m(const tcasim::rod::RodModel& model) {
  using Type = tcasim::rod::Routing::Type;
  double r = 0.0;
  for (const auto& a : model.actuators) {
    if (a.routing.type == Type::kSpline) {
      for (const Eigen::Vector2d& p : a.routing.knot_offsets_m) r = std::max(r, p.norm());
      continue;
    }
    r = std::max(r, a.routing.type == Type::kHelix ? std::abs(a.routing.radius_m)
                                                   : a.routing.offset_m.norm());
  }
  return r;
}

/// Stiffest TCA string at the reference, max dF/d delta [N/m] (series law at the reference
/// elongation and temperatures); 0 when every string is tension-driven (its tension is
/// prescribed, so both solvers must give it exactly).
double max_tca_stiffness_N_m(const tcasim::rod::RodModel& model,
                             const tcasim::rod::Result& reference) {
  double k = 0.0;
  for (std::size_t i = 0; i < model.actuators.size() && i < reference.actuators.size(); ++i) {
    const auto& d = model.actuators[i].drive;
    if (d.type != tcasim::rod::Drive::Type::kTca) continue;
    k = std::max(k, std::abs(tcasim::tca::series_tension(
                                 *d.tca, reference.actuators[i].elongation_m, d.segments)
                                 .dF_ddelta_N_m));
  }
  return k;
}

/// Largest |value| over the actuators of a result (0 without actuators).
double max_abs(const tcasim::rod::Result& r, double tcasim::rod::ActuatorResult::*value) {
  double m = 0.0;
  for (const auto& a : r.actuators) m = std::max(m, std::abs(a.*value));
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Cross-check of the shooting and FE solvers on the scenario suite"};
  bool quick = false;
  std::string out_dir = "crosscheck-out";
  std::string scenario_dir = TCASIM_SCENARIO_DIR;
  std::vector<std::string> only;
  xc::ReferenceSettings ref_settings;
  app.add_flag("--quick", quick, "fewer meshes (seconds)");
  app.add_option("--out-dir", out_dir, "output folder for CSV files");
  app.add_option("--scenario-dir", scenario_dir, "folder with the suite's scenario files");
  app.add_option("--scenario", only, "restrict to these scenario names (repeatable)");
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
    const std::vector<xc::FeSettings> meshes = xc::crosscheck_meshes(quick);

    fmt::print("Step 1: suite ({})\n", scenario_dir);
    std::vector<std::pair<std::string, std::string>> skipped;
    const std::vector<tcasim::rod::RodModel> models = xc::load_suite(scenario_dir, only, skipped);
    const std::size_t expected = xc::expected_scenarios(
        scenario_dir, only,
        only.empty() && scenario_dir == TCASIM_SCENARIO_DIR ? xc::kShippedSuiteScenarios : 1);

    fmt::print("Step 2: reference (RK4 {} / {} steps, CVODE rtol {:.0e}) and FE meshes\n",
               ref_settings.steps, ref_settings.steps / 2, ref_settings.cvode_rtol);
    tcasim::rod::AtomicOutput csv(out_dir + "/crosscheck.csv", "crosscheck csv");
    csv << xc::crosscheck_csv_header();
    struct Entry {
      const tcasim::rod::RodModel* model;
      xc::Reference reference;
      std::vector<xc::CrossCheckRow> rows;
    };
    std::vector<Entry> entries;
    for (const auto& model : models) {
      progress(model.name + ": shooting reference");
      Entry e{&model, xc::shooting_reference(model, ref_settings), {}};
      e.rows = xc::cross_check(model, e.reference, meshes, progress);
      for (const auto& row : e.rows)
        csv << xc::crosscheck_csv_row(row, e.reference, ref_settings.steps);
      entries.push_back(std::move(e));
    }
    csv.commit();

    fmt::print("Step 3: table (FE - shooting; reference error = |p(N) - p(N/2)| / 15)\n");
    for (const auto& e : entries) {
      fmt::print(
          "{}: L = {} m, reference error {:.2e} m, CVODE - RK4 {:.2e} m, shooting {:.3f} s\n",
          e.model->name, e.model->length_m, e.reference.self_error_m,
          e.reference.cvode_difference_m, e.reference.rk4.time_s);
      fmt::print("  largest reference tension {:.4e} N, largest reference elongation {:.4e} m\n",
                 max_abs(e.reference.rk4.result, &tcasim::rod::ActuatorResult::tension_N),
                 max_abs(e.reference.rk4.result, &tcasim::rod::ActuatorResult::elongation_m));
      fmt::print("  {:>5} {:>8} {:>11} {:>11} {:>11} {:>11} {:>11} {:>11} {:>11} {:>8}\n", "order",
                 "elements", "tip [m]", "tip / L", "mid [m]", "rot [rad]", "tension [N]",
                 "elong. [m]", "react. [N]", "fe [s]");
      for (const auto& r : e.rows) {
        fmt::print(
            "  {:>5} {:>8} {:>11.3e} {:>11.3e} {:>11.3e} {:>11.3e} {:>11.3e} {:>11.3e} {:>11.3e} "
            "{:>8.3f}{}\n",
            r.order, r.elements, r.diff.tip_m, r.diff.tip_m / r.length_m, r.diff.mid_m,
            r.diff.rotation_rad, r.diff.max_tension_N, r.diff.max_elongation_m, r.diff.reaction_N,
            r.fe_time_s, r.converged ? "" : "  NOT CONVERGED");
      }
    }

    fmt::print("Step 4: gates\n");
    tcasim::validation::Gates gates("validate_crosscheck");
    // Every suite scenario must be cross-checked: one a solver does not support is a failure.
    gates.expect_count("scenarios", entries.size(), expected);
    for (const auto& [name, why] : skipped) gates.not_run(name, why);
    for (const auto& e : entries) {
      const std::string& name = e.model->name;
      const double L = e.model->length_m;
      int failed = 0;
      for (const auto& r : e.rows) failed += r.converged ? 0 : 1;
      gates.check(name + ": every solve converges", failed == 0 && e.reference.converged(),
                  fmt::format("{} FE solves failed; reference {}", failed,
                              e.reference.converged() ? "ok" : "failed"),
                  "0");
      std::vector<const xc::CrossCheckRow*> quadratic;
      for (const auto& r : e.rows) {
        if (r.order == 2) quadratic.push_back(&r);
      }
      const auto* finest = quadratic.back();
      gates.at_most(
          fmt::format("{}: FE (order 2, {} elements) vs shooting, max(tip, mid) difference / L",
                      name, finest->elements),
          position_difference(*finest) / L, kAgreementOverL);
      gates.at_most(
          fmt::format("{}: FE (order 2, {} elements) vs shooting, tip rotation difference", name,
                      finest->elements),
          finest->diff.rotation_rad, kRotationBound_rad, "rad");
      if (!e.model->actuators.empty()) {
        // Bounds from the physics of the strings (constants above): de <= r_max dtheta, dT <= k de.
        const double r_max = max_string_offset_m(*e.model);
        const double elongation_bound_m = kElongationOverOffset * r_max;
        const double k_max = max_tca_stiffness_N_m(*e.model, e.reference.rk4.result);
        gates.at_most(
            fmt::format(
                "{}: FE (order 2, {} elements) vs shooting, max string elongation difference "
                "(bound {:.0e} r_max, r_max = {:.3e} m)",
                name, finest->elements, kElongationOverOffset, r_max),
            finest->diff.max_elongation_m, elongation_bound_m, "m");
        gates.at_most(
            fmt::format("{}: FE (order 2, {} elements) vs shooting, max string tension difference "
                        "(bound k_max x elongation bound, k_max = {:.4g} N/m)",
                        name, finest->elements, k_max),
            finest->diff.max_tension_N, k_max * elongation_bound_m, "N");
      }
      gates.at_most(name + ": reference error estimate / L", e.reference.self_error_m / L,
                    kReferenceOverL);
      const double reduction =
          position_difference(*quadratic.front()) / position_difference(*finest);
      gates.check(name + ": difference shrinks under refinement (order 2)",
                  reduction >= kMinReduction,
                  fmt::format("{:.2e} m ({} el.) -> {:.2e} m ({} el.): {:.0f}x",
                              position_difference(*quadratic.front()), quadratic.front()->elements,
                              position_difference(*finest), finest->elements, reduction),
                  fmt::format(">= {:.0f}x", kMinReduction));
    }
    gates.write_csv(out_dir);
    fmt::print("Wrote {}/crosscheck.csv and gates.csv ({:.1f} s)\n", out_dir, elapsed());
    return gates.finish();
  } catch (const std::exception& e) {
    fmt::print(stderr, "validate_crosscheck: error: {}\n", e.what());
    return 2;
  }
}
