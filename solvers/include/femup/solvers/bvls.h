// Bounded (and equality-constrained) linear least squares by a primal
// active-set method in the spirit of Stark & Parker's BVLS (Computational
// Statistics 10, 1995), generalised to linear equalities C x = d: every
// iteration solves the least-squares problem of the unknowns off their bounds
// within the null space of C, steps to the first bound it meets, and frees the
// bound whose multiplier has the wrong sign. It starts, as BVLS does, from the
// unconstrained least-squares answer clipped to the box, and a tall A is
// reduced once to the n x n factor R of A = Q R. With equalities a first phase
// finds a feasible point (bounded least squares on C x = d) or reports the
// problem infeasible. The answer is checked by its KKT conditions.
#pragma once

#include "femup/solvers/linear_solver.h"

namespace femup {

class BvlsSolver : public LinearSolver {
 public:
  explicit BvlsSolver(const LinearSolverOptions& options) : options_(options) {}
  std::string name() const override { return "bvls"; }
  LinearSolution Solve(const LinearProblem& problem) const override;

 private:
  LinearSolverOptions options_;
};

}  // namespace femup
