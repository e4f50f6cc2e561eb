#include "femup/solvers/backend_linear_solvers.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "femup/errors.h"
#include "femup/problems/nonlinear_problem.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/solvers/uncertainty.h"
#include "nonlinear_common.h"

namespace femup {

namespace {

// How close to a bound (relative to max(1, |bound|)) counts as on it, as in
// CheckKkt.
constexpr double kActiveTolerance = 1e-9;

// Names of the free unknowns that lie on one of their bounds.
std::vector<std::string> OnBounds(const LinearProblem& problem,
                                  const Eigen::VectorXd& x) {
  std::vector<std::string> out;
  const int n = problem.num_unknowns();
  const auto on = [n](double value, const Eigen::VectorXd& bounds, int i) {
    return bounds.size() == n && std::isfinite(bounds[i]) &&
           std::abs(value - bounds[i]) <=
               kActiveTolerance * std::max(1.0, std::abs(bounds[i]));
  };
  for (int i : problem.FreeUnknowns()) {
    if (on(x[i], problem.lower, i) || on(x[i], problem.upper, i)) {
      out.push_back(problem.names.size() == static_cast<std::size_t>(n)
                        ? problem.names[i]
                        : "unknown " + std::to_string(i));
    }
  }
  return out;
}

// Solves `problem` on the nonlinear backend called `backend` and reports it as
// a linear solution.
LinearSolution SolveOnBackend(const std::string& backend,
                              const LinearSolverOptions& options,
                              const LinearProblem& problem) {
  const std::string invalid = problem.Validate();
  if (!invalid.empty()) throw InputError("linear problem", invalid);
  if (!(options.confidence_level > 0 && options.confidence_level < 1)) {
    std::ostringstream msg;
    msg << "must be in (0, 1), got " << options.confidence_level;
    throw InputError("solver.confidence_level", msg.str());
  }
  const NonlinearProblem nonlinear = AsNonlinear(problem, problem.prior);
  NonlinearSolverOptions nonlinear_options;  // tight tolerances by default
  nonlinear_options.max_iterations = options.max_iterations;
  nonlinear_options.kkt_tolerance = options.kkt_tolerance;
  const NonlinearSolution answer =
      CreateNonlinearSolver(backend, nonlinear_options)->Solve(nonlinear);

  LinearSolution solution;
  solution.x = answer.x;
  solution.residual = problem.A * answer.x - problem.b;
  solution.summary = answer.summary;
  solution.confidence_level = options.confidence_level;
  solution.noise_estimated = !problem.noise_known();
  solution.covariance = answer.covariance;
  if (solution.covariance.size() == 0) return solution;

  // Student t on the residual's degrees of freedom when the noise is estimated.
  SetIntervals(
      solution.noise_estimated
          ? problem.num_rows() - nonlinear_internal::EstimatedParameters(nonlinear)
          : 0.0,
      &solution);
  const std::vector<std::string> on_bounds = OnBounds(problem, solution.x);
  if (!on_bounds.empty()) {
    std::string list;
    for (const auto& name : on_bounds) list += (list.empty() ? "" : ", ") + name;
    solution.summary.warnings.push_back(
        "the covariance is linearised at the solution and ignores the active bounds "
        "on " +
        list + ": the intervals may reach past them");
  }
  return solution;
}

}  // namespace

LinearSolution CeresLinearSolver::Solve(const LinearProblem& problem) const {
  return SolveOnBackend("ceres", options_, problem);
}

LinearSolution IpoptLinearSolver::Solve(const LinearProblem& problem) const {
  return SolveOnBackend("ipopt", options_, problem);
}

}  // namespace femup
