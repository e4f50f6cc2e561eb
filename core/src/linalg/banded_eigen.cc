#include "femup/core/linalg/banded_eigen.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

// LAPACK (gfortran): every CHARACTER argument has a hidden length argument
// after the others. They must be passed: a Fortran routine may forward them in
// a tail call and write them into the caller's argument area, which corrupts
// the C++ caller's stack when they are missing.
extern "C" {
void dsbgvx_(const char* jobz, const char* range, const char* uplo, const int* n,
             const int* ka, const int* kb, double* ab, const int* ldab, double* bb,
             const int* ldbb, double* q, const int* ldq, const double* vl,
             const double* vu, const int* il, const int* iu, const double* abstol, int* m,
             double* w, double* z, const int* ldz, double* work, int* iwork, int* ifail,
             int* info, std::size_t jobz_length, std::size_t range_length,
             std::size_t uplo_length);
void dgbtrf_(const int* m, const int* n, const int* kl, const int* ku, double* ab,
             const int* ldab, int* ipiv, int* info);
void dgbtrs_(const char* trans, const int* n, const int* kl, const int* ku,
             const int* nrhs, const double* ab, const int* ldab, const int* ipiv,
             double* b, const int* ldb, int* info, std::size_t trans_length);
}

namespace femup {

int Bandwidth(const Eigen::MatrixXd& a) {
  int b = 0;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      if (a(i, j) != 0) b = std::max(b, static_cast<int>(std::abs(i - j)));
  return b;
}

bool LowestBandedEigenpairs(const Eigen::MatrixXd& stiffness, const Eigen::MatrixXd& mass,
                            int count, bool vectors, BandedEigenpairs* out,
                            std::string* why) {
  const int n = static_cast<int>(stiffness.rows());
  if (stiffness.cols() != n || mass.rows() != n || mass.cols() != n || n == 0) {
    if (why) *why = "K and M must be square, non-empty and of the same size";
    return false;
  }
  if (count < 1 || count > n) {
    if (why) *why = "the number of eigenpairs must be between 1 and the size";
    return false;
  }
  const int kd = std::max(Bandwidth(stiffness), Bandwidth(mass));
  const int ld = kd + 1;
  // Upper band storage: ab(kd + i - j, j) = a(i, j) for max(0, j - kd) <= i <= j.
  std::vector<double> ab(static_cast<std::size_t>(ld) * n, 0.0), bb(ab.size(), 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - kd); i <= j; ++i) {
      ab[static_cast<std::size_t>(kd + i - j + j * ld)] = stiffness(i, j);
      bb[static_cast<std::size_t>(kd + i - j + j * ld)] = mass(i, j);
    }
  const int il = 1, iu = count, ldz = 1;
  // Twice the underflow threshold: the eigenvalues to full relative accuracy
  // of the tridiagonal problem (LAPACK's advice), which the lowest modes of a
  // stiff beam need.
  const double vl = 0, vu = 0, abstol = 2 * std::numeric_limits<double>::min();
  int found = 0, info = 0;
  std::vector<double> w(n), work(7 * static_cast<std::size_t>(n)), q(1), z(1);
  std::vector<int> iwork(5 * static_cast<std::size_t>(n)), ifail(n);
  dsbgvx_("N", "I", "U", &n, &kd, &kd, ab.data(), &ld, bb.data(), &ld, q.data(), &ldz,
          &vl, &vu, &il, &iu, &abstol, &found, w.data(), z.data(), &ldz, work.data(),
          iwork.data(), ifail.data(), &info, 1, 1, 1);
  if (info != 0 || found != count) {
    if (why)
      *why = info > n ? "the mass matrix is not positive definite"
                      : "LAPACK dsbgvx failed (info " + std::to_string(info) + ")";
    return false;
  }
  out->eigenvalues = Eigen::Map<Eigen::VectorXd>(w.data(), count);
  out->vectors.resize(0, 0);
  if (!vectors) return true;
  // Inverse iteration: (K - sigma M) x_{k+1} = M x_k with sigma the computed
  // eigenvalue; the system is nearly singular in that eigenvector's direction
  // only, so two steps from any start that is not orthogonal to it give the
  // vector to rounding. Band storage for dgbtrf: kl = ku = kd, 2 kd extra rows.
  const int ldlu = 3 * kd + 1;
  out->vectors.resize(n, count);
  std::vector<double> lu(static_cast<std::size_t>(ldlu) * n);
  std::vector<int> ipiv(n);
  const double scale = std::max(stiffness.cwiseAbs().maxCoeff(), 1e-300);
  for (int p = 0; p < count; ++p) {
    // Shift a hair off the eigenvalue so the factorisation is not exactly
    // singular; the amplification of the wanted direction stays ~1e12.
    const double lambda = out->eigenvalues[p];
    const double sigma = lambda + 1e-12 * std::max(std::abs(lambda), scale * 1e-12);
    std::fill(lu.begin(), lu.end(), 0.0);
    for (int j = 0; j < n; ++j)
      for (int i = std::max(0, j - kd); i <= std::min(n - 1, j + kd); ++i)
        lu[static_cast<std::size_t>(2 * kd + i - j + j * ldlu)] =
            stiffness(i, j) - sigma * mass(i, j);
    dgbtrf_(&n, &n, &kd, &kd, lu.data(), &ldlu, ipiv.data(), &info);
    if (info != 0) {
      // info > 0: an exactly zero pivot, which the shift off the eigenvalue
      // makes all but impossible.
      if (why) *why = "LAPACK dgbtrf failed (info " + std::to_string(info) + ")";
      return false;
    }
    // A start with every component present: a fixed, irregular vector.
    Eigen::VectorXd x(n);
    for (int i = 0; i < n; ++i) x[i] = 1.0 + 0.5 * std::sin(1.7 * i + 0.3 * p);
    const int one = 1;
    for (int step = 0; step < 2; ++step) {
      Eigen::VectorXd rhs = mass * x;
      dgbtrs_("N", &n, &kd, &kd, &one, lu.data(), &ldlu, ipiv.data(), rhs.data(), &n,
              &info, 1);
      if (info != 0 || !rhs.allFinite()) {
        if (why) *why = "inverse iteration failed";
        return false;
      }
      x = rhs / rhs.cwiseAbs().maxCoeff();
    }
    // Orthogonalise against the lower vectors (M inner product): matters only
    // for close eigenvalues.
    for (int r = 0; r < p; ++r)
      x -= out->vectors.col(r) * out->vectors.col(r).dot(mass * x);
    const double norm = std::sqrt(x.dot(mass * x));
    if (!(norm > 0)) {
      if (why) *why = "inverse iteration gave a zero vector";
      return false;
    }
    x /= norm;
    Eigen::Index largest = 0;
    x.cwiseAbs().maxCoeff(&largest);
    if (x[largest] < 0) x = -x;
    out->vectors.col(p) = x;
  }
  return true;
}

}  // namespace femup
