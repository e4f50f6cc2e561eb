// Eigenpairs of dense symmetric matrices and of small symmetric-definite
// pencils by LAPACK: dsyevr (MRRR) for a matrix; dpotrf, dsygst, dsyevr and
// dtrsm for a pencil K x = lambda M x. Each reduces to tridiagonal form once
// (4/3 n^3 flops, blocked dsytrd); the values then cost O(n^2) and each vector
// asked for O(n^2) plus its back-transformation, where a full decomposition
// (Eigen's SelfAdjointEigenSolver: implicit QR accumulating every vector) adds
// about 6 n^3. The modal analysis of small models (modal.h) and the
// identifiability report of the dense least-squares solvers use them.
#pragma once

#include <Eigen/Core>

namespace femup {

// Eigenvalues of the symmetric matrix whose lower triangle `lower` holds
// (n x n; the upper triangle is not read), ascending. False when LAPACK
// reports a failure (info != 0).
bool SymmetricEigenvalues(Eigen::MatrixXd lower, Eigen::VectorXd* values);

// The `count` smallest eigenvalues (ascending) and their orthonormal
// eigenvectors (n x count, column i for values[i]). 0 <= count <= n.
bool SmallestEigenpairs(Eigen::MatrixXd lower, int count, Eigen::VectorXd* values,
                        Eigen::MatrixXd* vectors);

enum class PencilStatus {
  kOk,
  kMassNotPositiveDefinite,  // M's Cholesky factorisation failed
  kFailed,                   // a size out of range, or LAPACK reported a failure
};

// The `count` smallest eigenvalues (ascending) of K x = lambda M x, K
// symmetric and M symmetric positive definite (their lower triangles are read,
// n x n), and their eigenvectors, M-orthonormal (x' M x = 1; n x count, column
// i for values[i]). 0 <= count <= n.
PencilStatus SmallestPencilEigenpairs(Eigen::MatrixXd stiffness, Eigen::MatrixXd mass,
                                      int count, Eigen::VectorXd* values,
                                      Eigen::MatrixXd* vectors);

}  // namespace femup
