// Least squares of a large compressed problem through its Gram matrix
// (private to the solvers; lstsq's route for LinearProblem::source_rows > 0).
//
// A compressed problem's A (normal_correction_system.h) is already a square
// root of a Gram matrix formed in floating point, so its singular values below
// about sqrt(machine epsilon) times the largest carry no information, and an
// SVD of A (about 22 n^3 flops with U and V) resolves nothing the Gram matrix
// G = D^-1 A' A D^-1 (D the column norms) does not. This route takes from G
// only what lstsq needs:
//   - all its eigenvalues (the squared singular values: one tridiagonal
//     reduction, LAPACK dsyevr), and the eigenvectors of the few below the rank
//     threshold, plus the smallest when the matrix is ill-conditioned
//     (symmetric_spectrum.h), for the identifiability report;
//   - the answer and the covariance from a Cholesky factor of G, made definite
//     on the dropped directions N by G + w_max N N' and projected off them by
//     P = I - N N' (then P (G + w_max N N')^-1 P is G's pseudo-inverse), the
//     answer refined twice with residuals in long double.
// The rank threshold is max(relative_tolerance, sqrt(n eps)) times the largest
// singular value: below sqrt(n eps) a singular value is the Gram matrix's
// rounding (the same n eps threshold the compression applies to its pivots).
#pragma once

#include <Eigen/Core>

#include "femup/solvers/identifiability.h"
#include "linear_common.h"

namespace femup::internal {

// What a least-squares decomposition gives the solver: the answer z in the
// free coordinates, the rank, a root of z's covariance per unit noise variance
// (Cov(z) = sigma^2 z_root z_root', n x n) and the identifiability report.
struct LeastSquaresDecomposition {
  Eigen::VectorXd z;
  Eigen::MatrixXd z_root;
  int rank = 0;
  Identifiability identifiability;
};

// The Gram route's effective relative rank threshold for n unknowns.
double GramRankTolerance(double relative_tolerance, Eigen::Index unknowns);

// False (and `out` unspecified) when the route cannot be trusted on this
// matrix: a zero or non-finite Gram matrix, a LAPACK failure, or a Cholesky
// factor that fails on the kept directions. The caller then takes the SVD.
bool LeastSquaresByGram(const ReducedProblem& reduced, double relative_tolerance,
                        bool scale_columns, LeastSquaresDecomposition* out);

}  // namespace femup::internal
