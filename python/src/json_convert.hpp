#pragma once
/// Conversion between JSON documents (nlohmann::json, as the library reads and writes files)
/// and Python objects (dict, list, str, int, float, bool, None), exact for every number: a
/// Python float is the same double, an integer stays an integer.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>

namespace tcasim::python {

namespace py = pybind11;

/// The Python object of a JSON value (objects keep their key order).
py::object to_python(const nlohmann::json& j);

/// The JSON value of a Python object. Accepts dict (str keys), list, tuple, str, bool, int,
/// float, None, numpy scalars and arrays (through .tolist()). Throws InputError naming the key
/// path (`actuators[0].drive`) for another type, a key that is not a string, a non-finite
/// float, an integer outside the 64-bit range, or nesting deeper than rod::kMaxJsonDepth.
nlohmann::json from_python(py::handle obj, const std::string& what = "scenario");

}  // namespace tcasim::python
