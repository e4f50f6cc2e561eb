// Dense kernels femup takes from the BLAS (femup/core/linalg/blas.h names
// which one) rather than from Eigen's own loops: Eigen is compiled for any
// x86-64 (SSE2), the BLAS picks kernels for the processor it runs on (a dense
// 1000 x 1000 product at 12.5 GFLOP/s by Eigen against 68 by OpenBLAS's
// AVX-512 kernels here; docs/benchmarks.md "The BLAS").
#pragma once

#include <Eigen/Core>
#include <vector>

namespace femup {

// The lower triangle of c = beta c + alpha a' a (BLAS dsyrk, "L", "T"):
// a is k x n, c is n x n (its strict upper triangle is not touched; with
// beta = 0 its lower triangle need not be set, as for the BLAS). Any
// stride Eigen::Ref allows for an inner stride of 1 (a block of a larger
// matrix). InputError (naming "c") when c is not n x n.
void RankUpdateLower(const Eigen::Ref<const Eigen::MatrixXd>& a, double alpha,
                     double beta, Eigen::Ref<Eigen::MatrixXd> c);

// x = L^-1 x for the lower triangular L held in l's lower triangle (BLAS
// dtrsm, "L", "L", "N", "N"; l's strict upper triangle is not read), x with
// l.rows() rows and any number of columns. InputError (naming "l" or "x") when
// l is not square or x's rows are not l's.
void SolveLowerInPlace(const Eigen::Ref<const Eigen::MatrixXd>& l,
                       Eigen::Ref<Eigen::MatrixXd> x);

// The Cholesky factor L (a = L L') in the lower triangle of a (LAPACK
// dpotrf, "L"; the strict upper triangle is not read nor written). False when
// a is not positive definite (a's lower triangle then holds a partial factor).
// InputError (naming "a") when a is not square.
bool CholeskyLower(Eigen::Ref<Eigen::MatrixXd> a);

// L^-1 in place of the lower triangular L held in a's lower triangle (LAPACK
// dtrtri, "L", "N"; the strict upper triangle is not touched). False when a
// diagonal entry is zero. InputError (naming "a") when a is not square.
bool InvertLowerTriangular(Eigen::Ref<Eigen::MatrixXd> a);

// Cholesky factorisation with complete (diagonal) pivoting of a symmetric
// positive semidefinite a (LAPACK dpstrf, "L"): P' a P = L L', P the
// permutation with P(pivots[k], k) = 1 (0-based), L lower triangular with
// rank columns. It stops when the largest remaining pivot is at or below
// `tolerance` (< 0: n eps times a's largest diagonal entry, LAPACK's
// default); rows and columns of a from `rank` on then hold no factor. L is left
// in a's lower triangle; its strict upper triangle is not touched. Returns the
// rank, or -1 when LAPACK reports an argument error or a is not finite.
// InputError (naming "a") when a is not square.
int PivotedCholeskyLower(Eigen::Ref<Eigen::MatrixXd> a, double tolerance,
                         std::vector<int>* pivots);

}  // namespace femup
