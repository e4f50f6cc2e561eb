// What every solver returns besides its answer: a status, not an exception.
#pragma once

#include <string>

namespace femup {

enum class SolverStatus {
  kSolved,         // a unique solution was found
  kMinimumNorm,    // rank deficient: the minimum-norm solution of the free unknowns
  kNoConvergence,  // an iterative solver stopped at its limit
  kFailed,         // the solver could not produce a solution (see message)
};
const char* ToString(SolverStatus status);  // "solved", "minimum_norm", ...

struct SolverSummary {
  SolverStatus status = SolverStatus::kFailed;
  std::string message;
  int iterations = 0;
  double cost = 0;  // 0.5 ||A x - b||^2 at the solution
  double time_seconds = 0;
  bool usable() const {
    return status == SolverStatus::kSolved || status == SolverStatus::kMinimumNorm;
  }
};

}  // namespace femup
