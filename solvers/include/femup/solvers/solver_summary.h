// What every solver returns besides its answer: a status, not an exception.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace femup {

enum class SolverStatus {
  kSolved,         // converged to a unique solution (optimality checked where it applies)
  kMinimumNorm,    // rank deficient: the minimum-norm solution of the free unknowns
  kNoConvergence,  // an iterative solver stopped at its limit, or short of optimality
  kInfeasible,     // no x satisfies the bounds and equalities
  kFailed,         // the solver could not produce a solution (see message)
};
const char* ToString(SolverStatus status);  // "solved", "minimum_norm", ...

struct SolverSummary {
  SolverStatus status = SolverStatus::kFailed;
  std::string message;
  int iterations = 0;
  double cost = 0;  // 0.5 ||W (A x - b)||^2 (or 0.5 ||r(x)||^2) at the solution
  double time_seconds = 0;
  // Largest violation of the first-order optimality (KKT) conditions, relative
  // to the gradient scale; NaN when not checked.
  double kkt_residual = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> warnings;
  bool usable() const {
    return status == SolverStatus::kSolved || status == SolverStatus::kMinimumNorm;
  }
};

}  // namespace femup
