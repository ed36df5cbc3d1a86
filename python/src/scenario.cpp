// Scenarios in Python: tcasim.load_scenario(path or dict) -> tcasim.Scenario.
#include "rod/scenario.hpp"

#include <pybind11/stl.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "common/error.hpp"
#include "json_convert.hpp"
#include "rod/json_file.hpp"
#include "rod/output_file.hpp"
#include "rod/result.hpp"

namespace tcasim::python {

std::shared_ptr<Scenario> as_scenario(py::handle obj) {
  if (py::isinstance<Scenario>(obj)) return obj.cast<std::shared_ptr<Scenario>>();
  auto s = std::make_shared<Scenario>();
  if (PyDict_Check(obj.ptr())) {
    s->document = from_python(obj, "scenario");
    const std::string cwd = std::filesystem::current_path().string();
    s->model = std::make_shared<const rod::RodModel>(rod::parse_scenario(s->document, cwd));
    return s;
  }
  if (PyUnicode_Check(obj.ptr()) || py::hasattr(obj, "__fspath__")) {
    const std::string path = py::module_::import("os").attr("fspath")(obj).cast<std::string>();
    s->document = rod::read_json_file(path, "scenario file");
    const std::string dir = std::filesystem::path(path).parent_path().string();
    s->model = std::make_shared<const rod::RodModel>(
        rod::parse_scenario(s->document, dir.empty() ? "." : dir));
    s->path = path;
    return s;
  }
  throw py::type_error("a scenario is a tcasim.Scenario, a dict or a file path, not " +
                       std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
}

std::size_t actuator_index(const rod::RodModel& model, const std::string& name,
                           const std::string& key) {
  std::string names;
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    if (model.actuators[i].name == name) return i;
    names += (names.empty() ? "" : ", ") + model.actuators[i].name;
  }
  throw InputError(key, name, "names no actuator of the scenario (it has: " + names + ")");
}

void register_scenario(py::module_& m) {
  py::class_<Scenario, std::shared_ptr<Scenario>>(
      m, "Scenario",
      "A validated scenario (docs/scenario-format.md): the document and the rod model built "
      "from it. Immutable: edit `to_dict()` and pass the dict to load_scenario() (or straight "
      "to solve()), which validates it again.")
      .def(
          "to_dict", [](const Scenario& s) { return to_python(s.document); },
          "A fresh dict of the scenario document (edit it freely; it is a copy).")
      .def(
          "to_json", [](const Scenario& s) { return rod::format_json(s.document) + "\n"; },
          "The scenario as JSON text, as save() writes it.")
      .def(
          "save",
          [](const Scenario& s, py::object path) {
            const std::string p =
                py::module_::import("os").attr("fspath")(path).cast<std::string>();
            rod::write_file_atomically(p, rod::format_json(s.document) + "\n", "scenario file");
          },
          py::arg("path"),
          "Writes the scenario as a JSON file (whole or not at all); load_scenario(path) reads "
          "back the same document.")
      .def_property_readonly(
          "name", [](const Scenario& s) { return s.model->name; }, "The scenario's `name`.")
      .def_property_readonly(
          "path", [](const Scenario& s) { return s.path; },
          "The file the scenario was read from (None for a dict).")
      .def_property_readonly(
          "actuators",
          [](const Scenario& s) {
            std::vector<std::string> names;
            for (const auto& a : s.model->actuators) names.push_back(a.name);
            return names;
          },
          "The actuator names, in file order.")
      .def_property_readonly(
          "tcas",
          [](const Scenario& s) {
            std::vector<std::string> ids;
            for (const auto& [id, t] : s.model->tcas) ids.push_back(id);
            return ids;
          },
          "The TCA ids of `tcas`.")
      .def_property_readonly(
          "length_m", [](const Scenario& s) { return s.model->length_m; }, "Body length L [m].")
      .def("__repr__", [](const Scenario& s) {
        return "<tcasim.Scenario '" + s.model->name + "'" + (s.path ? " from " + *s.path : "") +
               ">";
      });

  m.def(
      "load_scenario", [](py::object obj) { return as_scenario(obj); }, py::arg("scenario"),
      R"(Reads and validates a scenario (docs/scenario-format.md).

scenario: a file path (str or os.PathLike), a dict with the file's content, or a
    tcasim.Scenario (returned as is). Relative data paths of a dict resolve against the
    current folder.
Returns a tcasim.Scenario. Raises tcasim.InputError naming the key path, the value and
the rule for any malformed input (unknown key, wrong type, value out of range).)");
}

}  // namespace tcasim::python
