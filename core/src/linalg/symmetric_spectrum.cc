#include "femup/core/linalg/symmetric_spectrum.h"

#include <cstddef>
#include <vector>

// LAPACK (Fortran): the hidden lengths of the character arguments are passed
// after the others, as core/src/linalg/banded_eigen.cc explains.
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info,
             std::size_t uplo_length);
void dsygst_(const int* itype, const char* uplo, const int* n, double* a, const int* lda,
             const double* b, const int* ldb, int* info, std::size_t uplo_length);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag,
            const int* m, const int* n, const double* alpha, const double* a,
            const int* lda, double* b, const int* ldb, std::size_t side_length,
            std::size_t uplo_length, std::size_t transa_length, std::size_t diag_length);
void dsyevr_(const char* jobz, const char* range, const char* uplo, const int* n,
             double* a, const int* lda, const double* vl, const double* vu, const int* il,
             const int* iu, const double* abstol, int* m, double* w, double* z,
             const int* ldz, int* isuppz, double* work, const int* lwork, int* iwork,
             const int* liwork, int* info, std::size_t jobz_length,
             std::size_t range_length, std::size_t uplo_length);
}

namespace femup {
namespace {

// dsyevr on `a` (destroyed): jobz "N" or "V", range "A" (all) or "I" (the
// il-th to iu-th smallest, 1-based).
bool Dsyevr(const char* jobz, const char* range, int il, int iu, Eigen::MatrixXd* a,
            Eigen::VectorXd* values, Eigen::MatrixXd* vectors) {
  const int n = static_cast<int>(a->rows());
  values->setZero(n);
  if (n == 0) {
    if (vectors) vectors->resize(0, 0);
    return true;
  }
  const bool want_vectors = jobz[0] == 'V';
  const int columns = range[0] == 'I' ? iu - il + 1 : n;
  Eigen::MatrixXd z(want_vectors ? n : 1, want_vectors ? columns : 1);
  const int ldz = static_cast<int>(z.rows());
  std::vector<int> support(2 * static_cast<std::size_t>(n));
  const double vl = 0, vu = 0, abstol = 0;  // abstol 0: LAPACK's default accuracy
  int found = 0, info = 0, lwork = -1, liwork = -1, iwork_size = 0;
  double work_size = 0;
  dsyevr_(jobz, range, "L", &n, a->data(), &n, &vl, &vu, &il, &iu, &abstol, &found,
          values->data(), z.data(), &ldz, support.data(), &work_size, &lwork, &iwork_size,
          &liwork, &info, 1, 1, 1);
  if (info != 0) return false;
  lwork = static_cast<int>(work_size);
  liwork = iwork_size;
  std::vector<double> work(static_cast<std::size_t>(lwork));
  std::vector<int> iwork(static_cast<std::size_t>(liwork));
  dsyevr_(jobz, range, "L", &n, a->data(), &n, &vl, &vu, &il, &iu, &abstol, &found,
          values->data(), z.data(), &ldz, support.data(), work.data(), &lwork,
          iwork.data(), &liwork, &info, 1, 1, 1);
  if (info != 0 || found != columns) return false;
  values->conservativeResize(found);
  if (want_vectors) *vectors = z.leftCols(found);
  return true;
}

}  // namespace

bool SymmetricEigenvalues(Eigen::MatrixXd lower, Eigen::VectorXd* values) {
  return Dsyevr("N", "A", 0, 0, &lower, values, nullptr);
}

bool SmallestEigenpairs(Eigen::MatrixXd lower, int count, Eigen::VectorXd* values,
                        Eigen::MatrixXd* vectors) {
  const int n = static_cast<int>(lower.rows());
  if (count < 0 || count > n) return false;
  if (count == 0) {
    values->resize(0);
    vectors->resize(n, 0);
    return true;
  }
  return Dsyevr("V", "I", 1, count, &lower, values, vectors);
}

PencilStatus SmallestPencilEigenpairs(Eigen::MatrixXd stiffness, Eigen::MatrixXd mass,
                                      int count, Eigen::VectorXd* values,
                                      Eigen::MatrixXd* vectors) {
  const int n = static_cast<int>(stiffness.rows());
  if (stiffness.cols() != n || mass.rows() != n || mass.cols() != n || count < 0 ||
      count > n) {
    return PencilStatus::kFailed;
  }
  if (count == 0) {
    values->resize(0);
    vectors->resize(n, 0);
    return PencilStatus::kOk;
  }
  int info = 0;
  dpotrf_("L", &n, mass.data(), &n, &info, 1);  // M = L L'
  if (info > 0) return PencilStatus::kMassNotPositiveDefinite;
  if (info < 0) return PencilStatus::kFailed;
  const int itype = 1;  // K x = lambda M x -> (inv(L) K inv(L')) y = lambda y
  dsygst_(&itype, "L", &n, stiffness.data(), &n, mass.data(), &n, &info, 1);
  if (info != 0) return PencilStatus::kFailed;
  if (!Dsyevr("V", "I", 1, count, &stiffness, values, vectors))
    return PencilStatus::kFailed;
  const double one = 1.0;  // x = inv(L') y
  dtrsm_("L", "L", "T", "N", &n, &count, &one, mass.data(), &n, vectors->data(), &n, 1, 1,
         1, 1);
  return vectors->allFinite() && values->allFinite() ? PencilStatus::kOk
                                                     : PencilStatus::kFailed;
}

}  // namespace femup
