// Keyword arguments as Python objects (bindings.hpp): the conversions that pybind11's
// casters would refuse with a TypeError become InputErrors naming the keyword.
#include <fmt/format.h>

#include <climits>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "common/error.hpp"

namespace tcasim::python {

namespace {

std::string repr_text(py::handle value) { return py::repr(value).cast<std::string>(); }

/// A bool is an int in Python, but steps=True is a mistake, not 1.
bool is_bool(py::handle value) { return PyBool_Check(value.ptr()); }

}  // namespace

long long integer_arg(py::handle value, const char* key) {
  if (is_bool(value) || !PyIndex_Check(value.ptr())) {
    throw InputError(key, repr_text(value), "must be an integer");
  }
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) throw py::error_already_set();
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0) {
    throw InputError(key, py::str(index).cast<std::string>(),
                     fmt::format("must be an integer in [{}, {}] (64 bits)", LLONG_MIN, LLONG_MAX));
  }
  if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
  return v;
}

std::optional<long long> optional_integer_arg(py::handle value, const char* key) {
  if (value.is_none()) return std::nullopt;
  return integer_arg(value, key);
}

double number_arg(py::handle value, const char* key) {
  if (is_bool(value) || PyUnicode_Check(value.ptr()) || PyBytes_Check(value.ptr())) {
    throw InputError(key, repr_text(value), "must be a number");
  }
  const double v = PyFloat_AsDouble(value.ptr());
  if (v == -1.0 && PyErr_Occurred()) {
    const bool overflow = PyErr_ExceptionMatches(PyExc_OverflowError);
    PyErr_Clear();
    if (overflow) {
      throw InputError(key, py::str(value).cast<std::string>(),
                       "must be a number within the range of a double (|x| < 1.8e308)");
    }
    throw InputError(key, repr_text(value), "must be a number");
  }
  return v;
}

std::optional<double> optional_number_arg(py::handle value, const char* key) {
  if (value.is_none()) return std::nullopt;
  return number_arg(value, key);
}

std::vector<double> number_list_arg(py::handle value, const char* key) {
  if (PyUnicode_Check(value.ptr()) || PyBytes_Check(value.ptr()) ||
      !py::isinstance<py::iterable>(value)) {
    throw InputError(key, repr_text(value), "must be a sequence of numbers");
  }
  std::vector<double> out;
  for (const py::handle item : value) out.push_back(number_arg(item, key));
  return out;
}

}  // namespace tcasim::python
