// `tcasim inverse` and `tcasim grasp`: inverse kinetostatics ([Pawlowski2019] Section IV)
// and the grasp temperature of a blocked finger (Section V-D, Eqs. (43)-(44)).
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "apps/cli_util.hpp"
#include "apps/commands.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "cosserat/inverse.hpp"
#include "rod/result.hpp"
#include "rod/scenario.hpp"
#include "study/inverse_document.hpp"
#include "study/options.hpp"

namespace tcasim::app {

namespace {

/// Exit code of a solve that ran but did not converge (the output file is still written).
constexpr int kExitNotConverged = 4;

using study::OptionNames;

/// Runs f, re-issuing the library's bound error under the command-line flag's name.
template <class F>
auto with_flag_names(F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    study::rethrow_under_option_name(e, OptionNames::kFlags);
  }
}

void write_json(const nlohmann::json& j, const std::string& path) {
  Output out(path);
  out.stream() << rod::format_json(j) << "\n";
  out.commit();
}

}  // namespace

void add_inverse_command(CLI::App& app) {
  struct Flags {
    std::string scenario, target, actuators, out;
    std::optional<double> max_t_degC;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand(
      "inverse",
      "Inverse kinetostatics: actuation (temperatures or tensions) that puts the tip at a target");
  cmd->add_option("scenario", flags->scenario, "scenario file (tcasim.scenario/1), free tip")
      ->required();
  cmd->add_option("--target-m", flags->target, "target tip position X,Y,Z [m], world frame")
      ->required();
  cmd->add_option("--actuators", flags->actuators,
                  "comma-separated actuator names to adjust (default: all)");
  cmd->add_option("--max-temperature-degC", flags->max_t_degC,
                  "upper temperature bound [degC] (default: the material's valid maximum)");
  cmd->add_option("--out", flags->out, "JSON file (default: stdout)");
  cmd->callback([flags] {
    const rod::RodModel model = rod::read_scenario(flags->scenario);
    if (model.tip_constraint) {
      throw InputError(
          "scenario tip_constraint", "(present)",
          "must be absent for `tcasim inverse` (it moves a free tip; use `tcasim grasp` "
          "for a blocked tip)");
    }
    cosserat::InverseOptions o;
    const Eigen::Vector3d target = parse_vector3(flags->target, "--target-m");
    o.actuators = actuator_indices(model, flags->actuators, "--actuators");
    if (o.actuators.empty()) {
      throw InputError("--actuators", flags->actuators, "the scenario has no actuator to adjust");
    }
    o.max_temperature_K = study::max_temperature_K(flags->max_t_degC, OptionNames::kFlags);
    const study::DocumentRun r =
        with_flag_names([&] { return study::inverse_document(model, target, o); });
    write_json(r.document, flags->out);
    if (!r.converged) {
      fmt::print(stderr, "tcasim inverse: not converged ({}): {}\n", r.status, r.message);
      throw CLI::RuntimeError(kExitNotConverged);
    }
  });
}

void add_grasp_command(CLI::App& app) {
  struct Flags {
    std::string scenario, out;
    double mass_g = 0.0, friction = 0.0;
    long long fingers = 0;
    std::optional<double> max_t_degC;
  };
  auto flags = std::make_shared<Flags>();
  auto* cmd = app.add_subcommand("grasp",
                                 "Grasp temperature: TCA temperature at which a blocked finger's "
                                 "normal force reaches m g/(mu n)");
  cmd->add_option("scenario", flags->scenario,
                  "scenario of one finger with a tip_constraint and its contact normal")
      ->required();
  cmd->add_option("--mass-g", flags->mass_g, "grasped mass [g]")->required();
  cmd->add_option("--friction", flags->friction, "friction coefficient mu finger/object")
      ->required();
  cmd->add_option("--fingers", flags->fingers, "number of fingers n")
      ->check(fits_64_bits())
      ->required();
  cmd->add_option("--max-temperature-degC", flags->max_t_degC,
                  "upper temperature bound [degC] (default: the material's valid maximum)");
  cmd->add_option("--out", flags->out, "JSON file (default: stdout)");
  cmd->callback([flags] {
    study::check_grasp_options(flags->mass_g, flags->friction, flags->fingers, OptionNames::kFlags);
    const rod::RodModel model = rod::read_scenario(flags->scenario);
    if (!model.tip_constraint || !model.tip_constraint->normal_W) {
      throw InputError(flags->scenario + ": tip_constraint.normal", "(missing)",
                       "`tcasim grasp` needs a tip_constraint with a \"normal\" (the contact "
                       "direction from the finger toward the object)");
    }
    const double max_t_K = study::max_temperature_K(flags->max_t_degC, OptionNames::kFlags);
    const study::DocumentRun r = with_flag_names([&] {
      return study::grasp_document(model, flags->mass_g, flags->friction,
                                   static_cast<int>(flags->fingers), max_t_K);
    });
    write_json(r.document, flags->out);
    if (!r.converged) {
      fmt::print(stderr, "tcasim grasp: not converged: {}\n", r.message);
      throw CLI::RuntimeError(kExitNotConverged);
    }
  });
}

}  // namespace tcasim::app
