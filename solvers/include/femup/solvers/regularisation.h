// Tikhonov regularisation in general form and the choice of its parameter:
//   min ||A x - b||^2 + lambda^2 ||L (x - x0)||^2
// (lambda in the convention of Hansen's Regularization Tools). The problem is
// brought to standard form once (A-weighted pseudo-inverse of L, Elden/Hansen)
// and one SVD then gives the residual norm, the solution semi-norm ||L (x - x0)||,
// the GCV function, the L-curve curvature and the quasi-optimality function as
// cheap functions of lambda. Each parameter-choice rule is refined off the grid
// (Brent's minimiser on log lambda, about 1e-7 relative in lambda; the discrepancy
// equation by TOMS 748 to near machine precision); when its optimum lies at an end of
// the search range it says so instead of returning the end point silently.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "femup/core/invalid.h"

namespace femup {

struct RegularisationOptions {
  // "gcv", "lcurve", "discrepancy", "quasi_optimality" or "fixed".
  std::string parameter_choice = "gcv";
  double lambda = 0;              // "fixed": lambda (tikhonov) ; tsvd uses `truncation`
  double noise_norm = 0;          // "discrepancy": ||e|| (in weighted units), > 0
  double discrepancy_factor = 1;  // "discrepancy": ||A x - b|| = factor * noise_norm
  // "identity", "first_difference", "second_difference" (over neighbouring
  // unknowns of one group) or "problem" (the problem's own regulariser).
  std::string op = "identity";
  int grid_points = 200;  // log-spaced grid for plots and bracketing
  double lambda_min = 0;  // search range; 0 = from the singular values
  double lambda_max = 0;
  Invalid Validate() const;  // ok when valid, else the field and what is wrong
};

// What a regularised solve reports (for JSON, tables and plots).
struct RegularisationReport {
  std::string parameter_choice;  // rule used
  double lambda = 0;             // chosen (tikhonov), or 0
  int truncation = 0;            // chosen k (tsvd), or 0
  bool at_range_end = false;     // the rule's optimum was an end of the range
  std::string note;              // why, when at_range_end or when a rule failed
  // The rules side by side (NaN when not applicable, e.g. discrepancy without a
  // noise level): the lambda each one picks.
  double lambda_lcurve = 0, lambda_gcv = 0, lambda_discrepancy = 0, lambda_quasi = 0;
  // The path on the grid.
  std::vector<double> grid_lambda, grid_residual_norm, grid_solution_norm, grid_gcv,
      grid_curvature, grid_quasi;
};

// One regularised problem in standard form. A (m x n), b (m), L (p x n; empty =
// identity), x0 (n; empty = zero).
class TikhonovPath {
 public:
  // `source_rows` and `residual_offset`: for a compressed problem (see
  // LinearProblem), the rows it stands for (GCV's degrees of freedom) and the
  // squared residual that no x changes; 0 and 0 for an ordinary one.
  TikhonovPath(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
               const Eigen::MatrixXd& l = Eigen::MatrixXd(),
               const Eigen::VectorXd& x0 = Eigen::VectorXd(), int source_rows = 0,
               double residual_offset = 0);

  Eigen::VectorXd Solve(double lambda) const;
  double ResidualNorm(double lambda) const;  // ||A x - b||
  double SolutionNorm(double lambda) const;  // ||L (x - x0)||
  double Gcv(double lambda) const;           // ||A x - b||^2 / (m - trace H)^2
  double Curvature(double lambda) const;     // of the L-curve in log-log scale
  double Quasi(double lambda) const;         // ||lambda dx/dlambda|| in standard form
  double EffectiveParameters(double lambda) const;  // trace of the influence matrix
  // The regularised inverse X (n x m, x - x0 = X (b - A x0)); resolution = X A.
  Eigen::MatrixXd Inverse(double lambda) const;

  const Eigen::VectorXd& singular_values() const {
    return sigma_;
  }  // of the standard form
  double DefaultLambdaMin() const;
  double DefaultLambdaMax() const;
  int num_rows() const { return m_; }
  int num_unknowns() const { return n_; }
  int null_space_dimension() const { return n_ - p_; }
  // Smallest residual any lambda can give (the part of b outside range(A)).
  double IncompatibleResidual() const { return delta0_; }

 private:
  int m_ = 0, n_ = 0, p_ = 0;
  int gcv_rows_ = 0;              // rows the data stand for (GCV)
  Eigen::VectorXd sigma_, beta_;  // standard-form singular values and U' b_bar
  Eigen::MatrixXd v_;             // standard-form right singular vectors (p x p')
  Eigen::MatrixXd l_pinv_a_;      // A-weighted pseudo-inverse of L (n x p)
  Eigen::MatrixXd x_null_map_;    // n x m: b -> null-space component of x
  Eigen::MatrixXd u_;             // m x p'
  Eigen::MatrixXd b_bar_map_;     // m x m projector I - P_{AW}
  Eigen::VectorXd x0_, b_, x_null_;
  Eigen::MatrixXd a_;
  double delta0_ = 0;
};

// Chooses lambda by `options.parameter_choice`, filling the report (grid, each
// rule's answer). Returns the chosen lambda.
double ChooseLambda(const TikhonovPath& path, const RegularisationOptions& options,
                    RegularisationReport* report);

}  // namespace femup
