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

#include "apps/commands.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/scenario.hpp"
#include "tca/curve.hpp"
#include "tca/tca.hpp"

namespace tcasim::app {

/// Picks one TCA of a scenario or TCA file (shared with `tcasim fit`), applying the
/// optional material and f12-form overrides. Throws InputError naming the flag.
std::shared_ptr<const tca::Tca> select_tca(const std::string& file, const std::string& id,
                                           const std::string& material_name,
                                           const std::string& f12_form) {
  const auto tcas = rod::read_tcas(file);
  std::string ids;
  for (const auto& [name, t] : tcas) ids += (ids.empty() ? "" : ", ") + name;
  std::shared_ptr<const tca::Tca> chosen;
  if (id.empty()) {
    require(tcas.size() == 1, "--tca", "(missing)",
            fmt::format("is required: {} defines {} TCAs: {}", file, tcas.size(), ids));
    chosen = tcas.begin()->second;
  } else {
    const auto it = tcas.find(id);
    require(it != tcas.end(), "--tca", id, fmt::format("is not a TCA of {} (it has: {})", file, ids));
    chosen = it->second;
  }
  if (material_name.empty() && f12_form.empty()) return chosen;
  tca::Parameters p = chosen->parameters();
  tca::Material m = chosen->material();
  if (!material_name.empty()) {
    m = rod::load_material(material_name, "--material");
    // Without an explicit form, the overriding material's own form applies (as in a file).
    if (f12_form.empty() && m.f12_form) p.f12_form = *m.f12_form;
  }
  if (!f12_form.empty()) {
    p.f12_form = f12_form == "paper" ? tca::F12Form::kPaper : tca::F12Form::kCastigliano;
  }
  return std::make_shared<const tca::Tca>(p, std::move(m));
}

namespace {

/// Parses "A:B:S" (inclusive grid) or "A" [degC].
std::vector<double> parse_temperatures_degC(const std::string& text) {
  constexpr const char* kKey = "--temperatures-degC";
  std::vector<double> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = text.find(':', start);
    const std::string piece = text.substr(start, colon == std::string::npos ? std::string::npos
                                                                            : colon - start);
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(piece, &used);
    } catch (const std::exception&) {
      used = std::string::npos;
    }
    require(used == piece.size() && !piece.empty(), kKey, text,
            "must be START:STOP:STEP or a single temperature, in degC");
    parts.push_back(v);
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  require(parts.size() == 1 || parts.size() == 3, kKey, text,
          "must be START:STOP:STEP or a single temperature, in degC");
  const std::vector<double> degC =
      parts.size() == 1 ? parts : tca::temperature_grid(parts[0], parts[1], parts[2], kKey);
  for (const double t : degC) {
    require(t > -units::kZeroCelsius_K, kKey, text, "contains a temperature below absolute zero");
  }
  return degC;
}

struct TcaOptions {
  std::string file, id, material, f12_form, out, temperatures;
  std::optional<double> tension_N, load_g;
};

void run_tca(const TcaOptions& o) {
  // Both given is rejected by CLI11 (excludes); here: neither.
  require(o.tension_N.has_value() || o.load_g.has_value(), "--tension-N", "(missing)",
          "is required unless --load-g is given (give exactly one)");
  const auto tca = select_tca(o.file, o.id, o.material, o.f12_form);
  const std::vector<double> temps_degC = parse_temperatures_degC(o.temperatures);
  std::vector<double> temps_K;
  for (const double t : temps_degC) temps_K.push_back(units::degC_to_K(t));
  double tension_N = 0.0;
  if (o.load_g) {
    require(*o.load_g >= 0.0, "--load-g", *o.load_g, "must be >= 0 (a hanging mass)");
    tension_N = tca::hanging_load_tension_N(units::g_to_kg(*o.load_g));
  } else {
    tension_N = *o.tension_N;
  }
  const auto curve = tca::elongation_curve(*tca, tension_N, temps_K);

  std::ofstream file;
  if (!o.out.empty()) {
    file.open(o.out);
    require(static_cast<bool>(file), "--out", o.out, "cannot be opened for writing");
  }
  std::ostream& out = o.out.empty() ? std::cout : file;
  fmt::print(out, "temperature_degC,elongation_m,tension_N,pitch_angle_deg,coils_closed\n");
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const tca::CurvePoint& p = curve[i];
    fmt::print(out, "{},{},{},{},{}\n", temps_degC[i], p.elongation_m,
               p.tension_N, units::rad_to_deg(p.pitch_angle_rad), p.coils_closed ? 1 : 0);
  }
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
  cmd->add_option("file", opts->file, "Scenario or TCA file (schema tcasim.tcas/1) defining the TCA")
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
