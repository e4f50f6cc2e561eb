// LinearProblem: find x with A x ~= b, in the weighted least-squares sense,
// subject to optional fixed values, linear equalities C x = d and bounds
// lower <= x <= upper; optionally regularised by ||L (x - prior)||. Every linear
// solver takes this one type; each uses the parts that apply to it.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "femup/core/invalid.h"

namespace femup {

struct LinearProblem {
  Eigen::MatrixXd A;                // m x n
  Eigen::VectorXd b;                // m
  std::vector<std::string> names;   // n unknown names ("mass[3]")
  std::vector<std::string> groups;  // n group names ("mass", "stiffness"); may be empty
  std::vector<std::string> row_labels;        // m, may be empty
  std::vector<std::pair<int, double>> fixed;  // (unknown index, known value)

  // Data noise. `row_weights` (m, positive) multiplies row i of A and b; or
  // `data_covariance` (m x m, symmetric positive definite) is the covariance of b,
  // and rows are whitened by its Cholesky factor. At most one of the two. When
  // either is given the noise is taken as known: parameter covariance is
  // (A' W A)^-1; otherwise it is estimated from the residual.
  Eigen::VectorXd row_weights;
  Eigen::MatrixXd data_covariance;

  // Bounds (n each; empty = none; -inf / +inf allowed per entry).
  Eigen::VectorXd lower;
  Eigen::VectorXd upper;

  // Linear equalities C x = d (q x n and q). Fixed values are kept apart above.
  Eigen::MatrixXd equality_matrix;
  Eigen::VectorXd equality_rhs;

  // Regularisation operator L (p x n; empty = identity) and prior x0 (n; empty =
  // zero), used by regularising solvers: min ||A x - b||^2 + lambda^2 ||L (x - x0)||^2.
  Eigen::MatrixXd regulariser;
  Eigen::VectorXd prior;

  // A compressed problem (e.g. normal_correction_system.h): A and b stand for a
  // larger system of `source_rows` rows whose squared residual norm is
  // ||A x - b||^2 + residual_offset for every x. Degrees of freedom, noise
  // estimates and parameter-choice rules use these. 0 and 0: an ordinary problem.
  int source_rows = 0;
  double residual_offset = 0;

  int num_rows() const { return static_cast<int>(A.rows()); }
  // Rows of the data the problem stands for (source_rows, or A's rows).
  int data_rows() const { return source_rows > 0 ? source_rows : num_rows(); }
  int num_unknowns() const { return static_cast<int>(A.cols()); }
  bool has_bounds() const;  // any finite bound on a free unknown
  bool has_equalities() const { return equality_matrix.rows() > 0; }
  bool noise_known() const {
    return row_weights.size() > 0 || data_covariance.size() > 0;
  }
  // Ok when consistent; otherwise what is wrong, with no field (sizes, NaN, a
  // fixed index out of range or listed twice, lower > upper, a fixed value
  // outside its bounds, a covariance that is not positive definite, equalities
  // that no x satisfies).
  Invalid Validate() const;
  // Fixes the unknown called `name` at `value`; throws InputError when no
  // unknown has that name.
  void Fix(const std::string& name, double value);
  std::vector<int> FreeUnknowns() const;  // indices not fixed, ascending
  bool IsFixed(int index) const;
  int IndexOf(const std::string& name) const;  // -1 when no unknown has that name
};

// The weighted system W A, W b (W = diag(row_weights), or the inverse Cholesky
// factor of data_covariance, or I).
struct WeightedSystem {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
};
WeightedSystem Weighted(const LinearProblem& problem);

// First- or second-difference operator over n unknowns ((n-1) x n or (n-2) x n).
// With `groups` (n labels), differences are taken only between consecutive
// unknowns of the same group (neighbouring elements of one parameter family).
// order 0 gives the identity.
Eigen::MatrixXd DifferenceOperator(int n, int order,
                                   const std::vector<std::string>& groups = {});

}  // namespace femup
