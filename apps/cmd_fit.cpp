// `tcasim fit`: calibrates TCA material parameters to measured elongation curves by
// nonlinear least squares (src/tca/calibration.hpp).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/cli_util.hpp"
#include "apps/commands.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/output_file.hpp"
#include "rod/result.hpp"
#include "tca/calibration.hpp"
#include "tca/tca.hpp"

namespace tcasim::app {

namespace {

using nlohmann::json;

struct FitOptions {
  std::string data, tca_file, id, material, f12_form, out;
  std::vector<std::string> fit;
  int max_evaluations = 4000;
};

/// A property in the material file format: a number if constant, else a polynomial.
json property_json(const tca::PolynomialDegC& p) {
  if (p.coefficients.size() == 1) return p.coefficients[0];
  return json{{"polynomial_degC", p.coefficients}};
}

/// The material in the data-file format of data/materials (readable by the rod parser).
json material_json(const tca::Material& m, const std::string& source) {
  json j;
  j["name"] = m.name;
  j["source"] = source;
  j["reference_temperature_degC"] = units::K_to_degC(m.reference_temperature_K);
  j["youngs_modulus_Pa"] = property_json(m.youngs_modulus_Pa);
  j["shear_modulus_Pa"] = property_json(m.shear_modulus_Pa);
  if (m.diameter.type == tca::DiameterLaw::Type::kLinearExpansion) {
    j["diameter"] = json{{"linear_expansion_1_K", m.diameter.linear_expansion_1_K}};
  } else {
    j["diameter"] = json{{"ratio_polynomial_degC", m.diameter.ratio_polynomial.coefficients}};
  }
  if (m.f12_form) j["f12_form"] = tca::to_string(*m.f12_form);
  if (m.min_temperature_K > 0.0 || m.max_temperature_K < 1e9) {
    j["valid_range_degC"] = {units::K_to_degC(m.min_temperature_K),
                             units::K_to_degC(m.max_temperature_K)};
  }
  return j;
}

void run_fit(const FitOptions& o) {
  require_count(o.max_evaluations, "--max-evaluations", 1, kMaxEvaluations);
  std::vector<tca::FitParameter> fit;
  for (const std::string& list : o.fit) {
    for (const std::string& name :
         split_list(list, ',', "--fit", "must be comma-separated parameter names")) {
      fit.push_back(tca::parse_fit_parameter(name, "--fit"));
    }
  }
  const auto tca = select_tca(o.tca_file, o.id, o.material, o.f12_form);
  const auto data = tca::read_measurements_csv(o.data);
  tca::CalibrationOptions options;
  options.max_function_evaluations = o.max_evaluations;
  tca::Material initial = tca->material();
  // A fitted material records the f12 form it was identified with.
  initial.f12_form = tca->parameters().f12_form;
  const tca::CalibrationResult r = tca::calibrate(tca->parameters(), initial, data, fit, options);

  fmt::print("fit of {} to {} ({} points, f12_form {}): {}, {} iterations, {} evaluations\n",
             tca->material().name, o.data, data.size(), tca::to_string(tca->parameters().f12_form),
             tca::to_string(r.status), r.iterations, r.function_evaluations);
  fmt::print("{:<22} {:>14} {:>14} {:>14}\n", "parameter", "initial", "fitted", "std_error");
  for (std::size_t i = 0; i < r.values.size(); ++i) {
    fmt::print("{:<22} {:>14.6g} {:>14.6g} {:>14.3g}\n", tca::to_string(r.parameters[i]),
               r.initial_values[i], r.values[i], r.standard_errors[i]);
  }
  fmt::print("rms residual: {:.4g} m\n", r.rms_residual_m);
  if (r.status == tca::CalibrationStatus::kFailed) fmt::print("note: {}\n", r.message);

  if (!o.out.empty()) {
    json j;
    j["schema"] = "tcasim.fit/1";
    j["data"] = o.data;
    j["tca_file"] = o.tca_file;
    j["tca"] = o.id;
    j["f12_form"] = tca::to_string(tca->parameters().f12_form);
    j["status"] = tca::to_string(r.status);
    j["message"] = r.message;
    j["iterations"] = r.iterations;
    j["function_evaluations"] = r.function_evaluations;
    j["points"] = data.size();
    j["rms_residual_m"] = r.rms_residual_m;
    j["parameters"] = json::array();
    for (std::size_t i = 0; i < r.values.size(); ++i) {
      j["parameters"].push_back(
          {{"name", tca::to_string(r.parameters[i])},
           {"initial", r.initial_values[i]},
           {"value", r.values[i]},
           {"standard_error",
            std::isfinite(r.standard_errors[i]) ? json(r.standard_errors[i]) : json(nullptr)}});
    }
    j["material"] = material_json(
        r.material, fmt::format("tcasim fit of {} to {} (initial material: {})",
                                fmt::join(o.fit, ","), o.data, tca->material().source));
    rod::write_file_atomically(o.out, rod::format_json(j) + "\n", "--out");
  }
  if (r.status == tca::CalibrationStatus::kFailed) {
    throw DomainError("calibration failed: " + r.message);
  }
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto opts = std::make_shared<FitOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fit",
      "Fit TCA material parameters to measured elongation curves (Levenberg-Marquardt on the "
      "elongation residuals of Eqs. (1)-(5)); prints fitted values, standard errors "
      "(s^2 (J^T J)^-1), RMS residual, iterations and status.");
  cmd->add_option("--data", opts->data,
                  "CSV with columns temperature_degC, elongation_m and tension_N or load_g "
                  "(hanging mass, F = -m g); other columns are ignored")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--tca-file", opts->tca_file, "Scenario or TCA file defining the TCA geometry")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--tca", opts->id, "Id of the TCA in --tca-file (required if it has several)");
  cmd->add_option("--fit", opts->fit,
                  "Parameters to fit, comma separated: youngs_modulus, youngs_modulus_slope "
                  "(at the reference temperature), shear_modulus, shear_modulus_slope, expansion "
                  "(rho, or the scale of a ratio polynomial)")
      ->required();  // split by split_list (CLI11's delimiter drops a trailing empty item)
  cmd->add_option("--material", opts->material,
                  "Start from this shipped material instead of the TCA's own");
  cmd->add_option("--f12-form", opts->f12_form, "Eq. (4) factor: paper (8) or castigliano (16)")
      ->check(CLI::IsMember({"paper", "castigliano"}));
  cmd->add_option("--max-evaluations", opts->max_evaluations,
                  "Maximum model evaluations of the least-squares solver")
      ->capture_default_str();
  cmd->add_option("--out", opts->out,
                  "Write the result (schema tcasim.fit/1, with the fitted material in the "
                  "data/materials format) to this JSON file");
  cmd->callback([opts] { run_fit(*opts); });
}

}  // namespace tcasim::app
