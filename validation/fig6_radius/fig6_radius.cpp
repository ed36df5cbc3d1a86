// validate_fig6_radius: bending radius against temperature of the paper's two soft
// manipulators ([Pawlowski2019] Section V-B, Fig. 6), solved by the Cosserat shooting solver.
//
// What it checks
//   The circular manipulator (8 mm diameter, 40 mm, one extension TCA 3 mm off-axis, with
//   initial bending) and the square one (10 mm side, 40 mm, U-shaped TCA = two strings 3 mm
//   off-axis, straight), heated from 25 to 150 degC in 5 degC steps (warm-started sweep),
//   with every shipped TCA material set. The radius is the paper's three-point inner-edge
//   radius (base, middle, tip).
// Reference
//   The paper's measured radii are only printed as a figure (no numbers); this program
//   reports the predicted curves and gates only what physics guarantees.
// Gates
//   1. every point converges;
//   2. at the reference temperature (25 degC) without gravity the TCA carries no tension
//      (|T| <= 1e-12 N), the square manipulator is straight (no radius) and the circular one
//      keeps its reference shape: inner-edge radius 1/|omega*| - D/2 to 1e-9 relative
//      (closed form of an unloaded precurved rod);
//   2b. with gravity the circular manipulator starts bent (finite radius at 25 degC).
//      (The square one is not gated straight with gravity: its own weight, 26 % of the
//      self-buckling load of this soft body, compresses it against the TCA, which bends it.)
//   3. above the reference temperature the radius decreases strictly with temperature
//      (the heated extension TCA pushes harder and bends the body further).
// Usage
//   validate_fig6_radius --out-dir out/fig6            (full: 25..150 degC step 5)
//   validate_fig6_radius --quick --out-dir /tmp/fig6   (25..150 degC step 25)
//   scripts/plot_fig6.py out/fig6                      (fig6.png from fig6_radius.csv)
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/units.hpp"
#include "cosserat/shooting.hpp"
#include "rod/output_file.hpp"
#include "rod/scenario.hpp"
#include "validation/common/gates.hpp"

