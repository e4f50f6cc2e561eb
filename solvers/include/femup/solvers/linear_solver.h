// Linear solvers: one interface, one factory. A solver takes a LinearProblem
// and returns a LinearSolution whose summary carries the outcome; only unusable
// input (sizes, NaN, unknown names) throws InputError, before any work.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "femup/problems/linear_problem.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/solver_summary.h"

namespace femup {

struct LinearSolverOptions {
  // Singular values below relative_rank_tolerance * s_max (of the column-scaled
  // matrix) count as zero.
  double relative_rank_tolerance = 1e-10;
  // Scale the columns of A to unit norm before the decomposition (the answer is
  // mapped back). Keeps the rank decision independent of parameter units.
  bool scale_columns = true;
  std::string Validate() const;  // empty when valid, else names the field
};

struct LinearSolution {
  Eigen::VectorXd x;                // every unknown, fixed ones at their values
  Eigen::VectorXd residual;         // A x - b
  Identifiability identifiability;  // of the free-unknown system that was solved
  SolverSummary summary;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  virtual LinearSolution Solve(const LinearProblem& problem) const = 0;
};

// Names the factory knows ("lstsq").
std::vector<std::string> AvailableLinearSolvers();
// Throws InputError("solver.name", ...) for an unknown name and
// InputError("solver.<field>", ...) for invalid options.
std::unique_ptr<LinearSolver> CreateLinearSolver(const std::string& name,
                                                 const LinearSolverOptions& options = {});

}  // namespace femup
