// tcasim._tcasim: the extension module of the `tcasim` Python package (docs/python.md).
// Errors of the library become the Python types of tcasim._errors: InputError (key, value,
// rule), DomainError; SolverError carries the partial result of a solve that did not converge.
#include <pybind11/pybind11.h>

#include <exception>

#include "bindings.hpp"
#include "common/data_dir.hpp"
#include "common/error.hpp"

namespace tcasim::python {

namespace {

// The Python classes (owned by the tcasim._errors module, which lives as long as the
// interpreter; one extra reference each, never released).
py::handle input_error_type;
py::handle domain_error_type;
py::handle solver_error_type;

}  // namespace

void throw_solver_error(const std::string& message, py::object result) {
  py::object exc = py::reinterpret_borrow<py::object>(solver_error_type)(message, result);
  PyErr_SetObject(solver_error_type.ptr(), exc.ptr());
  throw py::error_already_set();
}

}  // namespace tcasim::python

PYBIND11_MODULE(_tcasim, m) {
  namespace py = pybind11;
  using namespace tcasim::python;
  m.doc() =
      "tcasim's compiled core: scenarios, solves, sweeps, inverse and grasp problems, TCA "
      "curves, simulations. Use it through the `tcasim` package (docs/python.md).";
  py::module_ errors = py::module_::import("tcasim._errors");
  input_error_type = errors.attr("InputError").cast<py::object>().release();
  domain_error_type = errors.attr("DomainError").cast<py::object>().release();
  solver_error_type = errors.attr("SolverError").cast<py::object>().release();

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const tcasim::InputError& e) {
      py::object exc =
          py::reinterpret_borrow<py::object>(input_error_type)(e.key(), e.value(), e.rule());
      PyErr_SetObject(input_error_type.ptr(), exc.ptr());
    } catch (const tcasim::DomainError& e) {
      PyErr_SetString(domain_error_type.ptr(), e.what());
    } catch (const tcasim::ExternalError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  m.def("data_directory", &tcasim::data_directory,
        "The folder of the shipped data (materials/, scenarios/): $TCASIM_DATA_DIR if set, "
        "else the installed package's, else the source tree's data/.");
  register_scenario(m);
  register_solve(m);
  register_inverse(m);
  register_simulate(m);
}
