#include "femup/solvers/backend_linear_solvers.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/problems/nonlinear_problem.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/solvers/uncertainty.h"
#include "linear_common.h"
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

// Fewer estimated correct digits than this: the answer is not "solved".
constexpr double kMinimumDigits = 4.0;
// Fewer than this: a warning.
constexpr double kWarningDigits = 8.0;

// The backends stop on first-order tolerances, which on an ill-conditioned
// problem can leave the answer far from the exact minimiser while they report
// convergence (Ceres on NIST Wampler5 kept 1 digit, Ipopt on Filip none). This
// checks the answer by the data, on the unknowns that are free and off their
// bounds: a rank-deficient system is reported with the directions it cannot
// see, and the distance to the exact minimiser (one least-squares correction
// from a column-scaled SVD) is turned into correct digits. Too few digits make
// the answer "no_convergence".
void CheckAgainstExactMinimiser(const LinearProblem& problem,
                                const LinearSolverOptions& options,
                                const std::string& backend, LinearSolution* solution) {
  if (solution->x.size() != problem.num_unknowns() || !solution->x.allFinite()) return;
  const internal::ReducedProblem reduced = internal::Reduce(problem, backend);
  const Eigen::VectorXd z =
      reduced.basis.transpose() * (solution->x - reduced.particular);
  // Without equalities z are the free unknowns: leave out those on a bound.
  // With equalities z mixes them, so active bounds make the check inapplicable.
  const std::vector<std::string> on_bounds = OnBounds(problem, solution->x);
  if (reduced.has_equalities && !on_bounds.empty()) return;
  std::vector<int> inactive;
  for (Eigen::Index k = 0; k < z.size(); ++k) {
    if (!reduced.has_equalities && !reduced.names.empty() &&
        std::find(on_bounds.begin(), on_bounds.end(), reduced.names[k]) !=
            on_bounds.end()) {
      continue;
    }
    inactive.push_back(static_cast<int>(k));
  }
  if (inactive.empty() || reduced.A.rows() == 0) return;
  const Eigen::MatrixXd a = reduced.A(Eigen::all, inactive);
  // Column scaling and rank rule as AnalyseIdentifiability's, on one SVD that
  // also gives the correction.
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(a.cols());
  if (options.scale_columns) {
    for (Eigen::Index j = 0; j < a.cols(); ++j) {
      const double norm = a.col(j).norm();
      if (norm > 0) scale[j] = 1.0 / norm;
    }
  }
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(a * scale.asDiagonal(),
                                           Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sv = svd.singularValues();
  int rank = 0;
  for (Eigen::Index i = 0; i < sv.size(); ++i) {
    if (sv[i] > options.relative_rank_tolerance * sv[0]) ++rank;
  }
  if (rank < static_cast<int>(inactive.size())) {
    std::vector<std::string> names, groups;
    for (int k : inactive) {
      if (k < static_cast<int>(reduced.names.size())) names.push_back(reduced.names[k]);
      if (k < static_cast<int>(reduced.groups.size()))
        groups.push_back(reduced.groups[k]);
    }
    const Identifiability id = AnalyseIdentifiability(
        a, names, groups, options.relative_rank_tolerance, options.scale_columns);
    std::ostringstream msg;
    msg << "rank deficient (rank " << id.rank << " of " << inactive.size()
        << " unknowns): the data do not determine";
    for (std::size_t i = 0; i < id.null_directions.size(); ++i) {
      msg << (i == 0 ? " " : "; ") << id.null_directions[i].description;
    }
    msg << ". This answer is one of many minimisers (where " << backend
        << " stopped from its start), not the minimum-norm one: fix "
        << (id.null_directions.empty() ? std::string("an unknown")
                                       : id.null_directions[0].best_to_fix)
        << " or add an equality, or use lstsq for the minimum-norm answer";
    solution->summary.warnings.push_back(msg.str());
    return;
  }
  // One exact least-squares correction on the inactive unknowns.
  const Eigen::VectorXd r = reduced.b - reduced.A * z;
  const Eigen::VectorXd step = scale.asDiagonal() * svd.solve(r);
  // Largest relative change of an unknown, in column-scaled units (z_k ||a_k||,
  // what each unknown contributes to the fit); unknowns contributing less than
  // kNegligible of the largest are judged against that floor, so that a factor
  // near zero does not count as wrong for a tiny absolute change.
  constexpr double kNegligible = 1e-3;
  double worst = 0;
  Eigen::VectorXd w(step.size());
  for (Eigen::Index k = 0; k < step.size(); ++k) w[k] = z[inactive[k]] / scale[k];
  const double floor = std::max(kNegligible * w.cwiseAbs().maxCoeff(), 1e-300);
  for (Eigen::Index k = 0; k < step.size(); ++k) {
    worst =
        std::max(worst, std::abs(step[k] / scale[k]) / std::max(std::abs(w[k]), floor));
  }
  if (!std::isfinite(worst)) return;
  const double digits = worst > 0 ? -std::log10(worst) : 16.0;
  if (digits >= kWarningDigits) return;
  std::ostringstream msg;
  msg << std::fixed << std::setprecision(1) << backend
      << " stopped short of the exact least-squares minimiser: about "
      << std::max(digits, 0.0) << " correct digits (largest relative change "
      << std::scientific << std::setprecision(1) << worst
      << " of an unknown under one exact correction; column-scaled condition number "
      << sv[0] / sv[sv.size() - 1] << "). Use lstsq for ill-conditioned unconstrained "
      << "problems, or bvls with bounds";
  if (digits < kMinimumDigits && solution->summary.usable()) {
    solution->summary.status = SolverStatus::kNoConvergence;
    solution->summary.message = msg.str();
  } else {
    solution->summary.warnings.push_back(msg.str());
  }
}

// Solves `problem` on the nonlinear backend called `backend` and reports it as
// a linear solution.
LinearSolution SolveOnBackend(const std::string& backend,
                              const LinearSolverOptions& options,
                              const LinearProblem& problem) {
  if (const Invalid bad = problem.Validate())
    throw InputError("linear problem", bad.ToString());
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
  CheckAgainstExactMinimiser(problem, options, backend, &solution);
  solution.confidence_level = options.confidence_level;
  solution.noise_estimated = !problem.noise_known();
  solution.covariance = answer.covariance;
  if (solution.covariance.size() == 0) return solution;

  // Student t on the residual's degrees of freedom when the noise is estimated.
  SetIntervals(
      solution.noise_estimated
          ? problem.data_rows() - nonlinear_internal::EstimatedParameters(nonlinear)
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
