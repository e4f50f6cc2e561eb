// Least squares in long double for small dense problems given in long double
// (the NIST StRD linear sets are read at long double): a reference to score the
// double-precision solvers against, not a LinearSolver (no weights, bounds,
// fixed values or uncertainty). Column-pivoted Householder QR of the
// column-scaled matrix, all in long double (a 64-bit mantissa on x86-64, so
// about 3 more digits than double; where long double is double it is no better).
#pragma once

#include <Eigen/Core>
#include <string>

#include "femup/core/invalid.h"

namespace femup {

// The same aliases as femup/evaluation/nist_strd.h.
using VectorLD = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
using MatrixLD = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

struct ExtendedPrecisionOptions {
  // Pivots |R_kk| at or below relative_rank_tolerance * |R_00| (of the
  // column-scaled matrix) count as zero; 0 = Eigen's default, min(m, n) times the
  // machine epsilon of long double.
  double relative_rank_tolerance = 0;
  // Scale the columns of A to unit norm before the decomposition (the answer is
  // mapped back), so the rank decision does not depend on the units.
  bool scale_columns = true;
  Invalid Validate() const;  // ok when valid, else the field and what is wrong
};

struct ExtendedPrecisionSolution {
  VectorLD x;         // n: the least-squares solution; when rank deficient the
                      // basic one (zero on the columns the pivoting left out)
  VectorLD residual;  // m: A x - b, in long double
  int rank = 0;       // numerical rank from the QR pivots
  // |R_00| / |R_kk| over the kept pivots of the (scaled) matrix: a cheap lower
  // estimate of its condition number.
  double pivot_ratio = 0;
  std::string message;  // "full column rank (n)" or "rank r of n: ..."
  bool rank_deficient() const { return rank < x.size(); }
};

// min ||A x - b|| for A (m x n, m, n >= 1) and b (m). Throws
// InputError("extended precision least squares", ...) for mismatched sizes, an
// empty A, a NaN or infinite entry, or invalid options (naming the field).
ExtendedPrecisionSolution ExtendedPrecisionLeastSquares(
    const MatrixLD& a, const VectorLD& b, const ExtendedPrecisionOptions& options = {});

}  // namespace femup
