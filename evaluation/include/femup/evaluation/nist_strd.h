// NIST Statistical Reference Datasets (StRD) for linear and nonlinear least
// squares (https://www.itl.nist.gov/div898/strd/), read from NIST's own .dat
// files and turned into femup problems, so solvers can be scored against NIST's
// certified values.
//
// Readers throw InputError("<path>:<line>", what was expected) for a file that is
// missing, truncated or malformed.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "femup/problems/linear_problem.h"
#include "femup/problems/nonlinear_problem.h"

namespace femup {

using LongDouble = long double;
using VectorLD = Eigen::Matrix<LongDouble, Eigen::Dynamic, 1>;
using MatrixLD = Eigen::Matrix<LongDouble, Eigen::Dynamic, Eigen::Dynamic>;

// One linear StRD set (Norris, Pontius, NoInt1/2, Filip, Longley, Wampler1-5).
// Numbers are parsed with strtold, so no digit of the file is lost.
struct NistLinearDataset {
  std::string name;        // "Filip"
  std::string path;        // the file it was read from
  std::string difficulty;  // "Lower", "Average" or "Higher"
  std::string model;       // the file's model formula, as text (documentation only)
  // Polynomial degree in the single predictor x (Norris 1, Pontius 2, Filip 10,
  // Wampler 5, NoInt 1), or 0 for Longley (y = B0 + B1 x1 + ... + B6 x6).
  int degree = 0;
  bool intercept = true;  // false for NoInt1 and NoInt2 (y = B1 x)
  MatrixLD predictors;    // observations x predictors (1 column, 6 for Longley)
  VectorLD response;      // observations
  VectorLD certified;     // certified parameter estimates, in the order B0, B1, ...
  VectorLD certified_sd;  // their certified standard deviations
  LongDouble residual_sd = 0;
  LongDouble r_squared = 0;
  std::vector<std::string> parameter_names;  // "B0", "B1", ... (or "B1" for NoInt)

  int num_observations() const { return static_cast<int>(response.size()); }
  int num_parameters() const { return static_cast<int>(certified.size()); }
  // The model's design matrix (observations x parameters, columns in the order
  // of `certified`): [1, x, x^2, ..., x^degree] (without the 1 when there is no
  // intercept), or [1, x1, ..., x6] for Longley. Powers are formed in long double
  // and then cast to Scalar.
  template <typename Scalar>
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> Design() const;
  // Double precision: A = Design<double>(), b = response, names = parameter_names.
  LinearProblem Problem() const;
};

NistLinearDataset ReadNistLinear(const std::string& path);

// One nonlinear StRD set (27 of them, Misra1a ... Bennett5).
struct NistNonlinearDataset {
  std::string name;        // "Misra1a"
  std::string path;        // the file it was read from
  std::string difficulty;  // "Lower", "Average" or "Higher"
  std::string model;       // the file's model formula, as text (documentation only)
  Eigen::MatrixXd x;       // observations x predictors (2 columns for Nelson)
  Eigen::VectorXd y;       // observations
  Eigen::MatrixXd starts;  // parameters x 2: start 1 and start 2
  Eigen::VectorXd certified, certified_sd;
  double certified_rss = 0;  // residual sum of squares at the certified values
  double residual_sd = 0;    // certified; sqrt(certified_rss / degrees_of_freedom)
  // Observations - parameters. (Rat43.dat states 9, a slip in NIST's file: its
  // certified residual standard deviation is sqrt(RSS / 11), and 15 - 4 = 11.)
  int degrees_of_freedom = 0;
  std::vector<std::string> parameter_names;  // "b1", "b2", ...
  // The same numbers as parsed, in long double (the double copies above round
  // the data at 1e-16, which matters for sets whose certified RSS is tiny).
  MatrixLD x_long;
  VectorLD y_long, certified_long;
  LongDouble certified_rss_long = 0;

  int num_observations() const { return static_cast<int>(y.size()); }
  int num_parameters() const { return static_cast<int>(certified.size()); }
};

NistNonlinearDataset ReadNistNonlinear(const std::string& path);

// The problem min 0.5 ||r(b)||^2 with residuals r_i = f(x_i; b) - y_i (model
// minus data, the sign of AsNonlinear's A x - b; for Nelson, whose model is
// log[y] = f, r_i = f(x_i; b) - log(y_i)) and the Jacobian dr/db from forward-mode
// automatic differentiation. `start` is 1 or 2 (NIST's two starting points).
// evaluate returns false, with a reason, when a residual or derivative is not
// finite or x does not have one entry per parameter. Throws InputError for an unknown
// dataset name (listing the known ones), a dataset whose parameter or predictor count
// does not fit the model, or a start other than 1 or 2.
NonlinearProblem NistNonlinearProblem(const NistNonlinearDataset& data, int start);

// The residuals above, evaluated in long double from the long double data, for
// validation at NIST's certified values. Throws as NistNonlinearProblem does.
VectorLD NistNonlinearResiduals(const NistNonlinearDataset& data, const VectorLD& b);

// The datasets with a model implemented (all 27 nonlinear StRD sets), sorted.
std::vector<std::string> NistNonlinearModelNames();

// Log relative error, the NIST / McCullough measure of correct significant digits:
// -log10(|value - certified| / |certified|), or -log10(|value|) when certified is
// 0. Clipped to [0, 15]: the certified values carry at most 15 significant digits,
// so agreement beyond 15 digits (including an exact match) counts as 15, and a
// value off by more than the certified magnitude counts as 0. A NaN or infinite
// value (or certified value) gives 0.
double LogRelativeError(double value, double certified);
double LogRelativeError(long double value, long double certified);

// ---------------------------------------------------------------------------

template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> NistLinearDataset::Design() const {
  const Eigen::Index n = response.size();
  const Eigen::Index k = certified.size();
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> design(n, k);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index j = 0;
    if (intercept && j < k) design(i, j++) = Scalar(1);
    if (degree == 0) {
      for (Eigen::Index c = 0; c < predictors.cols() && j < k; ++c) {
        design(i, j++) = static_cast<Scalar>(predictors(i, c));
      }
    } else {
      LongDouble power = 1;
      for (int d = 1; d <= degree && j < k; ++d) {
        power *= predictors(i, 0);
        design(i, j++) = static_cast<Scalar>(power);
      }
    }
  }
  return design;
}

}  // namespace femup
