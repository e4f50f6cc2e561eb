// NonlinearProblem: find x minimising 0.5 ||r(x)||^2, with the residual vector
// r and its Jacobian given as a function of x, subject to optional fixed values,
// linear equalities C x = d and bounds. Every nonlinear solver takes this one
// type; a LinearProblem converts to it (r = W (A x - b)).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "femup/core/invalid.h"
#include "femup/problems/linear_problem.h"

namespace femup {

struct NonlinearProblem {
  // Fills `residuals` (always, resized by the callee) and `jacobian` (when not
  // null; num_residuals x num_parameters). Returns false when the model cannot be
  // evaluated at x (the solver then treats the step as unsuccessful); it may then
  // set *why. Must be safe to call repeatedly; need not be thread-safe.
  using Evaluate =
      std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd* residuals,
                         Eigen::MatrixXd* jacobian, std::string* why)>;

  int num_residuals = 0;
  Eigen::VectorXd initial;                    // n: the starting point
  std::vector<std::string> names;             // n, may be empty
  std::vector<std::string> groups;            // n, may be empty
  std::vector<std::string> residual_labels;   // may be empty
  std::vector<std::pair<int, double>> fixed;  // (index, value)
  Eigen::VectorXd lower, upper;               // n each, or empty
  Eigen::MatrixXd equality_matrix;            // q x n
  Eigen::VectorXd equality_rhs;               // q
  // Noise known: residuals are already divided by their standard deviations, so
  // the parameter covariance is (J' J)^-1 without a residual-variance estimate.
  bool residuals_whitened = false;
  Evaluate evaluate;

  int num_parameters() const { return static_cast<int>(initial.size()); }
  bool has_bounds() const;
  // Ok when consistent; otherwise what is wrong, with no field (sizes, NaN in
  // the start, lower > upper, a start or fixed value outside bounds, no
  // evaluate function). Does not call evaluate.
  Invalid Validate() const;
  std::vector<int> FreeUnknowns() const;
  bool IsFixed(int index) const;
};

// r(x) = W (A x - b) with the problem's weights, bounds, fixed values and
// equalities (the regulariser is not included). `start` (n or empty = zero,
// clipped into the bounds) is the starting point.
NonlinearProblem AsNonlinear(const LinearProblem& problem,
                             const Eigen::VectorXd& start = Eigen::VectorXd());

}  // namespace femup
