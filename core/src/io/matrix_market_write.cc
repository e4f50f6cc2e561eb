// Matrix Market writing: WriteMatrixMarket for a sparse matrix (coordinate,
// general or symmetric) and for a dense one (array), checked before the file
// is written atomically.
#include <charconv>
#include <cmath>
#include <string>

#include "femup/core/errors.h"
#include "femup/core/io/matrix_market.h"
#include "io/file_io.h"
#include "io/matrix_market_internal.h"

namespace femup {
namespace {

using internal::AtomicFile;
using matrix_market_internal::SizeText;

// ---------------------------------------------------------------------------
// Writing.

void AppendNumber(std::string* out, double value) {
  char buffer[40];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value,
                                    std::chars_format::general, 17);
  out->append(buffer, result.ptr);
}

void AppendIndex(std::string* out, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out->append(buffer, result.ptr);
}

constexpr size_t kFlushSize = 1 << 20;

}  // namespace

void WriteMatrixMarket(const std::string& path, const SparseMatrix& matrix,
                       bool symmetric) {
  // Check everything before touching the file system.
  if (symmetric) {
    if (matrix.rows() != matrix.cols()) {
      throw InputError(path, "cannot write a " + SizeText(matrix) +
                                 " matrix as 'symmetric': it is not square");
    }
    if (!IsSymmetric(matrix)) {
      throw InputError(path,
                       "cannot write the matrix as 'symmetric': it is not symmetric "
                       "(write it as general)");
    }
  }
  long long count = 0;
  for (Eigen::Index k = 0; k < matrix.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(matrix, k); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw InputError(path, "cannot write entry (" + std::to_string(it.row() + 1) +
                                   ", " + std::to_string(it.col() + 1) +
                                   "): it is not finite (NaN or infinite)");
      }
      if (!symmetric || it.row() >= it.col()) ++count;
    }
  }

  AtomicFile file(path);
  std::string text = "%%MatrixMarket matrix coordinate real ";
  text += symmetric ? "symmetric\n" : "general\n";
  text += "% written by femup\n";
  AppendIndex(&text, matrix.rows());
  text += ' ';
  AppendIndex(&text, matrix.cols());
  text += ' ';
  AppendIndex(&text, count);
  text += '\n';
  for (Eigen::Index k = 0; k < matrix.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(matrix, k); it; ++it) {
      if (symmetric && it.row() < it.col()) continue;
      AppendIndex(&text, it.row() + 1);
      text += ' ';
      AppendIndex(&text, it.col() + 1);
      text += ' ';
      AppendNumber(&text, it.value());
      text += '\n';
      if (text.size() >= kFlushSize) file.Write(&text);
    }
  }
  file.Write(&text);
  file.Commit();
}

void WriteMatrixMarket(const std::string& path, const Eigen::MatrixXd& matrix) {
  for (Eigen::Index j = 0; j < matrix.cols(); ++j) {
    for (Eigen::Index i = 0; i < matrix.rows(); ++i) {
      if (!std::isfinite(matrix(i, j))) {
        throw InputError(path, "cannot write entry (" + std::to_string(i + 1) + ", " +
                                   std::to_string(j + 1) +
                                   "): it is not finite (NaN or infinite)");
      }
    }
  }
  AtomicFile file(path);
  std::string text = "%%MatrixMarket matrix array real general\n% written by femup\n";
  AppendIndex(&text, matrix.rows());
  text += ' ';
  AppendIndex(&text, matrix.cols());
  text += '\n';
  for (Eigen::Index j = 0; j < matrix.cols(); ++j) {
    for (Eigen::Index i = 0; i < matrix.rows(); ++i) {
      AppendNumber(&text, matrix(i, j));
      text += '\n';
      if (text.size() >= kFlushSize) file.Write(&text);
    }
  }
  file.Write(&text);
  file.Commit();
}

}  // namespace femup
