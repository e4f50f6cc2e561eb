#include "femup/solvers/nonlinear_solver.h"

#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "femup/core/errors.h"
#include "femup/solvers/ceres_solver.h"
#include "femup/solvers/ipopt_solver.h"
#include "femup/solvers/kkt.h"
#include "nonlinear_common.h"

namespace femup {

namespace {

// Singular values below this times the largest count as zero (covariance and
// the rank of the equalities).
constexpr double kRankTolerance = 1e-10;

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

// `field`: "must be ..., got <value>" when `ok` is false, else ok.
template <typename T>
Invalid Require(bool ok, const char* field, const char* requirement, T value) {
  if (ok) return {};
  std::ostringstream msg;
  msg << "must be " << requirement << ", got " << value;
  return {field, msg.str()};
}

Invalid OneOf(const std::string& value, const char* field,
              const std::vector<std::string>& allowed) {
  if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return {};
  return {field, "unknown value '" + value + "' (allowed: " + Join(allowed) + ")"};
}

// Orthonormal basis (columns) of the null space of `c`; the identity when `c` has
// no rows.
Eigen::MatrixXd NullSpace(const Eigen::MatrixXd& c) {
  const auto n = c.cols();
  if (c.rows() == 0) return Eigen::MatrixXd::Identity(n, n);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(c, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::Index rank = 0;
  while (rank < s.size() && s[rank] > kRankTolerance * s[0]) ++rank;
  return svd.matrixV().rightCols(n - rank);
}

// The equality matrix restricted to the free parameters (no rows when there
// are no equalities).
Eigen::MatrixXd FreeEqualities(const NonlinearProblem& problem,
                               const std::vector<int>& free) {
  Eigen::MatrixXd c(problem.equality_matrix.rows(), free.size());
  for (std::size_t k = 0; k < free.size() && c.rows() > 0; ++k) {
    c.col(k) = problem.equality_matrix.col(free[k]);
  }
  return c;
}

}  // namespace

Invalid NonlinearSolverOptions::Validate() const {
  const auto nonnegative = [](double v) { return std::isfinite(v) && v >= 0; };
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  for (const Invalid& error : {
           Require(max_iterations > 0, "max_iterations", "positive", max_iterations),
           Require(nonnegative(function_tolerance), "function_tolerance",
                   "finite and >= 0", function_tolerance),
           Require(nonnegative(gradient_tolerance), "gradient_tolerance",
                   "finite and >= 0", gradient_tolerance),
           Require(nonnegative(parameter_tolerance), "parameter_tolerance",
                   "finite and >= 0", parameter_tolerance),
           OneOf(trust_region, "trust_region", {"levenberg_marquardt", "dogleg"}),
           Require(positive(initial_trust_region), "initial_trust_region",
                   "finite and > 0", initial_trust_region),
           Require(max_restarts >= 0, "max_restarts", ">= 0", max_restarts),
           OneOf(hessian, "hessian", {"gauss_newton", "limited_memory"}),
           Require(positive(kkt_tolerance), "kkt_tolerance", "finite and > 0",
                   kkt_tolerance),
           Require(max_outer_iterations > 0, "max_outer_iterations", "positive",
                   max_outer_iterations),
           Require(positive(equality_tolerance), "equality_tolerance", "finite and > 0",
                   equality_tolerance),
       }) {
    if (error) return error;
  }
  return {};
}

std::vector<std::string> AvailableNonlinearSolvers() { return {"ceres", "ipopt"}; }

std::unique_ptr<NonlinearSolver> CreateNonlinearSolver(
    const std::string& name, const NonlinearSolverOptions& options) {
  const std::vector<std::string> available = AvailableNonlinearSolvers();
  if (std::find(available.begin(), available.end(), name) == available.end()) {
    throw InputError("solver.name", "unknown solver '" + name +
                                        "' (available: " + Join(available) + ")");
  }
  nonlinear_internal::ValidateOptions(options);
  if (name == "ceres") return std::make_unique<CeresSolver>(options);
  return std::make_unique<IpoptSolver>(options);
}

namespace nonlinear_internal {

namespace {

// How close to a bound (relative to max(1, |bound|)) counts as on it (CheckKkt's
// default), and how many times the polish may change the set of held bounds.
constexpr double kActiveTolerance = 1e-9;
constexpr int kMaxPolishRounds = 10;
// A polish may raise the cost by this relative amount at most (rounding, and a
// parameter moved the last fraction of the way onto its bound).
constexpr double kPolishCostSlack = 1e-8;
constexpr double kInf = std::numeric_limits<double>::infinity();

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// |J' r|_inf over the free parameters, or 1 when that is 0.
double GradientScale(const NonlinearProblem& problem, const Eigen::MatrixXd& jacobian,
                     const Eigen::VectorXd& residuals) {
  const Eigen::VectorXd g = jacobian.transpose() * residuals;
  double scale = 0;
  for (int i : problem.FreeUnknowns()) scale = std::max(scale, std::abs(g[i]));
  return scale > 0 ? scale : 1.0;
}

bool Constrained(const NonlinearProblem& problem) {
  return problem.has_bounds() || problem.equality_matrix.rows() > 0;
}

KktReport Kkt(const NonlinearProblem& problem, const NonlinearSolution& solution,
              double gradient_scale, double active_tolerance) {
  return CheckKkt(solution.x, solution.jacobian.transpose() * solution.residual,
                  problem.lower, problem.upper, problem.equality_matrix,
                  problem.equality_rhs, problem.fixed, gradient_scale, active_tolerance);
}

// Turns a backend's result into a solution of `problem`: r, J, cost and
// covariance at x, and the KKT check (a kSolved answer that fails it becomes
// kNoConvergence).
NonlinearSolution Complete(const NonlinearProblem& problem,
                           const NonlinearSolverOptions& options, double gradient_scale,
                           const BackendResult& result) {
  NonlinearSolution solution;
  SolverSummary& summary = solution.summary;
  solution.x = result.x;
  summary.status = result.status;
  summary.message = result.message;
  summary.iterations = result.iterations;
  std::string why;
  if (!Evaluate(problem, solution.x, &solution.residual, &solution.jacobian, &why)) {
    summary.status = SolverStatus::kFailed;
    summary.message += "; the model cannot be evaluated at the returned point: " + why;
    solution.residual.resize(0);
    solution.jacobian.resize(0, 0);
    return solution;
  }
  summary.cost = 0.5 * solution.residual.squaredNorm();
  solution.covariance = Covariance(problem, solution.jacobian, solution.residual);
  if (!Constrained(problem)) return solution;
  const KktReport kkt = Kkt(problem, solution, gradient_scale, kActiveTolerance);
  summary.kkt_residual = kkt.residual();
  if (summary.status == SolverStatus::kSolved &&
      !(kkt.residual() <= options.kkt_tolerance)) {
    std::ostringstream msg;
    msg << "stopped short of the bounded optimum: KKT residual " << kkt.residual()
        << " > kkt_tolerance " << options.kkt_tolerance << " (" << kkt.Describe()
        << "); the backend reported: " << summary.message;
    summary.status = SolverStatus::kNoConvergence;
    summary.message = msg.str();
  }
  return solution;
}

// The free parameters whose bound an optimal answer should be on, with that
// bound's value: those where the reduced gradient g_i = (J'r - C'mu)_i pushes
// towards the bound and the Gauss-Newton step along x_i alone, g_i / |J_i|^2,
// would reach it. Exactly on the bound this is "the multiplier has the right
// sign"; a little inside (an interior-point answer) it does not depend on the
// units of x_i.
std::vector<std::pair<int, double>> BoundsToHold(const NonlinearProblem& problem,
                                                 const NonlinearSolution& solution,
                                                 double gradient_scale) {
  const int n = problem.num_parameters();
  Eigen::VectorXd g = solution.jacobian.transpose() * solution.residual;
  if (problem.equality_matrix.rows() > 0) {
    g -= problem.equality_matrix.transpose() *
         Kkt(problem, solution, gradient_scale, kActiveTolerance).equality_multipliers;
  }
  const Eigen::VectorXd curvature = solution.jacobian.colwise().squaredNorm();
  std::vector<std::pair<int, double>> held;
  for (int i : problem.FreeUnknowns()) {
    // Where the step along x_i alone would take it (unbounded when the residuals
    // do not depend on x_i).
    const double target = curvature[i] > 0 ? solution.x[i] - g[i] / curvature[i]
                                           : (g[i] > 0 ? -kInf : kInf);
    if (problem.lower.size() == n && g[i] > 0 && target <= problem.lower[i]) {
      held.emplace_back(i, problem.lower[i]);
    } else if (problem.upper.size() == n && g[i] < 0 && target >= problem.upper[i]) {
      held.emplace_back(i, problem.upper[i]);
    }
  }
  return held;
}

// A stationary point where the Jacobian of the free parameters, in relative
// units (column j times |x_j|), has a singular value below this times the
// largest is degenerate (see EscapeDegeneratePoint).
constexpr double kDegenerateRatio = 1e-8;
// Steps tried along the degenerate direction, as a fraction of each parameter's
// magnitude, and the relative decrease of the cost that makes one worth taking.
constexpr double kEscapeSteps[] = {1e-3,  -1e-3, 1e-2, -1e-2, 1e-1,
                                   -1e-1, 0.5,   -0.5, 0.9,   -0.9};
constexpr double kEscapeDecrease = 1e-9;
// Cost changes below this times the cost at the user's start are rounding (on a
// zero-residual problem the cost at the answer is itself rounding).
constexpr double kCostNoise = 1e-12;
// A step escapes only when the cost falls by more than this times what the
// Gauss-Newton model 0.5 |r + J dx|^2 predicts: otherwise it only continues the
// solve the backend ended (on a linear problem the two are the same).
constexpr double kBeyondGaussNewton = 2;

// Where to restart from when `solution` is a degenerate stationary point of an
// unconstrained problem: the model does not depend on some combination of the
// parameters there (a plateau where a term has vanished, or two terms merged),
// so the Gauss-Newton model both backends use is flat along it and neither
// leaves; the cost itself may still fall along it (the curvature J'J leaves
// out). Tries steps along that direction and returns false unless one lowers
// the cost by kEscapeDecrease relative (and above the rounding of
// `initial_cost`, the cost at the user's start) and by more than the
// Gauss-Newton model predicts (kBeyondGaussNewton).
bool EscapeDegeneratePoint(const NonlinearProblem& problem,
                           const NonlinearSolution& solution, double initial_cost,
                           Eigen::VectorXd* start) {
  const std::vector<int> free = problem.FreeUnknowns();
  const auto m = solution.jacobian.rows();
  if (free.empty() || m == 0) return false;
  // Relative units; a parameter at zero is scaled by its column's norm instead.
  Eigen::VectorXd unit(free.size());
  Eigen::MatrixXd j(m, free.size());
  for (std::size_t k = 0; k < free.size(); ++k) {
    const double x = std::abs(solution.x[free[k]]);
    const double norm = solution.jacobian.col(free[k]).norm();
    unit[k] = x > 0 ? x : (norm > 0 ? 1 / norm : 1.0);
    j.col(k) = solution.jacobian.col(free[k]) * unit[k];
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  const auto last = static_cast<Eigen::Index>(free.size()) - 1;
  // With fewer residuals than parameters the last singular values are zero.
  const double smallest = last < s.size() ? s[last] : 0.0;
  if (!(s.size() > 0 && s[0] > 0 && smallest < kDegenerateRatio * s[0])) return false;
  const Eigen::VectorXd direction = unit.cwiseProduct(svd.matrixV().col(last));
  Eigen::VectorXd change = Eigen::VectorXd::Zero(solution.x.size());
  for (std::size_t k = 0; k < free.size(); ++k) change[free[k]] = direction[k];
  const Eigen::VectorXd slope = solution.jacobian * change;  // J along the step
  const double cost0 = solution.summary.cost;
  double best = cost0 - std::max(kEscapeDecrease * cost0, kCostNoise * initial_cost);
  bool found = false;
  Eigen::VectorXd r;
  std::string why;
  for (double t : kEscapeSteps) {
    const Eigen::VectorXd x = solution.x + t * change;
    if (!Evaluate(problem, x, &r, nullptr, &why)) continue;
    const double cost = 0.5 * r.squaredNorm();
    const double modelled = 0.5 * (solution.residual + t * slope).squaredNorm();
    if (cost < best && cost0 - cost > kBeyondGaussNewton * (cost0 - modelled)) {
      best = cost;
      *start = x;
      found = true;
    }
  }
  return found;
}

}  // namespace

void ValidateOptions(const NonlinearSolverOptions& options) {
  ThrowIfInvalid(options.Validate(), "solver");
}

Eigen::VectorXd StartingPoint(const NonlinearProblem& problem) {
  Eigen::VectorXd x = problem.initial;
  for (const auto& [i, v] : problem.fixed) x[i] = v;
  return x;
}

bool Evaluate(const NonlinearProblem& problem, const Eigen::VectorXd& x,
              Eigen::VectorXd* residuals, Eigen::MatrixXd* jacobian, std::string* why) {
  std::string reason;
  if (!problem.evaluate(x, residuals, jacobian, &reason)) {
    *why = reason.empty() ? "evaluate returned false" : reason;
    return false;
  }
  std::ostringstream msg;
  if (residuals->size() != problem.num_residuals) {
    msg << "evaluate returned " << residuals->size() << " residuals, expected "
        << problem.num_residuals;
  } else if (jacobian != nullptr && (jacobian->rows() != problem.num_residuals ||
                                     jacobian->cols() != problem.num_parameters())) {
    msg << "evaluate returned a " << jacobian->rows() << " x " << jacobian->cols()
        << " Jacobian, expected " << problem.num_residuals << " x "
        << problem.num_parameters();
  } else if (!residuals->allFinite()) {
    msg << "evaluate returned a NaN or infinite residual";
  } else if (jacobian != nullptr && !jacobian->allFinite()) {
    msg << "evaluate returned a NaN or infinite Jacobian entry";
  } else {
    return true;
  }
  *why = msg.str();
  return false;
}

int EstimatedParameters(const NonlinearProblem& problem) {
  return static_cast<int>(
      NullSpace(FreeEqualities(problem, problem.FreeUnknowns())).cols());
}

Eigen::MatrixXd Covariance(const NonlinearProblem& problem,
                           const Eigen::MatrixXd& jacobian,
                           const Eigen::VectorXd& residuals) {
  const int n = problem.num_parameters();
  const std::vector<int> free = problem.FreeUnknowns();
  Eigen::MatrixXd jf(jacobian.rows(), free.size());
  for (std::size_t k = 0; k < free.size(); ++k) jf.col(k) = jacobian.col(free[k]);
  const Eigen::MatrixXd basis = NullSpace(FreeEqualities(problem, free));
  const auto dof = jacobian.rows() - basis.cols();
  if (basis.cols() == 0 || (!problem.residuals_whitened && dof <= 0)) {
    return Eigen::MatrixXd();
  }
  // (J N)' (J N) = V S^2 V', so N ((J N)' (J N))^-1 N' = (N V S^-1)(N V S^-1)'.
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jf * basis, Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  if (s.size() < basis.cols() || !(s[s.size() - 1] > kRankTolerance * s[0])) {
    return Eigen::MatrixXd();
  }
  const Eigen::MatrixXd factor = basis * svd.matrixV() * s.cwiseInverse().asDiagonal();
  const double variance = problem.residuals_whitened
                              ? 1.0
                              : residuals.squaredNorm() / static_cast<double>(dof);
  const Eigen::MatrixXd free_covariance = variance * factor * factor.transpose();
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t a = 0; a < free.size(); ++a) {
    for (std::size_t b = 0; b < free.size(); ++b) {
      covariance(free[a], free[b]) = free_covariance(a, b);
    }
  }
  return covariance;
}

NonlinearSolution Solve(const std::string& name, const NonlinearProblem& problem,
                        const NonlinearSolverOptions& options, const Backend& backend) {
  ValidateOptions(options);
  if (const Invalid bad = problem.Validate())
    throw InputError("nonlinear problem", bad.ToString());
  const auto start = std::chrono::steady_clock::now();

  Eigen::VectorXd r0;
  Eigen::MatrixXd j0;
  std::string why;
  if (!Evaluate(problem, StartingPoint(problem), &r0, &j0, &why)) {
    NonlinearSolution solution;
    solution.x = StartingPoint(problem);
    solution.summary.status = SolverStatus::kFailed;
    solution.summary.message =
        name + ": the model cannot be evaluated at the start: " + why;
    solution.summary.time_seconds = Seconds(start);
    return solution;
  }
  const double scale = GradientScale(problem, j0, r0);
  const BackendResult first = backend(problem, options, scale);
  NonlinearSolution solution = Complete(problem, options, scale, first);

  // Restart off degenerate stationary points (unconstrained problems only: the
  // escape step does not respect bounds or equalities), keeping a restart only
  // when it ends lower.
  for (int restart = 1; restart <= options.max_restarts && !Constrained(problem) &&
                        solution.summary.status != SolverStatus::kFailed &&
                        solution.summary.iterations < options.max_iterations;
       ++restart) {
    NonlinearProblem moved = problem;
    if (!EscapeDegeneratePoint(problem, solution, 0.5 * r0.squaredNorm(),
                               &moved.initial)) {
      break;
    }
    NonlinearSolverOptions remaining = options;
    remaining.max_iterations = options.max_iterations - solution.summary.iterations;
    BackendResult result = backend(moved, remaining, scale);
    std::ostringstream msg;
    msg << solution.summary.message << "; the Jacobian lost rank there (a degenerate "
        << "stationary point): restarted from a lower point along that direction ("
        << restart << "): " << result.message;
    result.message = msg.str();
    result.iterations += solution.summary.iterations;
    NonlinearSolution next = Complete(problem, options, scale, result);
    if (next.summary.status == SolverStatus::kFailed ||
        !(next.summary.cost < solution.summary.cost)) {
      break;
    }
    solution = std::move(next);
  }

  // Polish a converged answer (see the header): hold the bounds it should be on
  // and re-solve the rest, while that is needed (it stopped short, or some of
  // those bounds are not met exactly) and the held set changes.
  std::vector<std::vector<std::pair<int, double>>> tried;
  const auto num_free = problem.FreeUnknowns().size();
  for (int round = 1;
       round <= kMaxPolishRounds && first.status == SolverStatus::kSolved &&
       Constrained(problem) && solution.summary.iterations < options.max_iterations;
       ++round) {
    const auto held = BoundsToHold(problem, solution, scale);
    const bool off_bound = std::any_of(held.begin(), held.end(), [&](const auto& h) {
      return solution.x[h.first] != h.second;
    });
    if (held.empty() || (solution.summary.usable() && !off_bound) ||
        std::find(tried.begin(), tried.end(), held) != tried.end()) {
      break;
    }
    tried.push_back(held);
    NonlinearProblem reduced = problem;
    reduced.initial = solution.x;
    reduced.fixed.insert(reduced.fixed.end(), held.begin(), held.end());
    BackendResult result;
    if (held.size() == num_free) {
      result = {StartingPoint(reduced), SolverStatus::kSolved,
                "every free parameter is on a bound", 0};
    } else {
      NonlinearSolverOptions remaining = options;
      remaining.max_iterations = options.max_iterations - solution.summary.iterations;
      result = backend(reduced, remaining, scale);
    }
    std::ostringstream msg;
    msg << first.message << "; then " << held.size()
        << " bound(s) held where it stopped and the rest re-solved (polish round "
        << round << "): " << result.message;
    result.message = msg.str();
    result.iterations += solution.summary.iterations;
    NonlinearSolution polished = Complete(problem, options, scale, result);
    // Keep a solved polish; otherwise only an improvement of an unsolved answer.
    // Either way never a higher cost: the bounds to hold come from a diagonal
    // Newton step, which on a nonlinear model can put a bound far from where
    // x stopped, and snapping x there can raise the cost (an attached mass's
    // radius of gyration sent to its upper bound raised one fit's misfit by
    // 44 %).
    const bool no_higher =
        polished.summary.cost <= solution.summary.cost * (1 + kPolishCostSlack) +
                                     kCostNoise * 0.5 * r0.squaredNorm();
    const bool better =
        no_higher && (polished.summary.status == SolverStatus::kSolved ||
                      (!solution.summary.usable() &&
                       polished.summary.status != SolverStatus::kFailed &&
                       polished.summary.kkt_residual < solution.summary.kkt_residual));
    if (!better) break;
    solution = std::move(polished);
  }
  solution.summary.time_seconds = Seconds(start);
  return solution;
}

}  // namespace nonlinear_internal
}  // namespace femup
