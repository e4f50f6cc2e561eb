// Truncated SVD: the least-squares solution from the k largest singular
// triplets of the (weighted, reduced) matrix, k given or chosen by GCV, the
// discrepancy principle, the discrete L-curve corner or quasi-optimality.
// Columns are not scaled (the classical definition, comparable with
// Regularization Tools' tsvd).
#pragma once

#include "femup/solvers/linear_solver.h"

namespace femup {

class TsvdSolver : public LinearSolver {
 public:
  explicit TsvdSolver(const LinearSolverOptions& options) : options_(options) {}
  std::string name() const override { return "tsvd"; }
  LinearSolution Solve(const LinearProblem& problem) const override;

 private:
  LinearSolverOptions options_;
};

}  // namespace femup
