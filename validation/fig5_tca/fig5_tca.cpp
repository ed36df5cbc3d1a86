// validate_fig5_tca: elongation-temperature curves of the two extension TCAs of Fig. 5.
//
// What it checks: the TCA model of [Pawlowski2019] Section II (Eqs. (1)-(5), closed coils,
// docs/conventions.md "TCA data of the paper's experiments") on the experiment of Section V-A /
// Fig. 5: the 3-thread TCA (l = 497 mm, L = 110 mm, D = 2 mm, N = 300) and the 4-thread TCA (l =
// 471 mm, L = 110 mm, D = 2.13 mm, N = 259), hanging loads 5 g + 2.5 g and 10 g + 5 g friction
// equivalents (F = -m g), 25..160 degC in steps of 5 degC, for every shipped material and both Eq.
// (4) factors (paper 8, castigliano 16). Reference: [Pawlowski2019] Fig. 5 (measured curves, given
// only as a plot; the paper's material values are not available, so no numeric comparison with the
// figure is gated). Gate (only what the physics guarantees):
//   1. the elongation is exactly 0 (coils closed) at every temperature below the onset and
//      positive above it;
//   2. the elongation is non-decreasing with temperature;
//   3. the heavier load has a later (or equal) onset than the lighter one;
//   4. with --tcasim EXE: `tcasim tca` prints the same numbers (same library path through
//      the file parser, the --load-g conversion and the CSV printer), to 1e-12 relative.
// Output: OUT/fig5_curves.csv, OUT/fig5_table.csv; a table on stdout; exit 1 if a gate fails.
// Sample commands:
//   validate_fig5_tca --out-dir out/fig5                 (full grid, 5 degC)
//   validate_fig5_tca --quick --out-dir /tmp/fig5 --tcasim build/apps/tcasim
//   /usr/bin/python3 scripts/plot_fig5.py out/fig5/fig5_curves.csv out/fig5/fig5.png
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/grid.hpp"
#include "common/units.hpp"
#include "rod/output_file.hpp"
#include "rod/scenario.hpp"
#include "tca/curve.hpp"
#include "tca/tca.hpp"
#include "validation/common/gates.hpp"

namespace {

using namespace tcasim;

/// The CSV printed by `tcasim tca` is shortest-round-trip: equal doubles print equal;
/// 1e-12 relative allows for a different but equivalent evaluation order only.
constexpr double kCliRelTol = 1e-12;

struct Case {
  std::string tca_id;
  double load_g;  ///< hanging mass including the friction equivalent
  std::string material;
  tca::F12Form form;
  std::vector<double> temperatures_degC;
  std::vector<tca::CurvePoint> curve;
  std::optional<double> onset_K;
};

std::string case_name(const Case& c) {
  return fmt::format("{} {} g {} {}", c.tca_id, c.load_g, c.material, tca::to_string(c.form));
}

/// Runs `tcasim tca` and parses its CSV (elongation per temperature).
std::vector<double> run_cli(const std::string& exe, const std::string& file, const Case& c,
                            const std::string& grid) {
  const std::string cmd = fmt::format(
      "'{}' tca '{}' --tca {} --load-g {} --material {} --f12-form {} "
      "--temperatures-degC {}",
      exe, file, c.tca_id, c.load_g, c.material, tca::to_string(c.form), grid);
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run " + cmd);
  std::string text;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) text += buffer;
  const int status = pclose(pipe);
  if (status != 0) throw std::runtime_error(fmt::format("`{}` exited with status {}", cmd, status));
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (line != "temperature_degC,elongation_m,tension_N,pitch_angle_deg,coils_closed") {
    throw std::runtime_error("unexpected header from tcasim tca: " + line);
  }
  std::vector<double> elongations;
  while (std::getline(in, line)) {
    const auto c1 = line.find(','), c2 = line.find(',', c1 + 1);
    elongations.push_back(std::stod(line.substr(c1 + 1, c2 - c1 - 1)));
  }
  return elongations;
}

