// Nonlinear least-squares solvers: one interface, one factory ("ceres",
// "ipopt"). A solver takes a NonlinearProblem and returns a NonlinearSolution
// whose summary carries the outcome; only unusable input throws InputError,
// before any work. Bounded and constrained answers are checked by their KKT
// conditions whichever backend produced them.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/invalid.h"
#include "femup/problems/nonlinear_problem.h"
#include "femup/solvers/solver_summary.h"

namespace femup {

struct NonlinearSolverOptions {
  int max_iterations = 500;
  double function_tolerance = 1e-14;   // relative change of the cost
  double gradient_tolerance = 1e-14;   // relative size of the projected gradient
  double parameter_tolerance = 1e-14;  // relative size of the step
  // Ceres: "levenberg_marquardt" or "dogleg". Ipopt: ignored.
  std::string trust_region = "levenberg_marquardt";
  // Ceres: the first trust-region radius. The default makes the first step
  // Gauss-Newton, exact for linear residuals (Ceres's own default, 1e4, damps it,
  // and Ceres then stops with linear problems only ~1e-8 accurate). Far from the
  // optimum of a nonlinear problem a full Gauss-Newton step can land in a region
  // it does not return from; 1e4 is safer there (docs/validation.md). Ipopt:
  // ignored.
  double initial_trust_region = 1e10;
  // Restarts off a degenerate stationary point (problems without bounds or
  // equalities; see Solve in nonlinear_common.h); 0 = none.
  int max_restarts = 3;
  // Ipopt: "gauss_newton" (J'J, exact for linear residuals) or "limited_memory".
  std::string hessian = "gauss_newton";
  // A bounded/constrained answer whose KKT residual exceeds this is reported as
  // kNoConvergence ("stopped short of the optimum"), whatever the backend said.
  double kkt_tolerance = 1e-6;
  // Ceres with linear equalities: augmented-Lagrangian outer iterations.
  int max_outer_iterations = 50;
  double equality_tolerance = 1e-10;
  bool verbose = false;
  Invalid Validate() const;  // ok when valid, else the field and what is wrong
};

struct NonlinearSolution {
  Eigen::VectorXd x;         // every parameter, fixed ones at their values
  Eigen::VectorXd residual;  // r(x)
  Eigen::MatrixXd jacobian;  // J(x)
  // Linearised parameter covariance over all parameters (rows/columns of fixed
  // ones are zero): (J'J)^-1 scaled by the residual variance unless the problem's
  // residuals are whitened; empty when J'J of the free parameters is singular.
  Eigen::MatrixXd covariance;
  SolverSummary summary;
};

class NonlinearSolver {
 public:
  virtual ~NonlinearSolver() = default;
  virtual std::string name() const = 0;
  virtual NonlinearSolution Solve(const NonlinearProblem& problem) const = 0;
};

std::vector<std::string> AvailableNonlinearSolvers();  // {"ceres", "ipopt"}
// Throws InputError("solver.name", ...) for an unknown name and
// InputError("solver.<field>", ...) for invalid options.
std::unique_ptr<NonlinearSolver> CreateNonlinearSolver(
    const std::string& name, const NonlinearSolverOptions& options = {});

}  // namespace femup
