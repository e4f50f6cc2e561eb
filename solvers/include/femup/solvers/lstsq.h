// Plain least squares by the singular value decomposition of the column-scaled
// matrix of the free unknowns: the unique solution when A has full column rank,
// otherwise the minimum-norm one (in scaled variables), with a warning that
// names the directions the data cannot determine.
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
