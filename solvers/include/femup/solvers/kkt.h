// First-order optimality (KKT) conditions of
//   min f(x)  s.t.  C x = d,  lower <= x <= upper,  x_i = v_i (fixed)
// checked at a point from the gradient g = grad f(x). Used to verify every
// bounded or constrained answer, whichever backend produced it.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace femup {

struct KktReport {
  double stationarity = 0;            // largest |g - C' mu - z| on free unknowns, / scale
  double sign = 0;                    // largest wrong-sign bound multiplier, / scale
  double feasibility = 0;             // largest bound or equality violation (absolute)
  Eigen::VectorXd bound_multipliers;  // n: > 0 at an active lower bound, < 0 at upper
  Eigen::VectorXd equality_multipliers;  // q
  std::vector<int> active_lower, active_upper;
  double residual() const;  // max(stationarity, sign, feasibility)
  std::string Describe() const;
};

// `scale` normalises the gradient terms (for least squares: a typical size of
// |A' W b| or of |J' r| at the start; values <= 0 mean 1). `active_tolerance` is how
// close to a bound (relative to max(1, |bound|)) counts as on it.
KktReport CheckKkt(const Eigen::VectorXd& x, const Eigen::VectorXd& gradient,
                   const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                   const Eigen::MatrixXd& equality_matrix,
                   const Eigen::VectorXd& equality_rhs,
                   const std::vector<std::pair<int, double>>& fixed, double scale,
                   double active_tolerance = 1e-9);

}  // namespace femup
