// tcasim.solve and tcasim.sweep: forward kinetostatics with both methods, with the options of
// `tcasim solve` / `tcasim sweep` under the flags' names without dashes, checked by the same
// functions (study/options.hpp).
// The numbers are those of the command line: the same library calls in the same order.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "bindings.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "cosserat/shooting.hpp"
#include "json_convert.hpp"
#include "method/method.hpp"
#include "rod/loads.hpp"
#include "rod/result.hpp"
#include "rod/vtk.hpp"
#include "study/options.hpp"
#include "study/sweep.hpp"

namespace tcasim::python {

namespace {

using study::OptionNames;

/// The solve options of the keywords (`tcasim solve --help`), checked by study/options.hpp
/// as the command line's flags.
struct SolveOptions {
  study::ShootingChoice shooting;
  study::FeChoice fe;
};

/// The keywords of both methods' options as C++ values (InputError naming a keyword that is
/// not a number of the right kind).
SolveOptions solve_options(const py::object& steps, std::optional<std::string> scheme,
                           const py::object& rtol, bool no_planar, const py::object& elements,
                           const py::object& order, const std::string& integration,
                           const std::string& linear_solver) {
  SolveOptions f;
  f.shooting.steps = optional_integer_arg(steps, "steps");
  f.shooting.scheme = std::move(scheme);
  f.shooting.rtol = optional_number_arg(rtol, "rtol");
  f.shooting.no_planar = no_planar;
  f.fe.elements = integer_arg(elements, "elements");
  f.fe.order = integer_arg(order, "order");
  f.fe.integration = integration;
  f.fe.linear_solver = linear_solver;
  return f;
}

/// A solve's result with the file's convergence rule (rod::to_json): a result holding a
/// non-finite number is not converged.
struct Result {
  rod::Result r;
  bool finite = true;

