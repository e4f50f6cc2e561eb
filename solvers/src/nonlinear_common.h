// What the nonlinear backends (ceres_solver.cc, ipopt_solver.cc) and their
// linear adapters share: the input checks done before any work, a checked call
// of the model, the linearised covariance, and the KKT check that every bounded
// or constrained answer goes through whichever backend produced it. Private to
// the solvers library.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <string>

#include "femup/problems/nonlinear_problem.h"
#include "femup/solvers/nonlinear_solver.h"

namespace femup {
namespace nonlinear_internal {

// Throws InputError("solver.<field>", ...) when the options are invalid.
void ValidateOptions(const NonlinearSolverOptions& options);

// Throws InputError("nonlinear problem", ...) when the problem cannot be solved
// as given (see NonlinearProblem::Validate).
void ValidateProblem(const NonlinearProblem& problem);

// The problem's start with the fixed parameters at their values.
Eigen::VectorXd StartingPoint(const NonlinearProblem& problem);

// Calls problem.evaluate and checks the answer: the residual has
// num_residuals entries, the Jacobian (when asked for) is num_residuals x n, and
// both are finite. Returns false and says why otherwise (a failed evaluation is
// an outcome the solvers handle, not an exception).
bool Evaluate(const NonlinearProblem& problem, const Eigen::VectorXd& x,
              Eigen::VectorXd* residuals, Eigen::MatrixXd* jacobian, std::string* why);

// |J' r|_inf over the free parameters, or 1 when that is 0: the scale of the
// relative gradient tolerance and of the KKT check.
double GradientScale(const NonlinearProblem& problem, const Eigen::MatrixXd& jacobian,
                     const Eigen::VectorXd& residuals);

// Number of parameters the data estimate: free parameters less the rank of the
// equalities restricted to them. The residual variance has m minus this many
// degrees of freedom.
int EstimatedParameters(const NonlinearProblem& problem);

// Linearised covariance over all n parameters at (J, r): (J_f' J_f)^-1 s^2 on the
// free parameters, restricted to the null space of the equalities when there are
// any (N (N' J_f' J_f N)^-1 N'), zero rows and columns for fixed parameters.
// s^2 = |r|^2 / (m - EstimatedParameters) unless the residuals are whitened (then
// 1). Empty when J_f N is numerically rank deficient or no degree of freedom is
// left to estimate s^2.
Eigen::MatrixXd Covariance(const NonlinearProblem& problem, const Eigen::MatrixXd& jacobian,
                           const Eigen::VectorXd& residuals);

// Completes a solution whose x, summary.status, summary.message and
// summary.iterations the backend has set: evaluates r and J at x (kFailed when
// that fails), fills the cost, covariance and time since `start`, and, when the
// problem has bounds or equalities, checks the KKT conditions with the gradient
// J' r scaled by `gradient_scale` (from the start). A kSolved answer whose KKT
// residual exceeds options.kkt_tolerance becomes kNoConvergence ("stopped short
// of the bounded optimum").
void Finish(const NonlinearProblem& problem, const NonlinearSolverOptions& options,
            double gradient_scale, std::chrono::steady_clock::time_point start,
            NonlinearSolution* solution);

}  // namespace nonlinear_internal
}  // namespace femup
