#include "femup/solvers/ceres_solver.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "femup/solvers/kkt.h"
#include "nonlinear_common.h"

namespace femup {

namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// First penalty of the augmented Lagrangian, relative to |J|_F^2 / |C|_F^2 at the
// start, and how far it may grow: large enough for a few outer iterations to
// reach a tight equality tolerance, small enough to keep the QR well conditioned.
constexpr double kInitialPenalty = 1e3;
constexpr double kMaxPenaltyGrowth = 1e8;

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

SolverStatus FromCeres(ceres::TerminationType type) {
  switch (type) {
    case ceres::CONVERGENCE:
      return SolverStatus::kSolved;
    case ceres::NO_CONVERGENCE:
      return SolverStatus::kNoConvergence;
    default:  // FAILURE, USER_FAILURE
      return SolverStatus::kFailed;
  }
}

}  // namespace

NonlinearSolution CeresSolver::Solve(const NonlinearProblem& problem) const {
  nonlinear_internal::ValidateOptions(options_);
  nonlinear_internal::ValidateProblem(problem);
  const auto start = std::chrono::steady_clock::now();
  const int n = problem.num_parameters();
  const auto q = problem.equality_matrix.rows();
  const Eigen::MatrixXd& c = problem.equality_matrix;
  const Eigen::VectorXd& d = problem.equality_rhs;

  NonlinearSolution solution;
  SolverSummary& summary = solution.summary;
  Eigen::VectorXd& x = solution.x;  // Ceres works on x in place
  x = nonlinear_internal::StartingPoint(problem);
  Eigen::VectorXd r0;
  Eigen::MatrixXd j0;
  std::string why;
  if (!nonlinear_internal::Evaluate(problem, x, &r0, &j0, &why)) {
    summary.status = SolverStatus::kFailed;
    summary.message = "ceres: the model cannot be evaluated at the start: " + why;
    summary.time_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return solution;
  }
  const double scale = nonlinear_internal::GradientScale(problem, j0, r0);

  Eigen::VectorXd mu = Eigen::VectorXd::Zero(q);
  double rho = kInitialPenalty;
  if (q > 0 && c.squaredNorm() > 0) {
    rho *= std::max(j0.squaredNorm(), 1e-300) / c.squaredNorm();
  }
  const double max_rho = rho * kMaxPenaltyGrowth;

  std::string last_failure;
  ceres::Problem ceres_problem;  // owns the cost functions and the manifold
  ceres_problem.AddResidualBlock(new ModelCost(problem, &last_failure), nullptr, x.data());
  if (q > 0) {
    ceres_problem.AddResidualBlock(new EqualityPenalty(c, d, &rho, &mu), nullptr,
                                   x.data());
  }
  std::vector<int> fixed;
  for (const auto& f : problem.fixed) fixed.push_back(f.first);
  if (!fixed.empty()) {
    ceres_problem.SetManifold(x.data(), new ceres::SubsetManifold(n, fixed));
  }
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
  ceres_options.trust_region_strategy_type = options_.trust_region == "dogleg"
                                                 ? ceres::DOGLEG
                                                 : ceres::LEVENBERG_MARQUARDT;
  ceres_options.function_tolerance = options_.function_tolerance;
  // Ceres's gradient tolerance is absolute; ours is relative to the start.
  ceres_options.gradient_tolerance = options_.gradient_tolerance * scale;
  ceres_options.parameter_tolerance = options_.parameter_tolerance;
  ceres_options.logging_type =
      options_.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  ceres_options.minimizer_progress_to_stdout = options_.verbose;

  // Without equalities one pass; with them, the augmented-Lagrangian loop.
  ceres::Solver::Summary ceres_summary;
  double violation = 0;
  int outer = 0;
  while (true) {
    ceres_options.max_num_iterations = options_.max_iterations - summary.iterations;
    ceres::Solve(ceres_options, &ceres_problem, &ceres_summary);
    summary.iterations +=
        ceres_summary.num_successful_steps + ceres_summary.num_unsuccessful_steps;
    ++outer;
    if (q == 0 || FromCeres(ceres_summary.termination_type) == SolverStatus::kFailed) {
      break;
    }
    const Eigen::VectorXd gap = c * x - d;
    const double previous = violation;
    violation = gap.cwiseAbs().maxCoeff();
    if (violation < options_.equality_tolerance || outer >= options_.max_outer_iterations ||
        summary.iterations >= options_.max_iterations) {
      break;
    }
    mu += rho * gap;
    if (outer > 1 && violation > 0.25 * previous) rho = std::min(10 * rho, max_rho);
  }

  summary.status = FromCeres(ceres_summary.termination_type);
  std::ostringstream msg;
  msg << "ceres (" << options_.trust_region << "): " << ceres_summary.message;
  if (summary.status == SolverStatus::kFailed && !last_failure.empty()) {
    msg << " (last failed evaluation: " << last_failure << ")";
  }
  if (q > 0 && summary.status != SolverStatus::kFailed) {
    msg << "; equalities |C x - d|_inf = " << violation << " after " << outer
        << " augmented-Lagrangian iterations";
    if (!(violation < options_.equality_tolerance)) {
      // Infeasible when x is (to the KKT tolerance) a minimiser of |C x - d|^2 within
      // the bounds: that problem is convex, so no x does better.
      const Eigen::VectorXd gap = c * x - d;
      const double gap_scale =
          (c.cwiseAbs().transpose() * gap.cwiseAbs()).maxCoeff();
      const KktReport closest =
          CheckKkt(x, c.transpose() * gap, problem.lower, problem.upper,
                   Eigen::MatrixXd(), Eigen::VectorXd(), problem.fixed, gap_scale);
      if (closest.residual() <= options_.kkt_tolerance) {
        summary.status = SolverStatus::kInfeasible;
        msg << ": no x within the bounds satisfies the equalities (this x minimises "
               "|C x - d| over them)";
      } else {
        summary.status = SolverStatus::kNoConvergence;
        msg << ", above equality_tolerance " << options_.equality_tolerance;
      }
    }
  }
  summary.message = msg.str();
  nonlinear_internal::Finish(problem, options_, scale, start, &solution);
  return solution;
}

}  // namespace femup
