// Plain least squares by the singular value decomposition of the column-scaled
// matrix of the free unknowns: the unique solution when A has full column rank,
// otherwise the minimum-norm one (in scaled variables), with a warning that
// names the directions the data cannot determine. The answer is then refined
// twice on the augmented system [I A; A' 0] [r; x] = [b; 0] with its residuals in
// long double, which recovers the digits a plain solve loses on ill-conditioned
// problems with a large residual (docs/validation.md: NIST's Wampler4 and 5).
#pragma once

#include "femup/solvers/linear_solver.h"

namespace femup {

class LstsqSolver : public LinearSolver {
 public:
  explicit LstsqSolver(const LinearSolverOptions& options) : options_(options) {}
  std::string name() const override { return "lstsq"; }
  LinearSolution Solve(const LinearProblem& problem) const override;

 private:
  LinearSolverOptions options_;
};

}  // namespace femup
