// What the nonlinear backends (ceres_solver.cc, ipopt_solver.cc) and their
// linear adapters share: the input checks done before any work, a checked call
// of the model, the linearised covariance, and one driver that runs a backend,
// checks every bounded or constrained answer by its KKT conditions whichever
// backend produced it, and polishes answers that stopped short. Private to the
// solvers library.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>

#include "femup/problems/nonlinear_problem.h"
#include "femup/solvers/nonlinear_solver.h"

namespace femup {
namespace nonlinear_internal {

// Throws InputError("solver.<field>", ...) when the options are invalid.
void ValidateOptions(const NonlinearSolverOptions& options);

// The problem's start with the fixed parameters at their values.
Eigen::VectorXd StartingPoint(const NonlinearProblem& problem);

// Calls problem.evaluate and checks the answer: the residual has
// num_residuals entries, the Jacobian (when asked for) is num_residuals x n, and
// both are finite. Returns false and says why otherwise (a failed evaluation is
// an outcome the solvers handle, not an exception).
bool Evaluate(const NonlinearProblem& problem, const Eigen::VectorXd& x,
              Eigen::VectorXd* residuals, Eigen::MatrixXd* jacobian, std::string* why);

// Number of parameters the data estimate: free parameters less the rank of the
// equalities restricted to them. The residual variance has m minus this many
// degrees of freedom.
int EstimatedParameters(const NonlinearProblem& problem);

// Linearised covariance over all n parameters at (J, r): (J_f' J_f)^-1 s^2 on the
// free parameters, restricted to the null space N of the equalities when there
// are any (N (N' J_f' J_f N)^-1 N'), zero rows and columns for fixed parameters.
// s^2 = |r|^2 / (m - EstimatedParameters) unless the residuals are whitened (then
// 1). Empty when J_f N is numerically rank deficient or no degree of freedom is
// left to estimate s^2.
Eigen::MatrixXd Covariance(const NonlinearProblem& problem,
                           const Eigen::MatrixXd& jacobian,
                           const Eigen::VectorXd& residuals);

// What one run of a backend returns.
struct BackendResult {
  Eigen::VectorXd x;  // n
  SolverStatus status = SolverStatus::kFailed;
  std::string message;
  int iterations = 0;
};

// One run of a backend on `problem` from StartingPoint(problem), within
// options.max_iterations. `gradient_scale` is |J'r|_inf at the user's start (so
// that tolerances are relative to it). The problem has been validated, and the
// driver may pass a copy with more fixed parameters (bounds held).
using Backend = std::function<BackendResult(const NonlinearProblem& problem,
                                            const NonlinearSolverOptions& options,
                                            double gradient_scale)>;

// Solves `problem` with `backend` (called `name` in messages):
//  - throws InputError for invalid options ("solver.<field>") or problem
//    ("nonlinear problem"), before any evaluation;
//  - kFailed without running the backend when the model cannot be evaluated at
//    the start;
//  - fills r, J, cost, covariance and time at the answer (kFailed when the model
//    cannot be evaluated there);
//  - without bounds or equalities, restarts (up to options.max_restarts times)
//    from an answer where the Jacobian in relative units (column j times |x_j|)
//    loses rank: a degenerate stationary point (a plateau where a term has
//    vanished, two terms merged) where the Gauss-Newton model is flat along some
//    direction though the cost may not be. The best of a few steps along that
//    direction that lowers the cost is the new start; the restart is kept when
//    it ends lower (NIST's BoxBOD from start 1 ends on such a plateau);
//  - when the problem has bounds or equalities, checks the KKT conditions with
//    the gradient J'r relative to |J'r|_inf at the start. A converged answer
//    that fails them, or that lies near but not on bounds it should be on, is
//    polished: those bounds are held (fixed at their values) and the rest
//    re-solved, while the held set changes (an active-set step). A bound is
//    one to hold when the reduced gradient pushes towards it and the
//    Gauss-Newton step along that parameter alone would reach it: Ceres's
//    projected steps stall short of bounded optima, Ipopt's interior iterates
//    stop a little inside active bounds. The polished answer is kept when it
//    is solved (or better than an unsolved one). An answer that still fails the
//    check becomes kNoConvergence ("stopped short of the bounded optimum: KKT
//    residual ...").
NonlinearSolution Solve(const std::string& name, const NonlinearProblem& problem,
                        const NonlinearSolverOptions& options, const Backend& backend);

}  // namespace nonlinear_internal
}  // namespace femup
