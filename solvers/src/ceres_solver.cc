#include "femup/solvers/ceres_solver.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "femup/solvers/kkt.h"
#include "nonlinear_common.h"

namespace femup {

namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// First penalty of the augmented Lagrangian, relative to |J|_F^2 / |C|_F^2 at the
// start, and how far it may grow: large enough for a few outer iterations to
// reach a tight equality tolerance, small enough to keep the QR well conditioned.
constexpr double kInitialPenalty = 1e3;
constexpr double kMaxPenaltyGrowth = 1e8;
// Most re-solves with stalled bounds held between two multiplier updates.
constexpr int kMaxHolds = 20;
// A solve has stalled on a bound when this many successful steps in a row
// achieved less than this fraction of the decrease the model predicted (so the
// trust region shrank each time) while x sat on a bound. Ceres keeps iterates
// in the box by projecting the unconstrained step, with a projected line search
// that upstream calls "incorrect and not terribly effective" (ceres-solver
// issue 187): once a bound clips the step, the steps shrink towards a point
// short of the optimum and Ceres reports convergence there.
constexpr int kStallSteps = 3;
constexpr double kStallRatio = 0.5;
// A converged solve is re-run with its bounds held while its KKT residual
// exceeds this (or options.kkt_tolerance if smaller): holding costs a few
// iterations, and on an ill-conditioned problem a KKT residual just under
// kkt_tolerance can still leave x far from the optimum.
constexpr double kStallKktTolerance = 1e-10;
// A solve stuck on a bound that its gradient pulls it off is restarted with that
// parameter moved inside by this fraction of its range (doubled each time), at
// most kMaxNudges times.
constexpr double kNudge = 1e-3;
constexpr int kMaxNudges = 10;
constexpr double kInf = std::numeric_limits<double>::infinity();

// r(x) of the problem as one Ceres cost on the single parameter block x (n).
class ModelCost final : public ceres::CostFunction {
 public:
  // `last_failure` receives why an evaluation failed (the last one wins).
  ModelCost(const NonlinearProblem& problem, std::string* last_failure)
      : problem_(problem), last_failure_(last_failure) {
    set_num_residuals(problem.num_residuals);
    mutable_parameter_block_sizes()->push_back(problem.num_parameters());
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int m = problem_.num_residuals, n = problem_.num_parameters();
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(parameters[0], n);
    const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    Eigen::VectorXd r;
    Eigen::MatrixXd j;
    if (!nonlinear_internal::Evaluate(problem_, x, &r, want_jacobian ? &j : nullptr,
                                      last_failure_)) {
      return false;
    }
    Eigen::Map<Eigen::VectorXd>(residuals, m) = r;
    if (want_jacobian) Eigen::Map<RowMajorMatrix>(jacobians[0], m, n) = j;
    return true;
  }

 private:
  const NonlinearProblem& problem_;
  std::string* last_failure_;
};

// The augmented-Lagrangian rows sqrt(rho) (C x - d + mu / rho); rho and mu are
// owned by the caller and updated between solves.
class EqualityPenalty final : public ceres::CostFunction {
 public:
  EqualityPenalty(const Eigen::MatrixXd& c, const Eigen::VectorXd& d, const double* rho,
                  const Eigen::VectorXd* mu)
      : c_(c), d_(d), rho_(rho), mu_(mu) {
    set_num_residuals(static_cast<int>(c.rows()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(c.cols()));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const auto q = c_.rows(), n = c_.cols();
    const double root = std::sqrt(*rho_);
    const Eigen::Map<const Eigen::VectorXd> x(parameters[0], n);
    Eigen::Map<Eigen::VectorXd>(residuals, q) = root * (c_ * x - d_ + *mu_ / *rho_);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<RowMajorMatrix>(jacobians[0], q, n) = root * c_;
    }
    return true;
  }

 private:
  const Eigen::MatrixXd& c_;
  const Eigen::VectorXd& d_;
  const double* rho_;
  const Eigen::VectorXd* mu_;
};

// Ends a Ceres solve that has stalled on a bound that is not held (see
// kStallSteps), so that the bounds can be held and the rest re-solved. Reads x
// from the parameter block, which needs
// Solver::Options::update_state_every_iteration.
class StallDetector final : public ceres::IterationCallback {
 public:
  // `held`: the parameters currently held on their bounds (ascending).
  StallDetector(const NonlinearProblem& problem, const double* x,
                const std::vector<int>* held)
      : problem_(problem), x_(x), held_(held) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    const bool poor = summary.iteration > 0 && summary.step_is_successful &&
                      summary.relative_decrease < kStallRatio;
    poor_steps_ = poor && OnBound() ? poor_steps_ + 1 : 0;
    return poor_steps_ >= kStallSteps ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                                      : ceres::SOLVER_CONTINUE;
  }