namespace {

using tcasim::units::degC_to_K;

/// An unloaded, unheated TCA carries no tension: only round-off of the shooting residual remains.
constexpr double kZeroTension_N = 1e-12;
/// The unloaded precurved rod is an exact arc; the solver resolves it to its Newton tolerance.
constexpr double kRadiusRelTol = 1e-9;

struct Point {
  double temperature_degC;
  tcasim::rod::Result result;
};

/// The model with every TCA rebuilt on a shipped material (parameters unchanged).
tcasim::rod::RodModel with_material(const tcasim::rod::RodModel& model,
                                    const std::string& material) {
  return tcasim::rod::with_tca_material(model, tcasim::rod::load_material(material, "material"));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Paper Fig. 6: bending radius vs temperature of the circular and square manipulators"};
  bool quick = false;
  std::string out_dir = "fig6-out";
  std::string scenario_dir = TCASIM_SCENARIO_DIR;
  app.add_flag("--quick", quick, "coarse temperature grid (seconds)");
  app.add_option("--out-dir", out_dir, "output folder for CSV files");
  app.add_option("--scenario-dir", scenario_dir, "folder with the shipped scenarios");
  CLI11_PARSE(app, argc, argv);

  try {
    std::filesystem::create_directories(out_dir);
    const double step_degC = quick ? 25.0 : 5.0;
    const std::vector<std::string> manipulators = {"circular-manipulator", "square-manipulator"};
    const std::vector<std::string> materials = {"silver-nylon-sun2022", "silver-nylon-castigliano"};

    fmt::print("Step 1: sweep 25..150 degC (step {} degC), {} manipulators x {} materials\n",
               step_degC, manipulators.size(), materials.size());
    tcasim::rod::AtomicOutput csv(out_dir + "/fig6_radius.csv", "fig6 csv");
    csv << "manipulator,material,temperature_degC,converged,iterations,bending_radius_m,tip_x_m,"
           "tip_y_m,tip_z_m,tension_N,elongation_m\n";
    std::map<std::pair<std::string, std::string>, std::vector<Point>> curves;
    std::map<std::pair<std::string, std::string>, tcasim::rod::Result> reference_results;
    std::map<std::string, double> reference_curvature_1_m;
    for (const auto& name : manipulators) {
      const tcasim::rod::RodModel base =
          tcasim::rod::read_scenario(scenario_dir + "/" + name + ".json");
      reference_curvature_1_m[name] = base.reference_curvature_at(0.0).norm();
      for (const auto& material : materials) {
        const tcasim::rod::RodModel model = with_material(base, material);
        tcasim::cosserat::Options options;
        options.integrator.steps = 64;
        tcasim::cosserat::ShootingSolver solver(model, options);
        auto actuation = tcasim::rod::Loads::from_model(model);
        tcasim::cosserat::Solution solution;
        auto& curve = curves[{name, material}];
        {  // gate 2: reference temperature, no gravity
          auto unloaded = actuation;
          unloaded.gravity_W_m_s2.setZero();
          for (std::size_t i = 0; i < model.actuators.size(); ++i) {
            if (model.actuators[i].drive.type == tcasim::rod::Drive::Type::kTca) {
              unloaded.set_temperature_K(i, degC_to_K(25.0));
            }
          }
          tcasim::cosserat::Solution fresh;
          const auto summary = solver.solve(unloaded, fresh);
          reference_results[{name, material}] = solver.make_result(unloaded, fresh, summary);
        }
        for (double t = 25.0; t <= 150.0 + 1e-9; t += step_degC) {
          for (std::size_t i = 0; i < model.actuators.size(); ++i) {
            if (model.actuators[i].drive.type == tcasim::rod::Drive::Type::kTca) {
              actuation.set_temperature_K(i, degC_to_K(t));
            }
          }
          const auto summary = solver.solve(actuation, solution);
          curve.push_back({t, solver.make_result(actuation, solution, summary)});
          const auto& r = curve.back().result;
          fmt::print(
              csv, "{},{},{},{},{},{},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e}\n", name, material, t,
              r.converged ? 1 : 0, r.iterations,
              r.bending_radius_m ? fmt::format("{:.12e}", *r.bending_radius_m) : std::string(),
              r.tip_position_W_m.x(), r.tip_position_W_m.y(), r.tip_position_W_m.z(),
              r.actuators.at(0).tension_N, r.actuators.at(0).elongation_m);
        }
      }
    }
    csv.commit();

    fmt::print("Step 2: table (bending radius [mm]; '-' = straight)\n");
    fmt::print("{:<22} {:<26}", "manipulator", "material");
    const std::vector<double> shown = {25, 50, 75, 100, 125, 150};
    for (double t : shown) fmt::print(" {:>8}", fmt::format("{}C", t));
    fmt::print("\n");
    for (const auto& [key, curve] : curves) {
      fmt::print("{:<22} {:<26}", key.first, key.second);
      for (double t : shown) {
        std::string cell = "?";
        for (const auto& p : curve) {
          if (std::abs(p.temperature_degC - t) < 1e-9) {
            cell = p.result.bending_radius_m
                       ? fmt::format("{:.2f}", 1e3 * *p.result.bending_radius_m)
                       : "-";
          }
        }
        fmt::print(" {:>8}", cell);
      }
      fmt::print("\n");
    }

    fmt::print("Step 3: gates\n");
    tcasim::validation::Gates gates("validate_fig6_radius");
    // Declared cases: every manipulator x material curve, each on the whole 25..150 degC grid.
    const auto grid_points = static_cast<std::size_t>(std::lround(125.0 / step_degC)) + 1;
    gates.expect_count("curves (manipulator x material)", curves.size(),
                       manipulators.size() * materials.size());
    for (const auto& [key, curve] : curves) {
      const std::string label = key.first + " / " + key.second;
      gates.expect_count(label + " temperatures", curve.size(), grid_points);
      int unconverged = 0;
      for (const auto& p : curve) unconverged += p.result.converged ? 0 : 1;
      gates.check(label + ": every point converges", unconverged == 0,
                  fmt::format("{} of {} did not", unconverged, curve.size()), "0");
      const bool circular = key.first == "circular-manipulator";
      const auto& ref = reference_results.at(key);
      const double ref_tension = ref.actuators.at(0).tension_N;
      gates.check(label + ": no tension at 25 degC without gravity",
                  ref.converged && std::abs(ref_tension) <= kZeroTension_N,
                  fmt::format("|T| = {:.3e} N", ref_tension),
                  fmt::format("<= {:.0e} N", kZeroTension_N));
      if (circular) {
        // Inner edge of an arc of radius R at half width h toward its center: radius R - h.
        const double kappa = reference_curvature_1_m.at(key.first);
        const double expected = 1.0 / kappa - 0.5 * 0.008;
        const double got = ref.bending_radius_m.value_or(0.0);
        gates.check(label + ": unloaded reference shape, radius vs closed form 1/|omega*| - D/2",
                    std::abs(got - expected) <= kRadiusRelTol * expected,
                    fmt::format("relative difference {:.3e} ({:.9f} m vs {:.9f} m)",
                                std::abs(got - expected) / expected, got, expected),
                    fmt::format("<= {:.0e}", kRadiusRelTol));
        const auto& first = curve.front().result;
        gates.check(
            label + ": starts bent at 25 degC with gravity", first.bending_radius_m.has_value(),
            first.bending_radius_m ? fmt::format("radius {:.2f} mm", 1e3 * *first.bending_radius_m)
                                   : "straight",
            "a finite radius");
      } else {
        gates.check(label + ": straight at 25 degC without gravity",
                    !ref.bending_radius_m.has_value(),
                    ref.bending_radius_m ? fmt::format("radius {:.3e} m", *ref.bending_radius_m)
                                         : "straight",
                    "no radius");
      }
      bool decreasing = true;
      std::string where;
      for (std::size_t k = 1; k < curve.size(); ++k) {
        const auto& a = curve[k - 1].result.bending_radius_m;
        const auto& b = curve[k].result.bending_radius_m;
        if (k == 1 && !a && b) continue;  // a straight start: no radius to compare with
        if (!a || !b || !(*b < *a)) {
          decreasing = false;
          where = fmt::format(" (not at {} -> {} degC)", curve[k - 1].temperature_degC,
                              curve[k].temperature_degC);
          break;
        }
      }
      gates.check(label + ": radius decreases strictly with temperature", decreasing,
                  decreasing ? "strictly decreasing" : "not" + where, "strictly decreasing");
    }
    gates.write_csv(out_dir);
    fmt::print("Wrote {}/fig6_radius.csv and gates.csv\n", out_dir);
    return gates.finish();
  } catch (const std::exception& e) {
    fmt::print(stderr, "validate_fig6_radius: error: {}\n", e.what());
    return 2;
  }
}
