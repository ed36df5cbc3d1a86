// tcasim.inverse, tcasim.grasp and tcasim.tca_curve: the documents of `tcasim inverse` and
// `tcasim grasp` (built by study/inverse_document.hpp for both) and the table of `tcasim tca`,
// built by the same library calls.
#include "cosserat/inverse.hpp"

#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "json_convert.hpp"
#include "rod/result.hpp"
#include "rod/scenario.hpp"
#include "rod/tca_choice.hpp"
#include "study/inverse_document.hpp"
#include "study/options.hpp"
#include "tca/curve.hpp"
#include "tca/tca.hpp"

namespace tcasim::python {

namespace {

using study::OptionNames;

/// max_temperature_degC -> K (NaN when None: the material's maximum).
double max_temperature_K(const py::object& t_degC) {
  return study::max_temperature_K(optional_number_arg(t_degC, "max_temperature_degC"),
                                  OptionNames::kPython);
}

/// target_m: three finite numbers (x, y, z) [m].
Eigen::Vector3d target_vector(const py::object& target_m) {
  const std::vector<double> v = number_list_arg(target_m, "target_m");
  const auto text = [&] { return py::repr(target_m).cast<std::string>(); };
  if (v.size() != 3) throw InputError("target_m", text(), "must be three finite numbers");
  const Eigen::Vector3d t(v[0], v[1], v[2]);
  if (!t.allFinite()) throw InputError("target_m", text(), "must be three finite numbers");
  return t;
}

/// Actuator names (a list, or one comma-separated string; None: all) -> model indices.
std::vector<int> actuator_list(const rod::RodModel& model, const py::object& names) {
  std::string text;
  if (!names.is_none()) {
    if (PyUnicode_Check(names.ptr())) {
      text = names.cast<std::string>();
    } else {
      for (const auto& n : names.cast<std::vector<std::string>>())
        text += (text.empty() ? "" : ",") + n;
    }
  }
  return study::actuator_indices(model, text, "actuators");
}

/// The document as a dict; tcasim.SolverError carrying it when `check` and not converged.
py::object checked(const study::DocumentRun& r, bool check, const std::string& what) {
  py::object out = to_python(r.document);
  if (check && !r.converged) {
    throw_solver_error(fmt::format("tcasim.{}: not converged ({}): {}", what, r.status, r.message),
                       out);
  }
  return out;
}

}  // namespace

void register_inverse(py::module_& m) {
  m.def(
      "inverse",
      [](py::object scenario, py::object target_arg, py::object actuators,
         py::object max_temperature_degC, bool check) {
        const std::shared_ptr<Scenario> sc = as_scenario(scenario);
        const rod::RodModel& model = *sc->model;
        if (model.tip_constraint) {
          throw InputError("scenario tip_constraint", "(present)",
                           "must be absent for tcasim.inverse (it moves a free tip; use "
                           "tcasim.grasp for a blocked tip)");
        }
        const Eigen::Vector3d target_m = target_vector(target_arg);
        cosserat::InverseOptions o;
        o.actuators = actuator_list(model, actuators);
        if (o.actuators.empty()) {
          throw InputError("actuators", "(none)", "the scenario has no actuator to adjust");
        }
        o.max_temperature_K = max_temperature_K(max_temperature_degC);
        study::DocumentRun r;
        {
          py::gil_scoped_release release;
          // As `tcasim inverse`: default shooting options, TCAs starting at ambient.
          r = study::inverse_document(model, target_m, o);
        }
        return checked(r, check, "inverse");
      },
      py::arg("scenario"), py::arg("target_m"), py::kw_only(), py::arg("actuators") = py::none(),
      py::arg("max_temperature_degC") = py::none(), py::arg("check") = true,
      R"(Inverse kinetostatics, as `tcasim inverse`: the actuation (TCA temperatures, or
tensions of tension drives) that puts the tip at a target ([Pawlowski2019] Section IV).

scenario: a tcasim.Scenario, a dict or a file path (free tip: no tip_constraint).
target_m: target tip position (x, y, z) [m], world frame.
actuators: names to adjust (a list or a comma-separated string; default all).
max_temperature_degC: upper temperature bound [degC] (default the material's maximum).
check: raise tcasim.SolverError (the document as .result) when not converged.
Returns the document of `tcasim inverse --out` (schema tcasim.inverse/1) as a dict:
converged, status, message, iterations, forward_solves, target_m, tip.position_m,
distance_m [m], and per actuator name, at_bound, temperature_degC (with coils_closed,
contact_force_N [N]) or tension_N [N].)");

  m.def(
      "grasp",
      [](py::object scenario, py::object mass_arg, py::object friction_arg, py::object fingers_arg,
         py::object max_temperature_degC, bool check) {
        const double mass_g = number_arg(mass_arg, "mass_g");
        const double friction = number_arg(friction_arg, "friction");
        const long long fingers = integer_arg(fingers_arg, "fingers");
        study::check_grasp_options(mass_g, friction, fingers, OptionNames::kPython);
        const std::shared_ptr<Scenario> sc = as_scenario(scenario);
        const rod::RodModel& model = *sc->model;
        if (!model.tip_constraint || !model.tip_constraint->normal_W) {
          throw InputError("tip_constraint.normal", "(missing)",
                           "tcasim.grasp needs a tip_constraint with a \"normal\" (the contact "
                           "direction from the finger toward the object)");
        }
        const double max_t_K = max_temperature_K(max_temperature_degC);
        study::DocumentRun r;
        {
          py::gil_scoped_release release;
          // As `tcasim grasp`.
          r = study::grasp_document(model, mass_g, friction, static_cast<int>(fingers), max_t_K);
        }
        return checked(r, check, "grasp");
      },
      py::arg("scenario"), py::kw_only(), py::arg("mass_g"), py::arg("friction"),
      py::arg("fingers"), py::arg("max_temperature_degC") = py::none(), py::arg("check") = true,
      R"(Grasp temperature, as `tcasim grasp`: the TCA temperature at which a blocked finger's
normal force reaches m g / (mu n) ([Pawlowski2019] Eqs. (43)-(44)).

scenario: one finger with a tip_constraint and its contact normal.
mass_g: grasped mass [g]; friction: mu; fingers: n.
Returns the document of `tcasim grasp --out` (schema tcasim.grasp/1) as a dict:
temperature_degC, normal_force_N [N], blocked_normal_force_N [N], root_temperature_degC,
iterations, tip.position_m [m], converged, message.)");

  m.def(
      "tca_curve",
      [](py::object source, py::object temperatures_arg, py::object tension_arg,
         py::object load_arg, std::optional<std::string> tca_id,
         std::optional<std::string> material, std::optional<std::string> f12_form) {
        const std::vector<double> temperatures_degC =
            number_list_arg(temperatures_arg, "temperatures_degC");
        const std::optional<double> tension_N = optional_number_arg(tension_arg, "tension_N");
        const std::optional<double> load_g = optional_number_arg(load_arg, "load_g");
        rod::TcaMap tcas;
        std::string name;
        if (py::isinstance<Scenario>(source) || PyDict_Check(source.ptr())) {
          const std::shared_ptr<Scenario> sc = as_scenario(source);
          tcas = sc->model->tcas;
          name = "scenario '" + sc->model->name + "'";
        } else {
          name = py::module_::import("os").attr("fspath")(source).cast<std::string>();
          tcas = rod::read_tcas(name);  // a scenario or a TCA file (tcasim.tcas/1)
        }
        const double t_N = study::tca_tension_N(tension_N, load_g, OptionNames::kPython);
        const std::vector<double> temps_K =
            study::temperatures_K(temperatures_degC, "temperatures_degC", OptionNames::kPython);
        // As `tcasim tca` (rod/tca_choice.hpp), the arguments under their Python names.
        const auto tca = rod::select_tca(tcas, name, {tca_id, material, f12_form},
                                         [](const std::string& key) { return key; });
        std::vector<tca::CurvePoint> curve;
        {
          py::gil_scoped_release release;
          curve = tca::elongation_curve(*tca, t_N, temps_K);
        }
        const auto n = static_cast<py::ssize_t>(curve.size());
        py::array_t<double> e(n), f(n), a(n);
        py::array_t<bool> closed(n);
        for (py::ssize_t k = 0; k < n; ++k) {
          const tca::CurvePoint& p = curve[static_cast<std::size_t>(k)];
          e.mutable_data()[k] = p.elongation_m;
          f.mutable_data()[k] = p.tension_N;
          a.mutable_data()[k] = units::rad_to_deg(p.pitch_angle_rad);
          closed.mutable_data()[k] = p.coils_closed;
        }
        py::dict out;
        out["temperature_degC"] = py::array_t<double>(n, temperatures_degC.data());
        out["elongation_m"] = e;
        out["tension_N"] = f;
        out["pitch_angle_deg"] = a;
        out["coils_closed"] = closed;
        return out;
      },
      py::arg("source"), py::arg("temperatures_degC"), py::kw_only(),
      py::arg("tension_N") = py::none(), py::arg("load_g") = py::none(),
      py::arg("tca") = py::none(), py::arg("material") = py::none(),
      py::arg("f12_form") = py::none(),
      R"(Elongation of one TCA under a constant load over temperatures, as `tcasim tca`
([Pawlowski2019] Eqs. (1)-(5); an extension TCA stays at its closed length until the onset).

source: a tcasim.Scenario or dict (its `tcas`), or the path of a scenario or TCA file.
temperatures_degC: temperatures [degC].
tension_N: constant tension F [N] (positive pulls the TCA longer), or
load_g: a hanging mass [g] compressing it (F = -m g); give exactly one.
tca: the TCA id (required when the source defines several).
material: override the material with a shipped one (data/materials/NAME.json).
f12_form: override the Eq. (4) factor, "paper" (8) or "castigliano" (16).
Returns a dict of numpy arrays: temperature_degC, elongation_m [m], tension_N [N],
pitch_angle_deg [deg], coils_closed (the columns of `tcasim tca`).)");
}

}  // namespace tcasim::python