 private:
  bool OnBound() const {
    const int n = problem_.num_parameters();
    for (int i : problem_.FreeUnknowns()) {
      if (std::binary_search(held_->begin(), held_->end(), i)) continue;
      if ((problem_.lower.size() == n && x_[i] == problem_.lower[i]) ||
          (problem_.upper.size() == n && x_[i] == problem_.upper[i])) {
        return true;
      }
    }
    return false;
  }

  const NonlinearProblem& problem_;
  const double* x_;
  const std::vector<int>* held_;
  int poor_steps_ = 0;
};

SolverStatus FromCeres(ceres::TerminationType type) {
  switch (type) {
    case ceres::CONVERGENCE:
    case ceres::USER_SUCCESS:  // only StallDetector ends a solve this way
      return SolverStatus::kSolved;
    case ceres::NO_CONVERGENCE:
      return SolverStatus::kNoConvergence;
    default:  // FAILURE, USER_FAILURE
      return SolverStatus::kFailed;
  }
}

// The free parameters on a bound whose multiplier has the right sign, and
// whether the point fails the KKT conditions (to kStallKktTolerance) of the
// pass's problem, min 0.5 |r|^2 + the augmented-Lagrangian penalty within the
// bounds. The signs are those of the original problem (equality multipliers by
// least squares): the penalised gradient carries rho (C x - d), which is large
// and of any sign while the penalty is large and C x - d not yet converged.
// Also the free parameters on a bound whose multiplier has the wrong sign: the
// gradient pulls them inside, yet Ceres's projected steps can stay stuck there.
struct Stall {
  std::vector<int> on_bounds;  // ascending
  // (parameter, +1 to step off its lower bound / -1 off its upper bound)
  std::vector<std::pair<int, double>> leaving;
  bool short_of_optimum = false;
};
Stall CheckStall(const NonlinearProblem& problem, const NonlinearSolverOptions& options,
                 double gradient_scale, const Eigen::VectorXd& x,
                 const Eigen::VectorXd& mu, double rho) {
  Stall stall;
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  std::string why;
  if (!nonlinear_internal::Evaluate(problem, x, &r, &j, &why)) return stall;
  const Eigen::VectorXd g = j.transpose() * r;
  const KktReport original =
      CheckKkt(x, g, problem.lower, problem.upper, problem.equality_matrix,
               problem.equality_rhs, problem.fixed, gradient_scale);
  for (int i : original.active_lower) {
    if (original.bound_multipliers[i] >= 0) {
      stall.on_bounds.push_back(i);
    } else {
      stall.leaving.emplace_back(i, 1.0);
    }
  }
  for (int i : original.active_upper) {
    if (original.bound_multipliers[i] <= 0) {
      stall.on_bounds.push_back(i);
    } else {
      stall.leaving.emplace_back(i, -1.0);
    }
  }
  std::sort(stall.on_bounds.begin(), stall.on_bounds.end());
  Eigen::VectorXd penalised = g;
  if (mu.size() > 0) {
    penalised += problem.equality_matrix.transpose() *
                 (mu + rho * (problem.equality_matrix * x - problem.equality_rhs));
  }
  const KktReport pass =
      CheckKkt(x, penalised, problem.lower, problem.upper, Eigen::MatrixXd(),
               Eigen::VectorXd(), problem.fixed, gradient_scale);
  stall.short_of_optimum =
      !(pass.residual() <= std::min(options.kkt_tolerance, kStallKktTolerance));
  return stall;
}

