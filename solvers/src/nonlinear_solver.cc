#include "femup/solvers/nonlinear_solver.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "femup/errors.h"
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

// "<field>: must be ..., got <value>" when `ok` is false, else "".
template <typename T>
std::string Require(bool ok, const char* field, const char* requirement, T value) {
  if (ok) return "";
  std::ostringstream msg;
  msg << field << ": must be " << requirement << ", got " << value;
  return msg.str();
}

std::string OneOf(const std::string& value, const char* field,
                  const std::vector<std::string>& allowed) {
  if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return "";
  return std::string(field) + ": unknown value '" + value + "' (allowed: " +
         Join(allowed) + ")";
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

// The equality matrix restricted to the free parameters.
Eigen::MatrixXd FreeEqualities(const NonlinearProblem& problem,
                               const std::vector<int>& free) {
  Eigen::MatrixXd c(problem.equality_matrix.rows(), free.size());
  for (std::size_t k = 0; k < free.size(); ++k) {
    c.col(k) = problem.equality_matrix.col(free[k]);
  }
  return c;
}

}  // namespace

std::string NonlinearSolverOptions::Validate() const {
  const auto nonnegative = [](double v) { return std::isfinite(v) && v >= 0; };
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  for (const std::string& error : {
           Require(max_iterations > 0, "max_iterations", "positive", max_iterations),
           Require(nonnegative(function_tolerance), "function_tolerance",
                   "finite and >= 0", function_tolerance),
           Require(nonnegative(gradient_tolerance), "gradient_tolerance",
                   "finite and >= 0", gradient_tolerance),
           Require(nonnegative(parameter_tolerance), "parameter_tolerance",
                   "finite and >= 0", parameter_tolerance),
           OneOf(trust_region, "trust_region", {"levenberg_marquardt", "dogleg"}),
           OneOf(hessian, "hessian", {"gauss_newton", "limited_memory"}),
           Require(positive(kkt_tolerance), "kkt_tolerance", "finite and > 0",
                   kkt_tolerance),
           Require(max_outer_iterations > 0, "max_outer_iterations", "positive",
                   max_outer_iterations),
           Require(positive(equality_tolerance), "equality_tolerance", "finite and > 0",
                   equality_tolerance),
       }) {
    if (!error.empty()) return error;
  }
  return "";
}

std::vector<std::string> AvailableNonlinearSolvers() { return {"ceres", "ipopt"}; }

std::unique_ptr<NonlinearSolver> CreateNonlinearSolver(
    const std::string& name, const NonlinearSolverOptions& options) {
  const std::vector<std::string> available = AvailableNonlinearSolvers();
  if (std::find(available.begin(), available.end(), name) == available.end()) {
    throw InputError("solver.name",
                     "unknown solver '" + name + "' (available: " + Join(available) + ")");
  }
  nonlinear_internal::ValidateOptions(options);
  if (name == "ceres") return std::make_unique<CeresSolver>(options);
  return std::make_unique<IpoptSolver>(options);
}

namespace nonlinear_internal {

void ValidateOptions(const NonlinearSolverOptions& options) {
  const std::string invalid = options.Validate();
  if (invalid.empty()) return;
  const auto colon = invalid.find(": ");
  throw InputError("solver." + invalid.substr(0, colon), invalid.substr(colon + 2));
}

void ValidateProblem(const NonlinearProblem& problem) {
  const std::string invalid = problem.Validate();
  if (!invalid.empty()) throw InputError("nonlinear problem", invalid);
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

double GradientScale(const NonlinearProblem& problem, const Eigen::MatrixXd& jacobian,
                     const Eigen::VectorXd& residuals) {
  const Eigen::VectorXd g = jacobian.transpose() * residuals;
  double scale = 0;
  for (int i : problem.FreeUnknowns()) scale = std::max(scale, std::abs(g[i]));
  return scale > 0 ? scale : 1.0;
}

int EstimatedParameters(const NonlinearProblem& problem) {
  const std::vector<int> free = problem.FreeUnknowns();
  if (problem.equality_matrix.rows() == 0) return static_cast<int>(free.size());
  return static_cast<int>(NullSpace(FreeEqualities(problem, free)).cols());
}

Eigen::MatrixXd Covariance(const NonlinearProblem& problem, const Eigen::MatrixXd& jacobian,
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
  const double variance =
      problem.residuals_whitened ? 1.0 : residuals.squaredNorm() / static_cast<double>(dof);
  const Eigen::MatrixXd free_covariance = variance * factor * factor.transpose();
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t a = 0; a < free.size(); ++a) {
    for (std::size_t b = 0; b < free.size(); ++b) {
      covariance(free[a], free[b]) = free_covariance(a, b);
    }
  }
  return covariance;
}

void Finish(const NonlinearProblem& problem, const NonlinearSolverOptions& options,
            double gradient_scale, std::chrono::steady_clock::time_point start,
            NonlinearSolution* solution) {
  SolverSummary& summary = solution->summary;
  std::string why;
  if (!Evaluate(problem, solution->x, &solution->residual, &solution->jacobian, &why)) {
    summary.status = SolverStatus::kFailed;
    summary.message += "; the model cannot be evaluated at the returned point: " + why;
    solution->residual.resize(0);
    solution->jacobian.resize(0, 0);
  } else {
    summary.cost = 0.5 * solution->residual.squaredNorm();
    solution->covariance = Covariance(problem, solution->jacobian, solution->residual);
    if (problem.has_bounds() || problem.equality_matrix.rows() > 0) {
      const KktReport kkt =
          CheckKkt(solution->x, solution->jacobian.transpose() * solution->residual,
                   problem.lower, problem.upper, problem.equality_matrix,
                   problem.equality_rhs, problem.fixed, gradient_scale);
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
    }
  }
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace nonlinear_internal
}  // namespace femup
