#include "femup/core/linalg/dense_kernels.h"

#include <cstddef>
#include <string>

#include "femup/core/errors.h"

// BLAS (Fortran): CHARACTER arguments carry hidden lengths after the others
// (core/src/linalg/banded_eigen.cc says why they must be passed).
extern "C" {
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* beta,
            double* c, const int* ldc, std::size_t uplo_length, std::size_t trans_length);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag,
            const int* m, const int* n, const double* alpha, const double* a,
            const int* lda, double* b, const int* ldb, std::size_t side_length,
            std::size_t uplo_length, std::size_t transa_length, std::size_t diag_length);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info,
             std::size_t uplo_length);
void dpstrf_(const char* uplo, const int* n, double* a, const int* lda, int* piv,
             int* rank, const double* tol, double* work, int* info,
             std::size_t uplo_length);
void dtrtri_(const char* uplo, const char* diag, const int* n, double* a, const int* lda,
             int* info, std::size_t uplo_length, std::size_t diag_length);
}

namespace femup {

void RankUpdateLower(const Eigen::Ref<const Eigen::MatrixXd>& a, double alpha,
                     double beta, Eigen::Ref<Eigen::MatrixXd> c) {
  const int k = static_cast<int>(a.rows());
  const int n = static_cast<int>(a.cols());
  if (c.rows() != n || c.cols() != n) {
    throw InputError("c", "must be " + std::to_string(n) + " x " + std::to_string(n) +
                              " for a of " + std::to_string(n) + " columns, got " +
                              std::to_string(c.rows()) + " x " +
                              std::to_string(c.cols()));
  }
  if (n == 0) return;
  if (k == 0) {  // c = beta c (dsyrk would do it too, but lda must be >= 1)
    if (beta == 0) {
      c.triangularView<Eigen::Lower>().setZero();  // as the BLAS: c need not be set
    } else {
      c.triangularView<Eigen::Lower>() *= beta;
    }
    return;
  }
  const int lda = static_cast<int>(a.outerStride());
  const int ldc = static_cast<int>(c.outerStride());
  dsyrk_("L", "T", &n, &k, &alpha, a.data(), &lda, &beta, c.data(), &ldc, 1, 1);
}

namespace {

void RequireSquare(const Eigen::Ref<Eigen::MatrixXd>& a) {
  if (a.rows() != a.cols()) {
    throw InputError("a", "must be square, got " + std::to_string(a.rows()) + " x " +
                              std::to_string(a.cols()));
  }
}

}  // namespace

void SolveLowerInPlace(const Eigen::Ref<const Eigen::MatrixXd>& l,
                       Eigen::Ref<Eigen::MatrixXd> x) {
  if (l.rows() != l.cols()) {
    throw InputError("l", "must be square, got " + std::to_string(l.rows()) + " x " +
                              std::to_string(l.cols()));
  }
  if (x.rows() != l.rows()) {
    throw InputError("x", "must have " + std::to_string(l.rows()) + " rows (l's), got " +
                              std::to_string(x.rows()));
  }
  const int m = static_cast<int>(x.rows());
  const int n = static_cast<int>(x.cols());
  if (m == 0 || n == 0) return;
  const int lda = static_cast<int>(l.outerStride());
  const int ldb = static_cast<int>(x.outerStride());
  const double one = 1.0;
  dtrsm_("L", "L", "N", "N", &m, &n, &one, l.data(), &lda, x.data(), &ldb, 1, 1, 1, 1);
}

bool CholeskyLower(Eigen::Ref<Eigen::MatrixXd> a) {
  RequireSquare(a);
  const int n = static_cast<int>(a.rows());
  if (n == 0) return true;
  const int lda = static_cast<int>(a.outerStride());
  int info = 0;
  dpotrf_("L", &n, a.data(), &lda, &info, 1);
  return info == 0;
}

bool InvertLowerTriangular(Eigen::Ref<Eigen::MatrixXd> a) {
  RequireSquare(a);
  const int n = static_cast<int>(a.rows());
  if (n == 0) return true;
  const int lda = static_cast<int>(a.outerStride());
  int info = 0;
  dtrtri_("L", "N", &n, a.data(), &lda, &info, 1, 1);
  return info == 0;
}

int PivotedCholeskyLower(Eigen::Ref<Eigen::MatrixXd> a, double tolerance,
                         std::vector<int>* pivots) {
  RequireSquare(a);
  const int n = static_cast<int>(a.rows());
  pivots->resize(static_cast<std::size_t>(n));
  if (n == 0) return 0;
  for (int j = 0; j < n; ++j) {
    if (!a.col(j).tail(n - j).allFinite()) return -1;
  }
  const int lda = static_cast<int>(a.outerStride());
  std::vector<double> work(2 * static_cast<std::size_t>(n));
  int rank = 0, info = 0;
  dpstrf_("L", &n, a.data(), &lda, pivots->data(), &rank, &tolerance, work.data(), &info,
          1);
  if (info < 0) return -1;
  for (int& k : *pivots) --k;  // Fortran's 1-based indices
  return rank;
}

}  // namespace femup
