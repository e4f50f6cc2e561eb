// Tikhonov regularisation, standard form (L = I) or general form (first or
// second differences over neighbouring unknowns of one group, or the problem's
// own operator), around the problem's prior: lambda chosen by the rule in
// options.regularisation (see regularisation.h). Fixed values and equalities
// are eliminated first; the answer carries the parameter-choice report (the
// L-curve and GCV function on a grid), the resolution matrix and the
// covariance of the regularised estimator.
#pragma once

#include "femup/solvers/linear_solver.h"

namespace femup {

class TikhonovSolver : public LinearSolver {
 public:
  explicit TikhonovSolver(const LinearSolverOptions& options) : options_(options) {}
  std::string name() const override { return "tikhonov"; }
  LinearSolution Solve(const LinearProblem& problem) const override;

 private:
  LinearSolverOptions options_;
};

}  // namespace femup
