// `tcasim tca`: elongation-temperature curve of one TCA under a constant load
// ([Pawlowski2019] Section II, Eqs. (1)-(5); the computation of validate_fig5_tca).
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/cli_util.hpp"
#include "apps/commands.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/scenario.hpp"
#include "study/options.hpp"
#include "tca/curve.hpp"
#include "tca/tca.hpp"

namespace tcasim::app {

namespace {

struct TcaOptions {
  std::string file, id, material, f12_form, out, temperatures;
  std::optional<double> tension_N, load_g;
};

void run_tca(const TcaOptions& o) {
  // Both given is rejected by CLI11 (excludes); here: neither (and the values' rules).
  const double tension_N = study::tca_tension_N(o.tension_N, o.load_g, study::OptionNames::kFlags);
  const auto tca = select_tca(o.file, o.id, o.material, o.f12_form);
  const std::vector<double> temps_degC = parse_range(o.temperatures, "--temperatures-degC");
  const std::vector<double> temps_K =
      study::temperatures_K(temps_degC, "temperatures_degC", study::OptionNames::kFlags);
  const auto curve = tca::elongation_curve(*tca, tension_N, temps_K);

  Output output(o.out);
  std::ostream& out = output.stream();
  fmt::print(out, "temperature_degC,elongation_m,tension_N,pitch_angle_deg,coils_closed\n");
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const tca::CurvePoint& p = curve[i];
    fmt::print(out, "{},{},{},{},{}\n", temps_degC[i], p.elongation_m, p.tension_N,
               units::rad_to_deg(p.pitch_angle_rad), p.coils_closed ? 1 : 0);
  }
  output.commit();
}

}  // namespace

void add_tca_command(CLI::App& app) {
  auto opts = std::make_shared<TcaOptions>();
  opts->temperatures = "25:160:5";
  CLI::App* cmd = app.add_subcommand(
      "tca",
      "Elongation of one TCA under a constant load over a temperature range ([Pawlowski2019] "
      "Eqs. (1)-(5), closed coils: an extension TCA stays at its closed length until the "
      "onset). Prints CSV temperature_degC,elongation_m,tension_N,pitch_angle_deg,coils_closed.");
  cmd->add_option("file", opts->file,
                  "Scenario or TCA file (schema tcasim.tcas/1) defining the TCA")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--tca", opts->id, "Id of the TCA in FILE (required if FILE defines several)");
  auto* tension = cmd->add_option("--tension-N", opts->tension_N,
                                  "Constant tension F [N], positive pulls the TCA longer");
  auto* load = cmd->add_option("--load-g", opts->load_g,
                               "Hanging mass [g] compressing the TCA: F = -m g (add friction "
                               "equivalents to it, e.g. 5 + 2.5 = 7.5 for Fig. 5)");
  tension->excludes(load);
  cmd->add_option("--temperatures-degC", opts->temperatures,
                  "Temperatures START:STOP:STEP (inclusive) or one value [degC]")
      ->capture_default_str();
  cmd->add_option("--f12-form", opts->f12_form,
                  "Override the Eq. (4) factor: paper (8) or castigliano (16)")
      ->check(CLI::IsMember({"paper", "castigliano"}));
  cmd->add_option("--material", opts->material,
                  "Override the TCA's material with a shipped one (data/materials/NAME.json)");
  cmd->add_option("--out", opts->out, "Write the CSV to this file instead of stdout");
  cmd->callback([opts] { run_tca(*opts); });
}

}  // namespace tcasim::app