// One run of Ceres; see CeresSolver::Solve.
nonlinear_internal::BackendResult RunCeres(const NonlinearProblem& problem,
                                           const NonlinearSolverOptions& options,
                                           double gradient_scale) {
  const int n = problem.num_parameters();
  const auto q = problem.equality_matrix.rows();
  const Eigen::MatrixXd& c = problem.equality_matrix;
  const Eigen::VectorXd& d = problem.equality_rhs;
  nonlinear_internal::BackendResult result;
  Eigen::VectorXd& x = result.x;  // Ceres works on x in place
  x = nonlinear_internal::StartingPoint(problem);

  Eigen::VectorXd mu = Eigen::VectorXd::Zero(q);
  double rho = kInitialPenalty;
  if (q > 0) {
    Eigen::VectorXd r;
    Eigen::MatrixXd j;
    std::string why;
    const double jacobian_size =
        nonlinear_internal::Evaluate(problem, x, &r, &j, &why) ? j.squaredNorm() : 0.0;
    if (jacobian_size > 0 && c.squaredNorm() > 0) rho *= jacobian_size / c.squaredNorm();
  }
  const double max_rho = rho * kMaxPenaltyGrowth;

  std::string last_failure;
  ceres::Problem ceres_problem;  // owns the cost functions and the manifolds
  ceres_problem.AddResidualBlock(new ModelCost(problem, &last_failure), nullptr,
                                 x.data());
  if (q > 0) {
    ceres_problem.AddResidualBlock(new EqualityPenalty(c, d, &rho, &mu), nullptr,
                                   x.data());
  }
  std::vector<int> fixed;
  for (const auto& f : problem.fixed) fixed.push_back(f.first);
  // Holds the fixed parameters and `on_bounds` constant.
  const auto hold = [&](const std::vector<int>& on_bounds) {
    std::vector<int> constant = fixed;
    constant.insert(constant.end(), on_bounds.begin(), on_bounds.end());
    ceres_problem.SetManifold(
        x.data(), constant.empty() ? nullptr : new ceres::SubsetManifold(n, constant));
  };
  hold({});
  for (int i : problem.FreeUnknowns()) {
    if (problem.lower.size() == n && std::isfinite(problem.lower[i])) {
      ceres_problem.SetParameterLowerBound(x.data(), i, problem.lower[i]);
    }
    if (problem.upper.size() == n && std::isfinite(problem.upper[i])) {
      ceres_problem.SetParameterUpperBound(x.data(), i, problem.upper[i]);
    }
  }

  ceres::Solver::Options ceres_options;
  ceres_options.linear_solver_type = ceres::DENSE_QR;
  ceres_options.trust_region_strategy_type =
      options.trust_region == "dogleg" ? ceres::DOGLEG : ceres::LEVENBERG_MARQUARDT;
  // The default (see NonlinearSolverOptions) is nearly undamped: Ceres's own
  // first region (1e4) damps the first Levenberg-Marquardt steps by 1e-4
  // relative, and Ceres stops once the cost no longer changes in floating
  // point, which leaves x only ~1e-8 accurate on a linear problem. Failed steps
  // shrink the region as usual.
  ceres_options.initial_trust_region_radius = options.initial_trust_region;
  ceres_options.function_tolerance = options.function_tolerance;
  // Ceres's gradient tolerance is absolute; ours is relative to the start.
  ceres_options.gradient_tolerance = options.gradient_tolerance * gradient_scale;
  ceres_options.parameter_tolerance = options.parameter_tolerance;
  ceres_options.logging_type =
      options.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  ceres_options.minimizer_progress_to_stdout = options.verbose;
  std::vector<int> held;  // free parameters held on their bounds, ascending
  StallDetector stall_detector(problem, x.data(), &held);
  if (problem.has_bounds()) {
    ceres_options.update_state_every_iteration = true;
    ceres_options.callbacks.push_back(&stall_detector);
  }

  // Each pass solves with the current penalty. A converged pass that stopped
  // short of the (penalised) optimum on some bounds is repeated with those bounds
  // held; otherwise, with equalities, the multipliers are updated.
  ceres::Solver::Summary summary;
  SolverStatus status = SolverStatus::kFailed;
  std::string stop;  // why the last pass that produced x ended
  std::string late_failure;
  double violation = 0;
  int outer = 0, holds = 0, holds_this_pass = 0, nudges = 0;
  while (true) {
    const Eigen::VectorXd before = x;
    ceres_options.max_num_iterations = options.max_iterations - result.iterations;
    ceres::Solve(ceres_options, &ceres_problem, &summary);
    // summary.iterations starts with the evaluation at the start point.
    result.iterations += std::max(0, static_cast<int>(summary.iterations.size()) - 1);
    const SolverStatus pass = FromCeres(summary.termination_type);
    if (pass == SolverStatus::kFailed && status == SolverStatus::kSolved) {
      // A numerical failure after a converged pass (with a large penalty, Ceres
      // can end on "consecutive invalid steps"): x is the last accepted point,
      // judged below like the converged one.
      late_failure = summary.message;
      break;
    }
    status = pass;
    stop = summary.termination_type == ceres::USER_SUCCESS ? "stalled on a bound"
                                                           : summary.message;
    if (status != SolverStatus::kSolved) break;
    if (problem.has_bounds() && holds_this_pass < kMaxHolds &&
        result.iterations < options.max_iterations) {
      if (q > 0 && !held.empty() && x == before) {
        // The held bounds leave the equalities no room to improve: release
        // them and let the multipliers move.
        held.clear();
        hold(held);
      } else {
        const Stall stall = CheckStall(problem, options, gradient_scale, x, mu, rho);
        if (stall.short_of_optimum && stall.on_bounds != held) {
          held = stall.on_bounds;
          hold(held);
          ++holds;
          ++holds_this_pass;
          continue;
        }
        if (stall.short_of_optimum && !stall.leaving.empty() && nudges < kMaxNudges) {
          // Stuck on bounds the gradient pulls it off: step those parameters
          // inside by kNudge of their range (of max(1, |x|) for a one-sided
          // bound), twice as far at each further time, and go on from there.
          for (const auto& [i, direction] : stall.leaving) {
            const double lo = problem.lower.size() == n ? problem.lower[i] : -kInf;
            const double hi = problem.upper.size() == n ? problem.upper[i] : kInf;
            const double range =
                std::isfinite(hi - lo) ? hi - lo : std::max(1.0, std::abs(x[i]));
            x[i] =
                std::clamp(x[i] + direction * std::ldexp(kNudge, nudges) * range, lo, hi);
          }
          ++nudges;
          ++holds_this_pass;
          continue;
        }
      }
    }
    ++outer;
    holds_this_pass = 0;
    if (q == 0) break;
    const Eigen::VectorXd gap = c * x - d;
    const double previous = violation;
    violation = gap.cwiseAbs().maxCoeff();
    if (violation < options.equality_tolerance || outer >= options.max_outer_iterations ||
        result.iterations >= options.max_iterations) {
      break;
    }
    mu += rho * gap;
    if (outer > 1 && violation > 0.25 * previous) rho = std::min(10 * rho, max_rho);
  }
  if (q > 0) violation = (c * x - d).cwiseAbs().maxCoeff();

  result.status = status;
  std::ostringstream msg;
  msg << "ceres (" << options.trust_region << "): " << stop;
  if (result.status == SolverStatus::kFailed && !last_failure.empty()) {
    msg << " (last failed evaluation: " << last_failure << ")";
  }
  if (!late_failure.empty()) msg << "; then " << late_failure;
  if (holds > 0) {
    msg << "; re-solved " << holds << " time(s) with the bounds it stalled at held";
  }
  if (nudges > 0) {
    msg << "; moved off bounds the gradient pulls it from and re-solved " << nudges
        << " time(s)";
  }
  if (q > 0 && result.status != SolverStatus::kFailed) {
    msg << "; equalities |C x - d|_inf = " << violation << " after " << outer
        << " augmented-Lagrangian iterations";
    if (!(violation < options.equality_tolerance)) {
      // Infeasible when x is (to the KKT tolerance) a minimiser of |C x - d|^2
      // within the bounds: that problem is convex, so no x does better.
      const Eigen::VectorXd gap = c * x - d;
      const double gap_scale = (c.cwiseAbs().transpose() * gap.cwiseAbs()).maxCoeff();
      const KktReport closest =
          CheckKkt(x, c.transpose() * gap, problem.lower, problem.upper,
                   Eigen::MatrixXd(), Eigen::VectorXd(), problem.fixed, gap_scale);
      if (closest.residual() <= options.kkt_tolerance) {
        result.status = SolverStatus::kInfeasible;
        msg << ": no x within the bounds satisfies the equalities (this x minimises "
               "|C x - d| over them)";
      } else {
        result.status = SolverStatus::kNoConvergence;
        msg << ", above equality_tolerance " << options.equality_tolerance;
      }
    }
  }
  result.message = msg.str();
  return result;
}

}  // namespace

NonlinearSolution CeresSolver::Solve(const NonlinearProblem& problem) const {
  return nonlinear_internal::Solve("ceres", problem, options_, RunCeres);
}

}  // namespace femup
