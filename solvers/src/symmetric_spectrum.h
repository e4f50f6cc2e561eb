// The spectrum of a dense symmetric matrix by LAPACK's dsyevr (private to the
// solvers): all eigenvalues, and the eigenvectors of the few smallest only.
// Both reduce the matrix to tridiagonal form once (4/3 n^3 flops, blocked
// dsytrd); the values then cost O(n^2) and each vector O(n^2) (MRRR), where a
// full decomposition would add about 4 n^3 for all the vectors.
#pragma once

#include <Eigen/Core>

namespace femup::internal {

// Eigenvalues of the symmetric matrix whose lower triangle `lower` holds
// (n x n; the upper triangle is not read), ascending. False when LAPACK
// reports a failure (info != 0).
bool SymmetricEigenvalues(Eigen::MatrixXd lower, Eigen::VectorXd* values);

// The `count` smallest eigenvalues (ascending) and their orthonormal
// eigenvectors (n x count, column i for values[i]). 0 <= count <= n.
bool SmallestEigenpairs(Eigen::MatrixXd lower, int count, Eigen::VectorXd* values,
                        Eigen::MatrixXd* vectors);

}  // namespace femup::internal
