#include "femup/solvers/linear_solver.h"

#include <cmath>
#include <sstream>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"
#include "femup/solvers/backend_linear_solvers.h"
#include "femup/solvers/bvls.h"
#include "femup/solvers/lstsq.h"
#include "femup/solvers/tikhonov.h"
#include "femup/solvers/tsvd.h"

namespace femup {

constexpr EnumName<SolverStatus> kSolverStatusNames[] = {
    {SolverStatus::kSolved, "solved"},
    {SolverStatus::kMinimumNorm, "minimum_norm"},
    {SolverStatus::kNoConvergence, "no_convergence"},
    {SolverStatus::kInfeasible, "infeasible"},
    {SolverStatus::kFailed, "failed"},
};

const char* ToString(SolverStatus status) {
  return NameIn(kSolverStatusNames, status, "failed");
}

Invalid LinearSolverOptions::Validate() const {
  std::ostringstream msg;
  if (!(relative_rank_tolerance > 0) || !(relative_rank_tolerance < 1) ||
      !std::isfinite(relative_rank_tolerance)) {
    msg << "must be in (0, 1), got " << relative_rank_tolerance;
    return {"rank_tolerance", msg.str()};
  }
  if (truncation < 0) {
    msg << "must be >= 0 (0 = chosen by the rule), got " << truncation;
    return {"truncation", msg.str()};
  }
  if (max_iterations < 1) {
    msg << "must be positive, got " << max_iterations;
    return {"max_iterations", msg.str()};
  }
  if (!(kkt_tolerance > 0) || !std::isfinite(kkt_tolerance)) {
    msg << "must be positive, got " << kkt_tolerance;
    return {"kkt_tolerance", msg.str()};
  }
  if (!(confidence_level > 0 && confidence_level < 1)) {
    msg << "must be in (0, 1), got " << confidence_level;
    return {"confidence_level", msg.str()};
  }
  if (gram_min_unknowns < 1) {
    msg << "must be >= 1, got " << gram_min_unknowns;
    return {"gram_min_unknowns", msg.str()};
  }
  return regularisation.Validate().Under("regularisation");
}

std::vector<std::string> AvailableLinearSolvers() {
  return {"lstsq", "tsvd", "tikhonov", "bvls", "ceres", "ipopt"};
}

std::unique_ptr<LinearSolver> CreateLinearSolver(const std::string& name,
                                                 const LinearSolverOptions& options) {
  ThrowIfInvalid(options.Validate(), "solver");
  if (name == "lstsq") return std::make_unique<LstsqSolver>(options);
  if (name == "tsvd") return std::make_unique<TsvdSolver>(options);
  if (name == "tikhonov") return std::make_unique<TikhonovSolver>(options);
  if (name == "bvls") return std::make_unique<BvlsSolver>(options);
  if (name == "ceres") return std::make_unique<CeresLinearSolver>(options);
  if (name == "ipopt") return std::make_unique<IpoptLinearSolver>(options);
  std::string known;
  for (const auto& n : AvailableLinearSolvers()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("solver.name",
                   "unknown solver '" + name + "' (available: " + known + ")");
}

}  // namespace femup
