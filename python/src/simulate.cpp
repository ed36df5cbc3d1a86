// tcasim.simulate: rod dynamics over time with the options of `tcasim simulate` under the
// flags' names in snake_case, checked and run by the same library calls
// (study::check_simulation_options, study::simulate), so the trajectory is the command's, to
// the last digit.
#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "common/error.hpp"
#include "rod/trajectory.hpp"
#include "study/simulation.hpp"

namespace tcasim::python {

namespace {

/// A simulation's trajectory: the rows of the CSV and how the run ended.
struct Trajectory {
  std::shared_ptr<const rod::RodModel> model;
  std::vector<std::string> columns;
  std::vector<rod::TrajectoryRow> rows;
  rod::TrajectoryOutcome outcome;
  bool adaptive = false;  // rows carry dt_s (the last column)

  /// The CSV text of `tcasim simulate --out`.
  std::string csv() const {
    std::ostringstream os;
    rod::write_trajectory_header(os, *model, adaptive);
    for (const rod::TrajectoryRow& r : rows) rod::write_trajectory_row(os, r);
    if (!outcome.ok) os << "# " << outcome.message << '\n';
    return os.str();
  }

  std::size_t column_index(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (columns[i] == name) return i;
    }
    throw py::key_error(name);
  }

  /// The column `name` over the rows (the CSV's units: degC for temperatures).
  py::array_t<double> column(std::size_t i) const {
    py::array_t<double> a(static_cast<py::ssize_t>(rows.size()));
    double* out = a.mutable_data();
    for (const rod::TrajectoryRow& r : rows) *out++ = rod::trajectory_values(r)[i];
    return a;
  }

  /// Columns i, i + 1, i + 2 as an (n, 3) array.
  py::array_t<double> xyz(std::size_t i) const {
    py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}});
    double* out = a.mutable_data();
    for (const rod::TrajectoryRow& r : rows) {
      const std::vector<double> v = rod::trajectory_values(r);
      out = std::copy(v.begin() + static_cast<long>(i), v.begin() + static_cast<long>(i) + 3, out);
    }
    return a;
  }
};

/// Raised inside the C++ loop when the Python progress callback raised (its error is set).
struct CallbackRaised {};

}  // namespace