  bool converged() const { return r.converged && finite; }
  std::string status() const {
    return converged() || r.status != "converged" ? r.status : std::string("non_finite_result");
  }
  std::string message() const {
    if (converged()) return {};
    return rod::to_json(r).value("message", std::string());
  }
};

bool finite3(const Eigen::Vector3d& v) { return v.allFinite(); }

/// True when every number rod::to_json writes is finite.
bool all_finite(const rod::Result& r) {
  for (const auto& [k, v] : r.discretization) {
    if (!std::isfinite(v)) return false;
  }
  if (r.residual && !std::isfinite(*r.residual)) return false;
  if (!std::isfinite(r.characteristic_force_N) || !std::isfinite(r.wall_time_s)) return false;
  if (!r.tip_R_WB.allFinite() || !finite3(r.tip_position_W_m)) return false;
  for (const auto& a : r.actuators) {
    if (!std::isfinite(a.tension_N) || !std::isfinite(a.elongation_m)) return false;
    if (a.is_tca && !std::isfinite(a.contact_force_N)) return false;
    for (const auto& [seg, c] : a.segments) {
      if (!std::isfinite(seg.fraction) || !std::isfinite(seg.temperature_K) ||
          !std::isfinite(c.contact_force_N)) {
        return false;
      }
    }
  }
  if (r.bending_radius_m && !std::isfinite(*r.bending_radius_m)) return false;
  if (r.tip_reaction_force_W_N && !finite3(*r.tip_reaction_force_W_N)) return false;
  for (std::size_t k = 0; k < r.centerline_s_m.size(); ++k) {
    if (!std::isfinite(r.centerline_s_m[k]) || !finite3(r.centerline_p_W_m[k])) return false;
  }
  for (const Eigen::Matrix3d& R : r.centerline_R_WB) {
    if (!R.allFinite()) return false;
  }
  for (const rod::ProbeResult& p : r.probes) {
    if (!finite3(p.position_W_m)) return false;
  }
  for (const rod::ContactResult& c : r.contacts) {
    if (!finite3(c.force_W_N) || !finite3(c.moment_W_Nm) || !std::isfinite(c.max_penetration_m)) {
      return false;
    }
  }
  if (r.base_reaction &&
      (!finite3(r.base_reaction->force_W_N) || !finite3(r.base_reaction->moment_W_Nm))) {
    return false;
  }
  return true;
}

py::array_t<double> vec3(const Eigen::Vector3d& v) {
  py::array_t<double> a(3);
  std::copy(v.data(), v.data() + 3, a.mutable_data());
  return a;
}

py::array_t<double> mat3(const Eigen::Matrix3d& m) {
  py::array_t<double> a({3, 3});
  auto w = a.mutable_unchecked<2>();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w(i, j) = m(i, j);
  return a;
}

py::object optional_float(const std::optional<double>& v) {
  return v ? py::object(py::float_(*v)) : py::object(py::none());
}

/// One actuator entry as the result file writes it (rod::to_json).
py::dict actuator_dict(const rod::ActuatorResult& a) {
  py::dict e;
  e["name"] = a.name;
  e["tension_N"] = a.tension_N;
  e["elongation_m"] = a.elongation_m;
  if (a.is_tca) {
    e["coils_closed"] = a.coils_closed;
    e["contact_force_N"] = a.contact_force_N;
  }
  if (!a.segments.empty()) {
    py::list segs;
    for (const auto& [seg, c] : a.segments) {
      py::dict s;
      s["fraction"] = seg.fraction;
      s["temperature_degC"] = units::K_to_degC(seg.temperature_K);
      s["coils_closed"] = c.coils_closed;
      s["contact_force_N"] = c.contact_force_N;
      segs.append(s);
    }
    e["segments"] = segs;
  }
  return e;
}

/// Solves with the checked options of one method (as `tcasim solve`).
rod::Result solve_with(const rod::RodModel& model, const method::StaticOptions& options) {
  return method::solve(model, options);
}

/// The checked options of `method` (InputError naming the keyword).
method::StaticOptions method_options(const std::string& method, const SolveOptions& f) {
  return study::static_options(method, f.shooting, f.fe, OptionNames::kPython);
}

std::optional<std::string> fspath(const py::object& p) {
  if (p.is_none()) return std::nullopt;
  return py::module_::import("os").attr("fspath")(p).cast<std::string>();
}

/// Keeps a benchmarked result alive (the compiler may not drop the solve).
void benchmark_sink(const rod::Result& r) {
  static volatile double sink = 0.0;
  sink = sink + r.tip_position_W_m.x();
}

const std::string kOptionsDoc = fmt::format(R"(
Options (the flags of `tcasim solve`, without dashes; each applies to one method):
  steps: cosserat, fixed integration steps (even, in [2, {}]; default 100).
  scheme: cosserat, "rk4" (default, the paper's), "rk6" or "rk8".
  rtol: cosserat, SUNDIALS CVODE with this relative tolerance (excludes steps, scheme).
  no_planar: cosserat, solve a planar problem as a 3-D one (for cross-checks).
  elements: fe, number of elements (in [1, {}]; default 16).
  order: fe, Lagrange order of the elements, 1 or 2 (default 2).
  integration: fe, Gauss rule "reduced" (default) or "full".
  linear_solver: fe, "klu" (default), "umfpack" or "sparselu".
A value out of range or of the wrong kind raises tcasim.InputError naming the keyword.)",
                                            study::kMaxSteps, study::kMaxElements);

}  // namespace

void register_solve(py::module_& m) {
  py::class_<Result, std::shared_ptr<Result>>(
      m, "Result",
      "The outcome of one solve; its fields mirror the result file `tcasim.result/1` "
      "(docs/scenario-format.md), SI units, world frame. Vectors and centerlines are numpy "
      "arrays (a non-finite number, which the file writes as null, is NaN here). "
      "`to_dict()` is the file's content, `to_json()` its text, `result[key]` a key of it.")
      .def_property_readonly(
          "schema", [](const Result&) { return "tcasim.result/1"; }, "\"tcasim.result/1\".")
      .def_property_readonly(
          "scenario", [](const Result& r) { return r.r.scenario; }, "The scenario's name.")
      .def_property_readonly(
          "method", [](const Result& r) { return r.r.method; }, "\"cosserat\" or \"fe\".")
      .def_property_readonly(
          "discretization",
          [](const Result& r) {
            py::dict d;
            for (const auto& [k, v] : r.r.discretization) {
              const bool whole =
                  std::isfinite(v) && v == std::floor(v) && std::abs(v) <= 9007199254740992.0;
              d[py::str(k)] = whole ? py::object(py::int_(static_cast<long long>(v)))
                                    : py::object(py::float_(v));
            }
            return d;
          },
          "E.g. {\"steps\": 100, \"order\": 4} (cosserat) or {\"elements\": 16, \"order\": 2} "
          "(fe).")
      .def_property_readonly("converged", &Result::converged,
                             "True when the solve converged (and every number is finite).")
      .def_property_readonly("status", &Result::status,
                             "\"converged\" or the solver's reason for stopping.")
      .def_property_readonly("message", &Result::message,
                             "Why the solve did not converge (\"\" when it converged).")
      .def_property_readonly(
          "iterations", [](const Result& r) { return r.r.iterations; },
          "Newton iterations (shooting: all levels and continuation steps; FE: linear solves).")
      .def_property_readonly(
          "residual", [](const Result& r) { return optional_float(r.r.residual); },
          "Largest unbalanced force over the characteristic force (dimensionless), or None.")
      .def_property_readonly(
          "characteristic_force_N", [](const Result& r) { return r.r.characteristic_force_N; },
          "Characteristic force F_c [N] of the residual.")
      .def_property_readonly(
          "wall_time_s", [](const Result& r) { return r.r.wall_time_s; },
          "Wall time of the solve [s].")
      .def_property_readonly(
          "tip_position_m", [](const Result& r) { return vec3(r.r.tip_position_W_m); },
          "Tip position [m], world frame, shape (3,) (file: tip.position_m).")
      .def_property_readonly(
          "tip_rotation", [](const Result& r) { return mat3(r.r.tip_R_WB); },
          "Tip body frame in world coordinates R_WB, shape (3, 3) (file: tip.rotation).")
      .def_property_readonly(
          "actuators",
          [](const Result& r) {
            py::list out;
            for (const auto& a : r.r.actuators) out.append(actuator_dict(a));
            return out;
          },
          "Per actuator a dict as in the file: name, tension_N [N] and elongation_m [m] of one "
          "string; TCA drives add coils_closed and contact_force_N [N]; segmented ones "
          "segments (fraction, temperature_degC, coils_closed, contact_force_N).")
      .def_property_readonly(
          "bending_radius_m", [](const Result& r) { return optional_float(r.r.bending_radius_m); },
          "Three-point inner-edge bending radius [m] (None when straight).")
      .def_property_readonly(
          "tip_reaction_force_N",
          [](const Result& r) {
            return r.r.tip_reaction_force_W_N ? py::object(vec3(*r.r.tip_reaction_force_W_N))
                                              : py::object(py::none());
          },
          "With a tip_constraint: the force the holder applies to the rod [N], world frame, "
          "shape (3,); else None.")
      .def_property_readonly(
          "centerline_s_m",
          [](const Result& r) {
            return py::array_t<double>(static_cast<py::ssize_t>(r.r.centerline_s_m.size()),
                                       r.r.centerline_s_m.data());
          },
          "Arc length of the centerline samples [m], shape (n,) (file: centerline.s_m).")
      .def_property_readonly(
          "centerline_position_m",
          [](const Result& r) {
            const auto n = static_cast<py::ssize_t>(r.r.centerline_p_W_m.size());
            py::array_t<double> a({n, py::ssize_t{3}});
            double* out = a.mutable_data();
            for (const auto& p : r.r.centerline_p_W_m) out = std::copy(p.data(), p.data() + 3, out);
            return a;
          },
          "Centerline positions [m], world frame, shape (n, 3) (file: centerline.position_m).")
      .def_property_readonly(
          "centerline_rotation",
          [](const Result& r) {
            const auto n = static_cast<py::ssize_t>(r.r.centerline_R_WB.size());
            py::array_t<double> a({n, py::ssize_t{3}, py::ssize_t{3}});
            auto w = a.mutable_unchecked<3>();
            for (py::ssize_t k = 0; k < n; ++k)
              for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) w(k, i, j) = r.r.centerline_R_WB[k](i, j);
            return a;
          },
          "Body frames R_WB at the centerline samples, shape (n, 3, 3), row-major as in the "
          "file (centerline.rotation).")
      .def_property_readonly(
          "probes",
          [](const Result& r) {
            py::dict d;
            for (const rod::ProbeResult& p : r.r.probes) d[py::str(p.name)] = vec3(p.position_W_m);
            return d;
          },
          "The scenario's probes: a dict name -> world position [m], shape (3,), in the "
          "scenario's order (file: probes[k].position_m); empty without probes.")
      .def_property_readonly(
          "contacts",
          [](const Result& r) {
            py::dict d;
            for (const rod::ContactResult& c : r.r.contacts) {
              py::list regions;
              for (const rod::ContactRegion& g : c.regions) {
                py::dict region;
                region["s_m"] = py::make_tuple(g.s0_m, g.s1_m);
                region["force_N"] = vec3(g.force_W_N);
                regions.append(region);
              }
              py::dict entry;
              entry["force_N"] = vec3(c.force_W_N);
              entry["moment_Nm"] = vec3(c.moment_W_Nm);
              entry["regions"] = regions;
              entry["max_penetration_m"] = c.max_penetration_m;
              entry["core_penetration_between_m"] = c.core_penetration_between_m;
              d[py::str(c.obstacle)] = entry;
            }
            return d;
          },
          "Per obstacle (a dict name -> dict, in the scenario's order): its resultant force on "
          "the rod `force_N` (world), its moment `moment_Nm` about the base point, `regions` "
          "(a list of {s_m: (s0, s1), force_N}), `max_penetration_m` and "
          "`core_penetration_between_m`; empty without obstacles (file: contacts).")
      .def_property_readonly(
          "base_reaction",
          [](const Result& r) -> py::object {
            if (!r.r.base_reaction) return py::none();
            py::dict d;
            d["force_N"] = vec3(r.r.base_reaction->force_W_N);
            d["moment_Nm"] = vec3(r.r.base_reaction->moment_W_Nm);
            return d;
          },
          "What the clamp applies to the rod: {force_N, moment_Nm} (world frame, moment about "
          "the base point); None when the solver did not fill it (file: base_reaction).")
      .def(
          "to_dict", [](const Result& r) { return to_python(rod::to_json(r.r)); },
          "The result file's content as a dict (the numbers of the file, bit for bit).")
      .def(
          "to_json", [](const Result& r) { return rod::format_json(rod::to_json(r.r)) + "\n"; },
          "The text of the result file, as `tcasim solve --out` writes it.")
      .def(
          "save", [](const Result& r, py::object path) { rod::write_result(r.r, *fspath(path)); },
          py::arg("path"), "Writes the result file (as `tcasim solve --out PATH`).")
      .def(
          "__getitem__",
          [](const Result& r, const std::string& key) {
            py::dict d = to_python(rod::to_json(r.r));
            if (!d.contains(key)) throw py::key_error(key);
            return py::object(d[py::str(key)]);
          },
          "A key of the result file: result[\"tip\"][\"position_m\"].")
      .def("__repr__", [](const Result& r) {
        return fmt::format("<tcasim.Result {} {} {} tip=[{:.6g}, {:.6g}, {:.6g}] m>", r.r.scenario,
                           r.r.method, r.status(), r.r.tip_position_W_m.x(),
                           r.r.tip_position_W_m.y(), r.r.tip_position_W_m.z());
      });