int run(int argc, char** argv) {
  CLI::App app{"validate_fig5_tca: elongation vs temperature of the Fig. 5 extension TCAs"};
  bool quick = false;
  std::string out_dir = "validation-out/validate_fig5_tca";
  std::string tcas_file = std::string(TCASIM_SOURCE_DIR) + "/validation/scenarios/fig5-tcas.json";
  std::vector<std::string> materials = {"silver-nylon-sun2022", "silver-nylon-castigliano"};
  std::string tcasim_exe;
  app.add_flag("--quick", quick, "Coarse temperature grid (15 degC) for the quick test");
  app.add_option("--out-dir", out_dir, "Folder for fig5_curves.csv and fig5_table.csv")
      ->capture_default_str();
  app.add_option("--tcas-file", tcas_file, "TCA file with the ids three-thread and four-thread")
      ->capture_default_str();
  app.add_option("--materials", materials, "Shipped materials to run (comma separated)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--tcasim", tcasim_exe,
                 "Path of the tcasim executable: also check that `tcasim tca` reproduces the "
                 "curves (gate 4)");
  CLI11_PARSE(app, argc, argv);

  const double step_degC = quick ? 15.0 : 5.0;
  const double t_lo_degC = 25.0, t_hi_degC = 160.0;
  const std::string grid_text = fmt::format("{}:{}:{}", t_lo_degC, t_hi_degC, step_degC);

  fmt::print("Step 1: read the TCAs from {}\n", tcas_file);
  const auto tcas = rod::read_tcas(tcas_file);
  const std::vector<std::string> ids = {"three-thread", "four-thread"};
  for (const auto& id : ids) {
    if (tcas.count(id) == 0) throw InputError("--tcas-file", tcas_file, "must define TCA " + id);
    const auto& t = *tcas.at(id);
    fmt::print("  {}: alpha0 = {:.2f} deg, n = {:.1f} coils, d0 = {:.3f} mm, phi0 = {:.1f} rad\n",
               id, units::rad_to_deg(t.initial_pitch_angle_rad()), t.coil_count(),
               t.initial_fiber_diameter_m() * 1e3, t.initial_twist_rad());
  }

  fmt::print("Step 2: load the materials\n");
  std::map<std::string, tca::Material> mats;
  for (const auto& name : materials) {
    mats[name] = rod::load_material(name, "--materials");
    fmt::print("  {}: {}\n", name, mats[name].source.substr(0, 100));
  }

  fmt::print("Step 3: elongation curves, {}..{} degC step {} degC\n", t_lo_degC, t_hi_degC,
             step_degC);
  const std::vector<double> temps_degC = inclusive_grid(t_lo_degC, t_hi_degC, step_degC, "grid");
  std::vector<double> temps_K;
  for (const double t : temps_degC) temps_K.push_back(units::degC_to_K(t));
  std::vector<Case> cases;
  for (const auto& id : ids) {
    for (const double load_g : {5.0 + 2.5, 10.0 + 5.0}) {
      for (const auto& name : materials) {
        for (const tca::F12Form form : {tca::F12Form::kPaper, tca::F12Form::kCastigliano}) {
          tca::Parameters p = tcas.at(id)->parameters();
          p.f12_form = form;
          const tca::Tca model(p, mats.at(name));
          const double F = tca::hanging_load_tension_N(units::g_to_kg(load_g));
          Case c{id,
                 load_g,
                 name,
                 form,
                 temps_degC,
                 tca::elongation_curve(model, F, temps_K),
                 model.onset_temperature(F, temps_K.front(), temps_K.back())};
          cases.push_back(std::move(c));
        }
      }
    }
  }

  fmt::print("Step 4: gates\n");
  validation::Gates gates("validate_fig5_tca");
  for (const Case& c : cases) {
    // Gates 1 and 2, aggregated over the curve: count the points that break them.
    int closed_violations = 0, open_violations = 0, decreases = 0;
    double worst_below_m = 0.0;
    for (std::size_t i = 0; i < c.curve.size(); ++i) {
      const auto& p = c.curve[i];
      const bool below = !c.onset_K || p.temperature_K < *c.onset_K;
      if (below && !(p.elongation_m == 0.0 && p.coils_closed)) {
        ++closed_violations;
        worst_below_m = std::max(worst_below_m, std::abs(p.elongation_m));
      } else if (!below && p.temperature_K > *c.onset_K &&
                 !(p.elongation_m > 0.0 && !p.coils_closed)) {
        ++open_violations;
      }
      if (i > 0 && p.elongation_m < c.curve[i - 1].elongation_m) ++decreases;
    }
    gates.check(case_name(c) + ": zero elongation below the onset, positive above",
                closed_violations == 0 && open_violations == 0,
                fmt::format("{} points wrong below (max |delta| {:.3e} m), {} above",
                            closed_violations, worst_below_m, open_violations),
                "0 points");
    gates.check(case_name(c) + ": elongation non-decreasing with temperature", decreases == 0,
                fmt::format("{} decreases", decreases), "0 decreases");
  }
  for (const Case& light : cases) {
    for (const Case& heavy : cases) {
      if (heavy.tca_id != light.tca_id || heavy.material != light.material ||
          heavy.form != light.form || heavy.load_g <= light.load_g) {
        continue;
      }
      const double inf = std::numeric_limits<double>::infinity();
      const double t_heavy = heavy.onset_K.value_or(inf), t_light = light.onset_K.value_or(inf);
      gates.check(
          fmt::format("{}: onset not earlier than with {} g", case_name(heavy), light.load_g),
          t_heavy >= t_light,
          fmt::format("{:.2f} degC vs {:.2f} degC", units::K_to_degC(t_heavy),
                      units::K_to_degC(t_light)),
          "heavier >= lighter");
    }
  }
  if (!tcasim_exe.empty()) {
    fmt::print("  gate 4: `tcasim tca` ({}) against the library curves\n", tcasim_exe);
    for (const Case& c : cases) {
      const auto cli = run_cli(tcasim_exe, tcas_file, c, grid_text);
      double worst = cli.size() == c.curve.size() ? 0.0 : std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < std::min(cli.size(), c.curve.size()); ++i) {
        const double ref = c.curve[i].elongation_m;
        const double rel = ref == 0.0 ? std::abs(cli[i]) : std::abs(cli[i] - ref) / std::abs(ref);
        worst = std::max(worst, rel);
      }
      gates.at_most(
          case_name(c) + ": `tcasim tca` reproduces the library curve (relative difference)", worst,
          kCliRelTol);
    }
  }

  fmt::print("Step 5: write CSV to {}\n", out_dir);
  std::filesystem::create_directories(out_dir);
  tcasim::rod::AtomicOutput curves(out_dir + "/fig5_curves.csv", "fig5 curves csv");
  fmt::print(curves,
             "tca,load_g,material,f12_form,temperature_degC,elongation_m,pitch_angle_deg,"
             "coils_closed\n");
  tcasim::rod::AtomicOutput table(out_dir + "/fig5_table.csv", "fig5 table csv");
  fmt::print(table,
             "tca,load_g,material,f12_form,onset_temperature_degC,elongation_at_160_degC_m\n");
  for (const Case& c : cases) {
    for (std::size_t i = 0; i < c.curve.size(); ++i) {
      fmt::print(curves, "{},{},{},{},{},{},{},{}\n", c.tca_id, c.load_g, c.material,
                 tca::to_string(c.form), c.temperatures_degC[i], c.curve[i].elongation_m,
                 units::rad_to_deg(c.curve[i].pitch_angle_rad), c.curve[i].coils_closed ? 1 : 0);
    }
    fmt::print(table, "{},{},{},{},{},{}\n", c.tca_id, c.load_g, c.material, tca::to_string(c.form),
               c.onset_K ? fmt::format("{:.4f}", units::K_to_degC(*c.onset_K)) : "nan",
               c.curve.back().elongation_m);
  }
  curves.commit();
  table.commit();

  fmt::print("Step 6: table\n");
  fmt::print("{:<13} {:>6} {:<25} {:<12} {:>10} {:>14}\n", "tca", "load_g", "material", "f12_form",
             "onset_degC", "delta_160_mm");
  for (const Case& c : cases) {
    fmt::print("{:<13} {:>6} {:<25} {:<12} {:>10} {:>14.3f}\n", c.tca_id, c.load_g, c.material,
               tca::to_string(c.form),
               c.onset_K ? fmt::format("{:.2f}", units::K_to_degC(*c.onset_K)) : "none",
               c.curve.back().elongation_m * 1e3);
  }
  gates.write_csv(out_dir);
  return gates.finish();
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "validate_fig5_tca: error: {}\n", e.what());
    return 2;
  }
}
