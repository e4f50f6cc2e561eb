// Shared by the binding files of the Python module femup._femup: one Init
// function per area (models, measurements and ERA, solvers, studies,
// pipelines) and the conversion of sparse matrices to scipy.sparse.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "femup/core/fe/model.h"

namespace femup_python {

namespace py = pybind11;

// A scipy.sparse.csc_matrix over the compressed column storage of `matrix`
// without copying it: its arrays view the matrix's own storage and keep
// `owner` (the Python object that holds the matrix) alive. `matrix` must be in
// compressed form; when it is not, it is copied once into compressed form.
py::object CscView(const femup::SparseMatrix& matrix, py::handle owner);
// The same for a matrix the caller gives away: the arrays own it.
py::object CscOwned(femup::SparseMatrix matrix);
// A scipy.sparse matrix (any format) or a dense 2D array as an Eigen sparse
// matrix (a copy, in compressed column form). Throws femup::InputError naming
// `field` when `value` is neither or holds a non-finite value.
femup::SparseMatrix ToSparse(py::handle value, const std::string& field);

// A Python list of references into `items`, a vector held by the Python object
// `parent` (kept alive by each item): no copies.
template <typename T>
py::list RefList(const std::vector<T>& items, py::handle parent) {
  py::list out;
  for (const T& item : items) {
    out.append(py::cast(&item, py::return_value_policy::reference_internal, parent));
  }
  return out;
}

// T::Validate() as Python has always seen it: "" when valid, else
// "field: what is wrong" (femup::Invalid is not bound).
template <typename T>
std::string ValidateText(const T& options) {
  return options.Validate().ToString();
}

// The Python exception femup.InputError (a ValueError), set up in module.cc.
extern PyObject* g_input_error;

void InitModels(py::module_& m);
void InitMeasurements(py::module_& m);
void InitSolvers(py::module_& m);
void InitStudies(py::module_& m);
void InitPipelines(py::module_& m);

}  // namespace femup_python