  m.def(
      "solve",
      [](py::object scenario, const std::string& method, py::object steps,
         std::optional<std::string> scheme, py::object rtol, bool no_planar, py::object elements,
         py::object order, const std::string& integration, const std::string& linear_solver,
         py::object vtk, py::object shape_csv, bool check) {
        const std::shared_ptr<Scenario> sc = as_scenario(scenario);
        const auto options =
            method_options(method, solve_options(steps, std::move(scheme), rtol, no_planar,
                                                 elements, order, integration, linear_solver));
        const std::optional<std::string> vtk_path = fspath(vtk), csv_path = fspath(shape_csv);
        auto result = std::make_shared<Result>();
        {
          py::gil_scoped_release release;
          result->r = solve_with(*sc->model, options);
          result->finite = all_finite(result->r);
          if (vtk_path) rod::write_vtp(*sc->model, result->r, *vtk_path);
          if (csv_path) rod::write_shape_csv(*sc->model, result->r, *csv_path);
        }
        py::object out = py::cast(result);
        if (check && !result->converged()) {
          throw_solver_error(
              "tcasim.solve: not converged (" + result->status() + "): " + result->message(), out);
        }
        return out;
      },
      py::arg("scenario"), py::arg("method") = "cosserat", py::kw_only(),
      py::arg("steps") = py::none(), py::arg("scheme") = py::none(), py::arg("rtol") = py::none(),
      py::arg("no_planar") = false, py::arg("elements") = 16, py::arg("order") = 2,
      py::arg("integration") = "reduced", py::arg("linear_solver") = "klu",
      py::arg("vtk") = py::none(), py::arg("shape_csv") = py::none(), py::arg("check") = true,
      (std::string(R"(Forward kinetostatics of one scenario, as `tcasim solve`.

scenario: a tcasim.Scenario, a dict or a file path.
method: "cosserat" (shooting, default) or "fe" (geometrically exact beam elements).
vtk, shape_csv: also write the deformed shape as VTK PolyData (.vtp) / CSV.
check: raise tcasim.SolverError (carrying the result as .result) when the solve does not
    converge (default); with check=False the result is returned with converged False.
Returns a tcasim.Result whose fields mirror the result file. The GIL is released while
the solver runs.)") +
       kOptionsDoc)
          .c_str());

