#include "femup/solvers/linear_solver.h"

#include <cmath>

#include "femup/errors.h"
#include "femup/solvers/lstsq.h"

namespace femup {

const char* ToString(SolverStatus status) {
  switch (status) {
    case SolverStatus::kSolved:
      return "solved";
    case SolverStatus::kMinimumNorm:
      return "minimum_norm";
    case SolverStatus::kNoConvergence:
      return "no_convergence";
    case SolverStatus::kFailed:
      return "failed";
  }
  return "failed";
}

std::string LinearSolverOptions::Validate() const {
  if (!(relative_rank_tolerance > 0) || !(relative_rank_tolerance < 1) ||
      !std::isfinite(relative_rank_tolerance)) {
    return "rank_tolerance must be in (0, 1)";
  }
  return "";
}

std::vector<std::string> AvailableLinearSolvers() { return {"lstsq"}; }

std::unique_ptr<LinearSolver> CreateLinearSolver(const std::string& name,
                                                 const LinearSolverOptions& options) {
  const std::string invalid = options.Validate();
  if (!invalid.empty()) throw InputError("solver.rank_tolerance", invalid);
  if (name == "lstsq") return std::make_unique<LstsqSolver>(options);
  std::string known;
  for (const auto& n : AvailableLinearSolvers()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("solver.name",
                   "unknown solver '" + name + "' (available: " + known + ")");
}

}  // namespace femup
