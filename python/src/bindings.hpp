#pragma once
/// Shared pieces of the tcasim Python bindings: the scenario handle, the error types, and
/// the registration function of each binding file.
#include <pybind11/pybind11.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

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

/// Keyword arguments taken as Python objects, so a value of the wrong kind or out of the C++
/// range is an InputError naming the keyword, not pybind11's TypeError; the option's own rule
/// is then checked by study/options.hpp, as for the command line.
/// An integer (int or an object with __index__, e.g. numpy.int64; not a bool) in the 64-bit
/// range.
long long integer_arg(py::handle value, const char* key);
/// integer_arg, or nullopt for None.
std::optional<long long> optional_integer_arg(py::handle value, const char* key);
/// A real number (float, int or an object with __float__; not a bool or a text) in the range
/// of a double; NaN and infinities pass (the option's rule refuses them where it must).
double number_arg(py::handle value, const char* key);
/// number_arg, or nullopt for None.
std::optional<double> optional_number_arg(py::handle value, const char* key);
/// An iterable of real numbers (list, tuple, range, numpy array), each as number_arg; not a
/// text.
std::vector<double> number_list_arg(py::handle value, const char* key);

void register_scenario(py::module_& m);
void register_solve(py::module_& m);
void register_inverse(py::module_& m);
void register_simulate(py::module_& m);

}  // namespace tcasim::python