  m.def(
      "_solve_times_cpp",
      [](py::object scenario, const std::string& method, int repeats) {
        const std::shared_ptr<Scenario> sc = as_scenario(scenario);
        const auto options = method_options(method, SolveOptions{});
        std::vector<double> times;
        py::gil_scoped_release release;
        for (int k = 0; k < repeats; ++k) {
          const auto t0 = std::chrono::steady_clock::now();
          rod::Result r = solve_with(*sc->model, options);
          const auto t1 = std::chrono::steady_clock::now();
          benchmark_sink(r);
          times.push_back(std::chrono::duration<double>(t1 - t0).count());
        }
        return times;
      },
      py::arg("scenario"), py::arg("method") = "cosserat", py::arg("repeats") = 10,
      "For bench/python_overhead.py: the wall time [s] of each of `repeats` solves with the "
      "default options run in C++ (the work of tcasim.solve without Python).");

  m.def(
      "sweep",
      [](py::object scenario, const std::string& actuator, py::object temperatures_degC,
         py::object tensions_N, const std::string& method, py::object steps,
         std::optional<std::string> scheme, py::object rtol, bool no_planar, py::object elements,
         py::object order, const std::string& integration, const std::string& linear_solver,
         py::object jobs_arg, py::object chunk_arg) {
        const std::shared_ptr<Scenario> sc = as_scenario(scenario);
        const rod::RodModel& model = *sc->model;
        study::check_method(method, OptionNames::kPython);
        const std::size_t index = actuator_index(model, actuator, "actuator");
        const rod::Actuator& act = model.actuators[index];
        if (temperatures_degC.is_none() == tensions_N.is_none()) {
          throw InputError("temperatures_degC/tensions_N", "(both or none)",
                           "give exactly one of them");
        }
        const bool by_temperature = !temperatures_degC.is_none();
        if (by_temperature && act.drive.type != rod::Drive::Type::kTca) {
          throw InputError("temperatures_degC", "(given)",
                           "needs a TCA-driven actuator; '" + act.name + "' has a tension drive");
        }
        if (!by_temperature && act.drive.type != rod::Drive::Type::kTension) {
          throw InputError("tensions_N", "(given)",
                           "needs a tension-driven actuator; '" + act.name + "' has a TCA drive");
        }
        const std::vector<double> values =
            by_temperature ? number_list_arg(temperatures_degC, "temperatures_degC")
                           : number_list_arg(tensions_N, "tensions_N");
        if (!by_temperature) {
          for (double v : values) require(std::isfinite(v), "tensions_N", v, "must be finite");
        }
        const SolveOptions f = solve_options(steps, std::move(scheme), rtol, no_planar, elements,
                                             order, integration, linear_solver);
        const long long jobs = integer_arg(jobs_arg, "jobs");
        const long long chunk = integer_arg(chunk_arg, "chunk");
        study::check_sweep_jobs(jobs, chunk, OptionNames::kPython);
        // Options first, so a bad one is reported before any solve.
        study::Sweep sw;
        sw.actuator = index;
        sw.by_temperature = by_temperature;
        sw.values = by_temperature
                        ? study::temperatures_K(values, "temperatures_degC", OptionNames::kPython)
                        : values;
        sw.method = method_options(method, f);
        std::vector<rod::Result> results(values.size());
        {
          py::gil_scoped_release release;
          // As `tcasim sweep --chunk K --jobs N` (study/sweep.hpp): chunks of K consecutive
          // points, each starting cold, so the threads give the numbers of the serial run.
          const std::vector<IndexRange> chunks =
              fixed_chunks(values.size(), static_cast<std::size_t>(chunk));
          study::solve_chunks(model, sw, chunks, IndexRange{0, chunks.size()},
                              static_cast<int>(jobs),
                              [&](std::size_t k, rod::Result&& r) { results[k] = std::move(r); });
        }
        // Columns of the CSV of `tcasim sweep`, in its order (numbers unrounded).
        const auto n = static_cast<py::ssize_t>(values.size());
        py::dict cols;
        const auto column = [&](const std::string& name, auto get) {
          py::array_t<double> a(n);
          double* out = a.mutable_data();
          for (py::ssize_t k = 0; k < n; ++k) out[k] = get(results[static_cast<std::size_t>(k)]);
          cols[py::str(name)] = a;
        };
        const auto flag_column = [&](const std::string& name, auto get) {
          py::array_t<bool> a(n);
          bool* out = a.mutable_data();
          for (py::ssize_t k = 0; k < n; ++k) out[k] = get(results[static_cast<std::size_t>(k)]);
          cols[py::str(name)] = a;
        };
        const double nan = std::nan("");
        cols[by_temperature ? "temperature_degC" : "tension_N"] =
            py::array_t<double>(n, values.data());
        flag_column("converged", [](const rod::Result& r) { return r.converged; });
        {
          py::array_t<long long> a(n);
          for (py::ssize_t k = 0; k < n; ++k) {
            a.mutable_data()[k] = results[static_cast<std::size_t>(k)].iterations;
          }
          cols["iterations"] = a;
        }
        column("residual", [&](const rod::Result& r) { return r.residual.value_or(nan); });
        for (int i = 0; i < 3; ++i) {
          column(std::string("tip_") + "xyz"[i] + "_m",
                 [i](const rod::Result& r) { return r.tip_position_W_m[i]; });
        }
        column("bending_radius_m",
               [&](const rod::Result& r) { return r.bending_radius_m.value_or(nan); });
        for (std::size_t i = 0; i < model.actuators.size(); ++i) {
          const rod::Actuator& a = model.actuators[i];
          column(a.name + "_tension_N",
                 [i](const rod::Result& r) { return r.actuators[i].tension_N; });
          column(a.name + "_elongation_m",
                 [i](const rod::Result& r) { return r.actuators[i].elongation_m; });
          if (a.drive.type == rod::Drive::Type::kTca) {
            flag_column(a.name + "_coils_closed",
                        [i](const rod::Result& r) { return r.actuators[i].coils_closed; });
            column(a.name + "_contact_force_N",
                   [i](const rod::Result& r) { return r.actuators[i].contact_force_N; });
          }
          if (a.drive.segmented) {
            for (std::size_t k = 0; k < a.drive.segments.size(); ++k) {
              const std::string p = fmt::format("{}_{}", a.name, k + 1);
              flag_column(p + "_coils_closed", [i, k](const rod::Result& r) {
                return r.actuators[i].segments[k].second.coils_closed;
              });
              column(p + "_contact_force_N", [i, k](const rod::Result& r) {
                return r.actuators[i].segments[k].second.contact_force_N;
              });
            }
          }
        }
        for (std::size_t i = 0; i < model.probes.size(); ++i) {
          for (int c = 0; c < 3; ++c) {
            column(model.probes[i].name + "_" + "xyz"[c] + "_m", [&, i, c](const rod::Result& r) {
              return i < r.probes.size() ? r.probes[i].position_W_m[c] : nan;
            });
          }
        }
        for (std::size_t i = 0; i < model.obstacles.size(); ++i) {
          for (int c = 0; c < 3; ++c) {
            column(fmt::format("{}_force_{}_N", model.obstacles[i].name, "xyz"[c]),
                   [i, c, nan](const rod::Result& r) {
                     return i < r.contacts.size() ? r.contacts[i].force_W_N[c] : nan;
                   });
          }
          flag_column(model.obstacles[i].name + "_in_contact", [i](const rod::Result& r) {
            return i < r.contacts.size() && r.contacts[i].in_contact();
          });
        }
        py::list status;
        for (const rod::Result& r : results) status.append(r.status);
        cols["status"] = status;
        return cols;
      },
      py::arg("scenario"), py::arg("actuator"), py::kw_only(),
      py::arg("temperatures_degC") = py::none(), py::arg("tensions_N") = py::none(),
      py::arg("method") = "cosserat", py::arg("steps") = py::none(), py::arg("scheme") = py::none(),
      py::arg("rtol") = py::none(), py::arg("no_planar") = false, py::arg("elements") = 16,
      py::arg("order") = 2, py::arg("integration") = "reduced", py::arg("linear_solver") = "klu",
      py::arg("jobs") = 1, py::arg("chunk") = study::kDefaultSweepChunk,
      (std::string(R"(Solves a scenario over a range of one actuator's temperature or tension,
as `tcasim sweep` (the same numbers): in chunks of `chunk` consecutive points, each
starting cold and warm-starting its points in order, solved on `jobs` threads (the GIL
released); the result does not depend on `jobs`.

actuator: the name of the swept actuator.
temperatures_degC: TCA temperatures [degC] (every segment), or
tensions_N: tensions of one string [N] (tension drive); give exactly one.
jobs: threads (1 to 1024; default 1); chunk: points per chunk (default 100).
Returns a dict of numpy arrays named as the columns of the sweep CSV (temperature_degC or
tension_N, converged, iterations, residual, tip_x_m, tip_y_m, tip_z_m, bending_radius_m,
<actuator>_tension_N, <actuator>_elongation_m, TCA drives <actuator>_coils_closed and
<actuator>_contact_force_N, ..., per probe <probe>_x_m, <probe>_y_m, <probe>_z_m; NaN where
the CSV has an empty cell) and a list `status`.
A point that does not converge is a row with converged False, never an exception.)") +
       kOptionsDoc)
          .c_str());
}

}  // namespace tcasim::python
