#pragma once
/// Shared pieces of the tcasim Python bindings: the scenario handle, the error types, and
/// the registration function of each binding file.
#include <pybind11/pybind11.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "rod/model.hpp"

namespace tcasim::python {

namespace py = pybind11;

/// A validated scenario: the document as given (a dict or a file's content) and the rod model
/// the library built from it. Immutable; edits go through to_dict() and load_scenario().
struct Scenario {
  nlohmann::json document;
  std::shared_ptr<const rod::RodModel> model;
  std::optional<std::string> path;  ///< the file it was read from, if any
};

/// A Scenario from a Scenario (itself), a dict (validated) or a path (str or os.PathLike).
std::shared_ptr<Scenario> as_scenario(py::handle obj);

/// Throws tcasim.SolverError(message, result) (the Python class of tcasim._errors).
[[noreturn]] void throw_solver_error(const std::string& message, py::object result);

/// Index of the actuator called `name` in the model; InputError(key, name, ...) listing the
/// names otherwise.
std::size_t actuator_index(const rod::RodModel& model, const std::string& name,
                           const std::string& key);

void register_scenario(py::module_& m);
void register_solve(py::module_& m);
void register_inverse(py::module_& m);
void register_simulate(py::module_& m);

}  // namespace tcasim::python
