// femup._femup: the library's pipelines for Python (femup/__init__.py is the
// package's front). Bad input raises femup.InputError (a ValueError) whose
// message is the C++ InputError's, naming the file, line and field; its
// `where` attribute is the location part alone.
#include <pybind11/pybind11.h>

#include "common.h"
#include "femup/core/errors.h"
#include "femup/core/linalg/blas.h"

namespace femup_python {

PyObject* g_input_error = nullptr;
PyObject* g_numerical_error = nullptr;

namespace {

void TranslateInputError(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const femup::InputError& e) {
    py::object error = py::reinterpret_borrow<py::object>(g_input_error)(e.what());
    error.attr("where") = e.where();
    PyErr_SetObject(g_input_error, error.ptr());
  } catch (const femup::NumericalError& e) {
    py::object error = py::reinterpret_borrow<py::object>(g_numerical_error)(e.what());
    error.attr("where") = e.where();
    PyErr_SetObject(g_numerical_error, error.ptr());
  }
}

}  // namespace

}  // namespace femup_python

PYBIND11_MODULE(_femup, m) {
  namespace fp = femup_python;
  namespace py = pybind11;
  m.doc() =
      "femup: finite element model updating from vibration measurements (the C++ "
      "library's pipelines; see docs/python.md)";
  static py::exception<femup::InputError> input_error(m, "InputError", PyExc_ValueError);
  input_error.attr("__doc__") =
      "Bad input: the message names the file, line and field (as the command line's "
      "errors do); `where` holds the location alone.";
  fp::g_input_error = input_error.ptr();
  static py::exception<femup::NumericalError> numerical_error(m, "NumericalError",
                                                              PyExc_RuntimeError);
  numerical_error.attr("__doc__") =
      "A numerical method failed on valid input (an eigensolver that did not "
      "converge); `where` holds the location.";
  fp::g_numerical_error = numerical_error.ptr();
  py::register_exception_translator(&fp::TranslateInputError);
  // One BLAS thread per caller, as the command line (femup/core/linalg/blas.h).
  femup::UseOneBlasThreadPerCaller();
  m.def("blas", &femup::BlasSummary,
        "The BLAS and LAPACK femup is linked against and its threads per call, e.g. "
        "'BLAS: OpenBLAS 0.3.21 ..., 1 thread per call' (femup parallelises above it).");
  fp::InitModels(m);
  fp::InitMeasurements(m);
  fp::InitSolvers(m);
  fp::InitStudies(m);
  fp::InitPipelines(m);
}
