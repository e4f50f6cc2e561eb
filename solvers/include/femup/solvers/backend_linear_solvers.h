// Bounded linear least squares on the nonlinear backends: the LinearProblem is
// converted with AsNonlinear (r = W (A x - b); start at the prior, or zero,
// clipped into the bounds) and solved by Ceres or Ipopt with tight tolerances,
// so the same bounded and constrained problems can be cross-checked against
// other linear solvers. The regulariser is not used; identifiability is not
// analysed (left empty).
#pragma once

#include <string>

#include "femup/solvers/linear_solver.h"

namespace femup {

// The covariance is the linearised one of the nonlinear solution (fixed
// unknowns zero); with an active bound it ignores that bound, and a warning in
// summary.warnings says so. The interval is x +- t se (Student t with m minus
// the estimated unknowns as degrees of freedom when the noise is estimated,
// normal when it is known) at options.confidence_level.
class CeresLinearSolver : public LinearSolver {
 public:
  explicit CeresLinearSolver(const LinearSolverOptions& options = {})
      : options_(options) {}
  std::string name() const override { return "ceres"; }
  // Throws InputError("linear problem", ...) when the problem is unusable.
  LinearSolution Solve(const LinearProblem& problem) const override;

 private:
  LinearSolverOptions options_;
};

// As CeresLinearSolver, on Ipopt with the exact (Gauss-Newton) Hessian.
class IpoptLinearSolver : public LinearSolver {
 public:
  explicit IpoptLinearSolver(const LinearSolverOptions& options = {})
      : options_(options) {}
  std::string name() const override { return "ipopt"; }
  LinearSolution Solve(const LinearProblem& problem) const override;

 private:
  LinearSolverOptions options_;
};

}  // namespace femup
