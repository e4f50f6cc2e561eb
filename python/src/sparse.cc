// scipy.sparse <-> Eigen::SparseMatrix<double> (compressed column storage on
// both sides, so a matrix crosses to Python without a copy).
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "common.h"
#include "femup/core/errors.h"

namespace femup_python {

namespace {

py::object CscFromArrays(const femup::SparseMatrix& a, py::handle owner) {
  const auto nnz = static_cast<py::ssize_t>(a.nonZeros());
  py::array_t<double> data({nnz}, {static_cast<py::ssize_t>(sizeof(double))},
                           a.valuePtr(), owner);
  py::array_t<int> indices({nnz}, {static_cast<py::ssize_t>(sizeof(int))},
                           a.innerIndexPtr(), owner);
  py::array_t<int> indptr({static_cast<py::ssize_t>(a.outerSize() + 1)},
                          {static_cast<py::ssize_t>(sizeof(int))}, a.outerIndexPtr(),
                          owner);
  // Views of a model's own storage: not to be written through.
  for (py::array* arr :
       {static_cast<py::array*>(&data), static_cast<py::array*>(&indices),
        static_cast<py::array*>(&indptr)}) {
    arr->attr("setflags")(py::arg("write") = false);
  }
  py::object csc = py::module_::import("scipy.sparse").attr("csc_matrix");
  return csc(py::make_tuple(data, indices, indptr),
             py::arg("shape") = py::make_tuple(a.rows(), a.cols()),
             py::arg("copy") = false);
}

}  // namespace

py::object CscView(const femup::SparseMatrix& matrix, py::handle owner) {
  if (!matrix.isCompressed() || matrix.nonZeros() == 0) {
    femup::SparseMatrix copy = matrix;
    return CscOwned(std::move(copy));
  }
  return CscFromArrays(matrix, owner);
}

py::object CscOwned(femup::SparseMatrix matrix) {
  auto* held = new femup::SparseMatrix();
  held->swap(matrix);
  held->makeCompressed();
  if (held->nonZeros() == 0) {
    // No storage to view (its pointers may be null): empty arrays of its size.
    const auto rows = held->rows(), cols = held->cols();
    delete held;
    py::object csc = py::module_::import("scipy.sparse").attr("csc_matrix");
    return csc(py::make_tuple(rows, cols));
  }
  py::capsule owner(held, [](void* p) { delete static_cast<femup::SparseMatrix*>(p); });
  return CscFromArrays(*held, owner);
}

femup::SparseMatrix ToSparse(py::handle value, const std::string& field) {
  // Read through scipy's CSC arrays (read-only views such as CscView's are
  // fine: they are only read); a dense 2D array goes through csc_matrix.
  using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
  using Ints = py::array_t<long long, py::array::c_style | py::array::forcecast>;
  femup::SparseMatrix out;
  try {
    py::module_ sparse = py::module_::import("scipy.sparse");
    py::object csc = sparse.attr("issparse")(value).cast<bool>()
                         ? value.attr("tocsc")()
                         : sparse.attr("csc_matrix")(py::module_::import("numpy").attr(
                               "asarray")(value, py::arg("dtype") = "float64"));
    const auto shape = csc.attr("shape").cast<std::pair<long long, long long>>();
    const Doubles data = Doubles::ensure(csc.attr("data"));
    const Ints indices = Ints::ensure(csc.attr("indices"));
    const Ints indptr = Ints::ensure(csc.attr("indptr"));
    if (!data || !indices || !indptr || indptr.size() != shape.second + 1) {
      throw femup::InputError(field,
                              "expected a scipy.sparse matrix or a 2D array of numbers");
    }
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(data.size()));
    for (long long c = 0; c < shape.second; ++c) {
      for (long long k = indptr.at(c); k < indptr.at(c + 1); ++k) {
        const double v = data.at(k);
        if (!std::isfinite(v))
          throw femup::InputError(field, "holds a value that is not finite");
        const long long r = indices.at(k);
        if (r < 0 || r >= shape.first)
          throw femup::InputError(field, "a row index is out of range");
        entries.emplace_back(static_cast<int>(r), static_cast<int>(c), v);
      }
    }
    out.resize(static_cast<Eigen::Index>(shape.first),
               static_cast<Eigen::Index>(shape.second));
    out.setFromTriplets(entries.begin(), entries.end());
  } catch (const py::error_already_set&) {
    throw femup::InputError(field,
                            "expected a scipy.sparse matrix or a 2D array of numbers");
  } catch (const py::cast_error&) {
    throw femup::InputError(field,
                            "expected a scipy.sparse matrix or a 2D array of numbers");
  }
  out.makeCompressed();
  return out;
}

}  // namespace femup_python