void register_simulate(py::module_& m) {
  py::class_<Trajectory, std::shared_ptr<Trajectory>>(
      m, "Trajectory",
      "The trajectory of tcasim.simulate: the rows of the CSV of `tcasim simulate` (one per "
      "output time, the first at t = 0) as numpy arrays. `traj[\"tip_x_m\"]` is a column by "
      "its CSV name (SI units; temperatures in degC, NaN for a tension drive); `to_csv()` the "
      "command's file, byte for byte.")
      .def_property_readonly(
          "columns", [](const Trajectory& t) { return t.columns; },
          "The column names, in the CSV's order (docs/scenario-format.md \"Trajectory file\").")
      .def_property_readonly(
          "t_s", [](const Trajectory& t) { return t.column(0); }, "Output times [s], shape (n,).")
      .def_property_readonly(
          "tip_position_m", [](const Trajectory& t) { return t.xyz(1); },
          "Tip positions [m], world frame, shape (n, 3).")
      .def_property_readonly(
          "kinetic_energy_J", [](const Trajectory& t) { return t.column(4); },
          "Kinetic energy [J], shape (n,).")
      .def_property_readonly(
          "probes",
          [](const Trajectory& t) {
            py::dict d;
            for (const rod::Probe& p : t.model->probes) {
              d[py::str(p.name)] = t.xyz(t.column_index(p.name + "_x_m"));
            }
            return d;
          },
          "The scenario's probes: a dict name -> world positions [m], shape (n, 3).")
      .def_property_readonly(
          "completed", [](const Trajectory& t) { return t.outcome.ok; },
          "True when the static state and every time step converged.")
      .def_property_readonly(
          "status", [](const Trajectory& t) { return t.outcome.status; },
          "\"converged\" or the failing solve's status (e.g. \"max-iterations\").")
      .def_property_readonly(
          "message", [](const Trajectory& t) { return t.outcome.message; },
          "Why the run stopped early (\"\" when completed); the CSV's last line is \"# \" + it.")
      .def_property_readonly(
          "steps_done", [](const Trajectory& t) { return t.outcome.steps_done; },
          "Converged (accepted) time steps.")
      .def_property_readonly(
          "steps_rejected", [](const Trajectory& t) { return t.outcome.steps_rejected; },
          "Adaptive steps (rtol): steps undone and retried smaller by the error test.")
      .def_property_readonly(
          "steps_failed", [](const Trajectory& t) { return t.outcome.steps_failed; },
          "Adaptive steps (rtol): steps undone and retried at a quarter after a failed Newton "
          "iteration.")
      .def(
          "__getitem__",
          [](const Trajectory& t, const std::string& name) {
            return t.column(t.column_index(name));
          },
          "A column by its CSV name, shape (n,).")
      .def(
          "__len__", [](const Trajectory& t) { return t.rows.size(); }, "Number of rows.")
      .def(
          "to_csv",
          [](const Trajectory& t, py::object path) -> py::object {
            const std::string text = t.csv();
            if (path.is_none()) return py::str(text);
            const std::string p =
                py::module_::import("os").attr("fspath")(path).cast<std::string>();
            std::ofstream f(p, std::ios::binary);
            f << text;
            if (!f) throw InputError("path", p, "could not be written");
            return py::none();
          },
          py::arg("path") = py::none(),
          "Writes the CSV of `tcasim simulate --out PATH` (with path None: returns its text).")
      .def("__repr__", [](const Trajectory& t) {
        return fmt::format("<tcasim.Trajectory {} rows, {}>", t.rows.size(), t.outcome.status);
      });

  m.def(
      "simulate",
      [](py::object scenario, const std::string& method, py::object duration_s, py::object dt_s,
         py::object rtol, py::object atol_m, py::object output_every_s, py::object output_every,
         py::object max_iterations, bool release_tip_load, py::object viscosity_Pa_s,
         py::object tip_mass_kg, py::object alpha, py::object steps, py::object elements,
         py::object order, py::object rho_inf, py::object progress, bool check) {
        const std::shared_ptr<Scenario> sc = as_scenario(scenario);
        study::check_method(method, study::OptionNames::kPython);
        // A keyword of the other method is refused, not ignored.
        std::vector<study::GivenOption> given;
        for (const auto& [value, key] :
             {std::pair{&alpha, "alpha"}, std::pair{&steps, "steps"},
              std::pair{&elements, "elements"}, std::pair{&order, "order"},
              std::pair{&rho_inf, "rho_inf"}}) {
          if (!value->is_none()) given.push_back({key, py::str(*value).cast<std::string>()});
        }
        study::refuse_other_method_options(method, given, study::OptionNames::kPython);
        study::SimulationOptions o;
        o.method = method;
        o.duration_s = number_arg(duration_s, "duration_s");
        // Exactly one of the two time-step modes, as the command's --dt-s and --rtol.
        if (!dt_s.is_none() && !rtol.is_none()) {
          throw InputError("dt_s", py::str(dt_s).cast<std::string>(),
                           "cannot be given with rtol (fixed or adaptive time steps: one of them)");
        }
        if (dt_s.is_none() && rtol.is_none()) {
          throw InputError("dt_s", "None",
                           "one of dt_s (fixed time steps) or rtol (adaptive) is required");
        }
        if (!dt_s.is_none()) o.dt_s = number_arg(dt_s, "dt_s");
        o.rtol = optional_number_arg(rtol, "rtol");
        o.atol_m = optional_number_arg(atol_m, "atol_m");
        o.output_every_s = optional_number_arg(output_every_s, "output_every_s");
        o.output_every = integer_arg(output_every, "output_every");
        o.max_iterations = integer_arg(max_iterations, "max_iterations");
        o.release_tip_load = release_tip_load;
        o.viscosity_Pa_s = optional_number_arg(viscosity_Pa_s, "viscosity_Pa_s");
        o.tip_mass_kg = optional_number_arg(tip_mass_kg, "tip_mass_kg");
        // The keywords override the defaults of SimulationOptions only when given.
        if (!alpha.is_none()) o.alpha = number_arg(alpha, "alpha");
        o.steps = optional_integer_arg(steps, "steps");
        if (!elements.is_none()) o.elements = integer_arg(elements, "elements");
        if (!order.is_none()) o.order = integer_arg(order, "order");
        if (!rho_inf.is_none()) o.rho_inf = number_arg(rho_inf, "rho_inf");
        study::check_simulation_options(o, study::OptionNames::kPython);

        auto traj = std::make_shared<Trajectory>();
        traj->model = sc->model;
        traj->adaptive = o.rtol.has_value();
        traj->columns = rod::trajectory_columns(*sc->model, traj->adaptive);
        study::SimulationHooks hooks;
        hooks.on_row = [&traj](const rod::TrajectoryRow& r) { traj->rows.push_back(r); };
        if (!progress.is_none()) {
          hooks.on_step = [&progress](long long done, long long total) {
            py::gil_scoped_acquire gil;
            try {
              progress(done, total);
            } catch (py::error_already_set& e) {
              e.restore();  // kept as this thread's Python error until the GIL is back
              throw CallbackRaised{};
            }
          };
        }
        try {
          py::gil_scoped_release release;
          traj->outcome = study::simulate(*sc->model, o, hooks, study::OptionNames::kPython);
        } catch (const CallbackRaised&) {
          throw py::error_already_set();
        }
        py::object out = py::cast(traj);
        if (check && !traj->outcome.ok) {
          throw_solver_error("tcasim.simulate: " + traj->outcome.message, out);
        }
        return out;
      },
      py::arg("scenario"), py::arg("method") = "cosserat", py::kw_only(), py::arg("duration_s"),
      py::arg("dt_s") = py::none(), py::arg("rtol") = py::none(), py::arg("atol_m") = py::none(),
      py::arg("output_every_s") = py::none(), py::arg("output_every") = 1,
      py::arg("max_iterations") = 30, py::arg("release_tip_load") = false,
      py::arg("viscosity_Pa_s") = py::none(), py::arg("tip_mass_kg") = py::none(),
      py::arg("alpha") = py::none(), py::arg("steps") = py::none(),
      py::arg("elements") = py::none(), py::arg("order") = py::none(),
      py::arg("rho_inf") = py::none(), py::arg("progress") = py::none(), py::arg("check") = true,
      fmt::format(
          R"(Rod dynamics of one scenario from its static state at t = 0, as `tcasim simulate`
(the same numbers): the scenario's time profiles, viscosity and tip mass.

scenario: a tcasim.Scenario, a dict or a file path.
method: "cosserat" (shooting, BDF-alpha in time) or "fe" (beam elements, Lie-group
    generalized-alpha).
duration_s: simulated time T [s] (> 0); dt_s: fixed time step [s] (> 0), round(T / dt)
    steps; or, instead of dt_s, adaptive steps (either method):
rtol: relative tolerance in (0, 1) of each step's local error estimate per rod length L,
    with atol_m: absolute tolerance [m] (>= 0, default 0): a step is accepted when its
    error <= atol_m + rtol L (docs/scenario-format.md "Adaptive time steps");
    output_every_s: (required with rtol) a row every this many seconds; the trajectory gets
    a last column dt_s, the size of the step that reached the row.
output_every: fixed steps, a row every K-th step (and t = 0 and the last step; default 1).
max_iterations: Newton iterations per time step (default 30, in [1, {}]).
release_tip_load: the scenario's tip load acts at t = 0 only (a released cantilever).
viscosity_Pa_s: Kelvin-Voigt viscosity [Pa s], constant along s (default: the scenario's).
tip_mass_kg: point mass at the tip [kg] (default: the scenario's).
alpha: cosserat, BDF-alpha parameter in [-0.5, 0] (default -0.2).
steps: cosserat, RK4 steps along s, in [1, {}] (default: enough for the time step,
    >= 20).
elements, order: fe, number of elements in [1, {}] (default 16) and their order, 1 or 2
    (default 2).
rho_inf: fe, generalized-alpha spectral radius at infinite frequency in [0, 1] (default 0.9).
progress: optional callable progress(done, total), called after each step: steps done of
    the total, with rtol output periods done.
check: raise tcasim.SolverError (the partial trajectory as .result) when the static state or
    a time step fails (default); with check=False the trajectory is returned with
    completed False.
Returns a tcasim.Trajectory. An option out of range or of the wrong kind (an integer
keyword given 2.5, a number beyond a double) raises tcasim.InputError naming it, with the
rule of the same flag of `tcasim simulate`. The GIL is released while the simulation runs.)",
          study::kMaxNewtonIterations, study::kMaxSteps, study::kMaxElements)
          .c_str());
}

}  // namespace tcasim::python
