// Identifiability of a linear problem: singular values, numerical rank, and the
// directions the data cannot see, described in terms of named parameters.
#pragma once

#include <Eigen/Core>
#include <Eigen/SVD>
#include <string>
#include <vector>

namespace femup {

struct NullDirection {
  Eigen::VectorXd coefficients;  // unit vector over the analysed unknowns
  double singular_value = 0;     // of the column-scaled matrix
  // In words, e.g. "common scaling: all mass, stiffness and added_mass factors
  // move together (0.28 mass[1] + ...)".
  std::string description;
  bool common_scaling = false;  // every mass and stiffness unknown, one sign
  // The unknown with the largest component: fixing it to a known value
  // removes this direction best.
  std::string best_to_fix;
};

struct Identifiability {
  Eigen::VectorXd singular_values;  // of A with unit-norm columns, descending
  double tolerance = 0;             // absolute threshold applied to them
  int rank = 0;
  double condition_number = 0;                 // s_max / s_min (inf when rank < n)
  double condition_number_in_rank = 0;         // s_max / s_rank
  double condition_number_unscaled = 0;        // of A itself, before column scaling
  std::vector<NullDirection> null_directions;  // one per singular value below tolerance
  std::vector<std::string> unseen;             // unknowns whose column is exactly zero
  std::vector<std::string> warnings;
};

// Analyses A (m x n) with columns scaled to unit norm (or as it is, when
// `scale_columns` is false: then the rank decision depends on the units).
// `names`/`groups` (may be empty) label the columns; groups "mass" and "stiffness" are
// used to recognise the common scaling of K and M. `relative_tolerance` times the largest
// singular value is the rank threshold.
Identifiability AnalyseIdentifiability(const Eigen::MatrixXd& a,
                                       const std::vector<std::string>& names,
                                       const std::vector<std::string>& groups,
                                       double relative_tolerance,
                                       bool scale_columns = true);

// The column scaling of that analysis: the column norms of A (1 for a zero
// column), or ones when `scale_columns` is false.
Eigen::VectorXd IdentifiabilityScale(const Eigen::MatrixXd& a, bool scale_columns);

// The same analysis from the caller's SVD of A * diag(scale)^-1, scale =
// IdentifiabilityScale(a, scale_columns), for A with at least as many rows as
// columns (then a thin V is all of V): the least-squares solver factorises
// once for both. Throws InputError as above, and when `scaled_svd` does not
// hold V of A's column count.
Identifiability AnalyseIdentifiability(const Eigen::MatrixXd& a,
                                       const Eigen::BDCSVD<Eigen::MatrixXd>& scaled_svd,
                                       const std::vector<std::string>& names,
                                       const std::vector<std::string>& groups,
                                       double relative_tolerance,
                                       bool scale_columns = true);

// The same analysis from what it needs when the caller has it without a full
// SVD (lstsq's Gram route on a large compressed problem): the column-scaled
// matrix's singular values (descending, up to n), the right singular vectors
// of the smallest ones only (`trailing_vectors`, n x t, column j for singular
// value n - t + j), and A's own condition number before column scaling
// (>= 0; inf allowed). The vectors must cover every singular value at or below
// the rank threshold, and the smallest one when the matrix has full rank but a
// condition number above 1e8 (the weakest direction the warning names);
// otherwise, or on sizes that do not fit, InputError.
Identifiability AnalyseIdentifiability(
    const Eigen::MatrixXd& a, const Eigen::VectorXd& singular_values,
    const Eigen::MatrixXd& trailing_vectors, double condition_number_unscaled,
    const std::vector<std::string>& names, const std::vector<std::string>& groups,
    double relative_tolerance, bool scale_columns = true);

}  // namespace femup
