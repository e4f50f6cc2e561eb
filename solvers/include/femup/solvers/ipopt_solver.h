// Nonlinear least squares on Ipopt (interior point): min 0.5 |r(x)|^2 with the
// bounds, fixed values (lower = upper) and linear equalities handled natively.
// The Hessian is the Gauss-Newton J'J (exact for linear residuals) or Ipopt's
// limited-memory quasi-Newton approximation (options.hessian). Bounds are not
// relaxed (Ipopt's default relaxes them by 1e-8). An interior-point answer stops
// a little inside its active bounds; it is finished by one more solve with those
// bounds held, and every bounded or constrained answer is checked by its KKT
// conditions, as with every backend.
//
// Ipopt's linear solver (MUMPS) is not thread-safe: solves are serialised within
// a process, so concurrent calls of Solve wait for each other.
#pragma once

#include <string>

#include "femup/solvers/nonlinear_solver.h"

namespace femup {

class IpoptSolver : public NonlinearSolver {
 public:
  explicit IpoptSolver(const NonlinearSolverOptions& options = {}) : options_(options) {}
  std::string name() const override { return "ipopt"; }
  // Throws InputError for invalid options or problem (before any work).
  // Ipopt's convergence tolerance `tol` is options.gradient_tolerance (at least
  // 1e-15) relative to |J'r|_inf at the start: the objective is scaled by it.
  // summary.iterations is Ipopt's iteration count.
  NonlinearSolution Solve(const NonlinearProblem& problem) const override;

 private:
  NonlinearSolverOptions options_;
};

}  // namespace femup
