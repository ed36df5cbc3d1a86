#include "json_convert.hpp"

#include <cmath>
#include <cstdint>
#include <string>

#include "common/error.hpp"
#include "rod/json_file.hpp"

namespace tcasim::python {

namespace {

using json = nlohmann::json;

std::string child_key(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string type_name(py::handle obj) { return py::str(py::type::handle_of(obj).attr("__name__")); }

json convert(py::handle obj, const std::string& what, const std::string& path, int depth) {
  const std::string key = path.empty() ? what : path;
  if (obj.is_none()) return nullptr;
  if (PyBool_Check(obj.ptr())) return obj.ptr() == Py_True;
  if (PyLong_Check(obj.ptr())) {
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(obj.ptr(), &overflow);
    if (overflow == 0) return static_cast<std::int64_t>(v);
    if (overflow > 0) {
      const unsigned long long u = PyLong_AsUnsignedLongLong(obj.ptr());
      if (!PyErr_Occurred()) return static_cast<std::uint64_t>(u);
      PyErr_Clear();
    }
    throw InputError(key, py::str(obj), "is an integer outside the 64-bit range");
  }
  if (PyFloat_Check(obj.ptr())) {
    const double v = PyFloat_AS_DOUBLE(obj.ptr());
    if (!std::isfinite(v)) throw InputError(key, format_value(v), "must be a finite number");
    return v;
  }
  if (PyUnicode_Check(obj.ptr())) return obj.cast<std::string>();
  if (depth >= rod::kMaxJsonDepth) {
    throw InputError(
        key, "(" + type_name(obj) + ")",
        "nests lists and dicts deeper than " + std::to_string(rod::kMaxJsonDepth) + " levels");
  }
  if (PyDict_Check(obj.ptr())) {
    json out = json::object();
    for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(obj)) {
      if (!PyUnicode_Check(k.ptr())) {
        throw InputError(key, py::repr(k), "has a key that is not a string");
      }
      const std::string name = k.cast<std::string>();
      out[name] = convert(v, what, child_key(path, name), depth + 1);
    }
    return out;
  }
  if (PyList_Check(obj.ptr()) || PyTuple_Check(obj.ptr())) {
    json out = json::array();
    std::size_t i = 0;
    for (const py::handle item : obj) {
      out.push_back(convert(item, what, path + "[" + std::to_string(i) + "]", depth + 1));
      ++i;
    }
    return out;
  }
  // numpy scalars and arrays: their Python equivalents.
  if (py::hasattr(obj, "tolist") && py::hasattr(obj, "dtype")) {
    return convert(obj.attr("tolist")(), what, path, depth);
  }
  throw InputError(key, py::repr(obj),
                   "has type " + type_name(obj) +
                       " (JSON values are dict, list, str, int, float, bool or None)");
}

}  // namespace

py::object to_python(const json& j) {
  switch (j.type()) {
    case json::value_t::null:
      return py::none();
    case json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case json::value_t::number_float:
      return py::float_(j.get<double>());
    case json::value_t::string:
      return py::str(j.get_ref<const std::string&>());
    case json::value_t::array: {
      py::list out(j.size());
      std::size_t i = 0;
      for (const json& item : j) out[i++] = to_python(item);
      return std::move(out);
    }
    case json::value_t::object: {
      py::dict out;
      for (const auto& [k, v] : j.items()) out[py::str(k)] = to_python(v);
      return std::move(out);
    }
    default:
      return py::none();  // binary and discarded values never occur in tcasim documents
  }
}

json from_python(py::handle obj, const std::string& what) { return convert(obj, what, "", 0); }

}  // namespace tcasim::python
