// Shared by the linear solvers (private): the problem reduced to its free
// coordinates, and the uncertainty of a linear estimator.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <string>
#include <vector>

#include "femup/problems/linear_problem.h"
#include "femup/solvers/linear_solver.h"

namespace femup::internal {

// x = particular + basis z: fixed values substituted, linear equalities
// eliminated exactly (basis = orthonormal null space of C on the free unknowns).
// A and b are weighted (rows whitened) and expressed in z.
struct ReducedProblem {
  Eigen::MatrixXd A;           // m x k
  Eigen::VectorXd b;           // m: W b - W A particular
  Eigen::MatrixXd basis;       // n x k
  Eigen::VectorXd particular;  // n
  bool has_equalities = false;
  std::vector<int> free;  // free unknowns (not fixed)
  // Labels of z: the free unknowns' names and groups without equalities,
  // "combination[k]" with them.
  std::vector<std::string> names, groups;
  WeightedSystem weighted;            // the full weighted system (n columns)
  std::vector<std::string> warnings;  // e.g. bounds the solver cannot take
  Eigen::MatrixXd ToX(const Eigen::VectorXd& z) const;
  // basis * m for a k-row matrix m: without equalities the basis selects the
  // free unknowns, so m's rows are placed (no product; n^3 flops saved at
  // n = k = 1000).
  Eigen::MatrixXd Lift(const Eigen::MatrixXd& m) const;
};

// Validates (InputError "linear problem" before any work) and reduces. Bounds
// are dropped: `solver` (its name) cannot take them, and a warning says so.
ReducedProblem Reduce(const LinearProblem& problem, const std::string& solver);

// Covariance, standard errors and intervals of an estimator x = particular + X b_w
// (X: n x m; only X X' is used, so any X with the same X X' will do),
// `parameters_used` the degrees of freedom the fit consumed (rank or trace of
// the influence matrix). Noise variance from the weighted residual unless the
// problem states its noise.
void FillUncertainty(const LinearProblem& problem, const Eigen::MatrixXd& x_map,
                     const Eigen::VectorXd& weighted_residual, double parameters_used,
                     double confidence_level, LinearSolution* solution);

// The answer x = particular + basis z of the estimate z: x, its residual
// A x - b, the cost 0.5 ||weighted residual||^2 and one iteration. Returns the
// weighted residual (for FillUncertainty).
Eigen::VectorXd SetAnswer(const LinearProblem& problem, const ReducedProblem& reduced,
                          const Eigen::VectorXd& z, LinearSolution* solution);

// The end of a regularised solve (TSVD, Tikhonov): status solved, `message`,
// the parameter choice's note and the reduction's warnings, the time taken.
void FinishRegularised(const std::string& message, const ReducedProblem& reduced,
                       double seconds, LinearSolution* solution);

class Stopwatch {
 public:
  double Seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_)
        .count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace femup::internal
