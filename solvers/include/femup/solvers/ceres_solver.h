// Nonlinear least squares on Ceres Solver (trust region: Levenberg-Marquardt or
// dogleg, dense QR). Fixed parameters are held constant, bounds are Ceres's own
// box constraints, and linear equalities C x = d are enforced by an
// augmented-Lagrangian outer loop (see CeresSolver::Solve). Ceres can report
// convergence while stopped short of a bounded optimum (its projected steps
// stall once a bound clips them); such stalls are detected and re-solved with
// the bounds reached held, and every bounded or constrained answer is checked
// by its KKT conditions.
#pragma once

#include <string>

#include "femup/solvers/nonlinear_solver.h"

namespace femup {

class CeresSolver : public NonlinearSolver {
 public:
  explicit CeresSolver(const NonlinearSolverOptions& options = {}) : options_(options) {}
  std::string name() const override { return "ceres"; }
  // Throws InputError for invalid options or problem (before any work).
  //
  // Equalities: each outer iteration k minimises
  //   0.5 |r(x)|^2 + 0.5 rho_k |C x - d + mu_k / rho_k|^2
  // (the penalty rows are extra residuals), then updates mu_{k+1} = mu_k +
  // rho_k (C x - d) and multiplies rho by 10 when |C x - d|_inf fell by less than
  // a factor 4. It stops once |C x - d|_inf < options.equality_tolerance, or
  // after options.max_outer_iterations (kNoConvergence; kInfeasible when x is a
  // KKT point of min |C x - d|^2 within the bounds, i.e. no feasible x exists).
  // Bounds: a solve that stalls on bounds, or converges short of its KKT
  // conditions, is repeated with the bounds it reached (with multipliers of the
  // right sign) held constant.
  // summary.iterations counts the trust-region steps of all these solves; all
  // share options.max_iterations.
  NonlinearSolution Solve(const NonlinearProblem& problem) const override;

 private:
  NonlinearSolverOptions options_;
};

}  // namespace femup
