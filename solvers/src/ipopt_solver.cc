#include "femup/solvers/ipopt_solver.h"

#include "femup/core/enum_names.h"

// Ipopt 3.11's headers leave parameters of default virtual methods unused; they
// are not ours to fix (CMake includes them as system headers, a plain -I does not).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <mutex>
#include <sstream>

#include "nonlinear_common.h"

namespace femup {

namespace {

using Ipopt::Index;
using Ipopt::Number;

// Ipopt reads bounds at or beyond +-1e19 as absent.
constexpr Number kNoBound = 2e19;
// Ipopt's `tol` must be positive; it is not taken below this. Ipopt measures
// complementarity by the product (x - bound) z, so a parameter of small scale
// can stop well inside an active bound unless tol is tight: on 400 random
// bounded problems tol = 1e-12 left 17 answers 1e-7 away from the optimum, tol
// = 1e-14 none (at about 10% more iterations).
constexpr double kMinTolerance = 1e-15;

// min 0.5 |r(x)|^2 subject to the problem's bounds, fixed values (lower = upper)
// and linear equalities, as Ipopt's TNLP. The residual and Jacobian are cached
// per point: Ipopt asks for f, grad f and the Hessian at the same x.
class LeastSquaresNlp final : public Ipopt::TNLP {
 public:
  LeastSquaresNlp(const NonlinearProblem& problem, const Eigen::VectorXd& start,
                  bool exact_hessian)
      : problem_(problem), exact_hessian_(exact_hessian), x_(start) {
    const auto& c = problem.equality_matrix;
    for (Index j = 0; j < c.cols(); ++j) {
      for (Index i = 0; i < c.rows(); ++i) {
        if (c(i, j) != 0) jacobian_entries_.emplace_back(i, j);
      }
    }
  }

  const Eigen::VectorXd& x() const { return x_; }
  const std::string& last_failure() const { return last_failure_; }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = problem_.num_parameters();
    m = static_cast<Index>(problem_.equality_matrix.rows());
    nnz_jac_g = static_cast<Index>(jacobian_entries_.size());
    nnz_h_lag = exact_hessian_ ? n * (n + 1) / 2 : 0;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] =
          problem_.lower.size() == n ? std::max(problem_.lower[i], -kNoBound) : -kNoBound;
      x_u[i] =
          problem_.upper.size() == n ? std::min(problem_.upper[i], kNoBound) : kNoBound;
    }
    for (const auto& [i, v] : problem_.fixed) x_l[i] = x_u[i] = v;
    for (Index k = 0; k < m; ++k) g_l[k] = g_u[k] = problem_.equality_rhs[k];
    return true;
  }

  // Only x is given: no warm start of the multipliers.
  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*, Number*,
                          Index, bool init_lambda, Number*) override {
    if (init_x) std::copy(x_.data(), x_.data() + n, x);
    return !init_z && !init_lambda;
  }

  bool eval_f(Index n, const Number* x, bool new_x, Number& obj_value) override {
    if (!Residuals(n, x, new_x)) return false;
    obj_value = 0.5 * residuals_.squaredNorm();
    return true;
  }

  bool eval_grad_f(Index n, const Number* x, bool new_x, Number* grad_f) override {
    if (!Jacobian(n, x, new_x)) return false;
    Eigen::Map<Eigen::VectorXd>(grad_f, n) = jacobian_.transpose() * residuals_;
    return true;
  }

  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    Eigen::Map<Eigen::VectorXd>(g, m) =
        problem_.equality_matrix * Eigen::Map<const Eigen::VectorXd>(x, n);
    return true;
  }

  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index* iRow, Index* jCol,
                  Number* values) override {
    for (std::size_t k = 0; k < jacobian_entries_.size(); ++k) {
      const auto [i, j] = jacobian_entries_[k];
      if (values == nullptr) {
        iRow[k] = i;
        jCol[k] = j;
      } else {
        values[k] = problem_.equality_matrix(i, j);
      }
    }
    return true;
  }

  // Gauss-Newton: obj_factor J'J, dense lower triangle (the constraints are
  // linear, so the multipliers do not enter).
  bool eval_h(Index n, const Number* x, bool new_x, Number obj_factor, Index,
              const Number*, bool, Index, Index* iRow, Index* jCol,
              Number* values) override {
    if (values == nullptr) {
      Index k = 0;
      for (Index i = 0; i < n; ++i) {
        for (Index j = 0; j <= i; ++j, ++k) {
          iRow[k] = i;
          jCol[k] = j;
        }
      }
      return true;
    }
    if (!Jacobian(n, x, new_x)) return false;
    const Eigen::MatrixXd h = jacobian_.transpose() * jacobian_;
    Index k = 0;
    for (Index i = 0; i < n; ++i) {
      for (Index j = 0; j <= i; ++j, ++k) values[k] = obj_factor * h(i, j);
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number,
                         const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    x_ = Eigen::Map<const Eigen::VectorXd>(x, n);
  }

 private:
  // Moves the cache to x when it is a new point.
  void Visit(Index n, const Number* x, bool new_x) {
    const Eigen::Map<const Eigen::VectorXd> point(x, n);
    if (!new_x && cached_x_.size() == n && cached_x_ == point) return;
    cached_x_ = point;
    have_residuals_ = have_jacobian_ = failed_ = false;
  }

  bool Residuals(Index n, const Number* x, bool new_x) {
    Visit(n, x, new_x);
    if (!have_residuals_ && !failed_) {
      failed_ = !nonlinear_internal::Evaluate(problem_, cached_x_, &residuals_, nullptr,
                                              &last_failure_);
      have_residuals_ = !failed_;
    }
    return !failed_;
  }

  bool Jacobian(Index n, const Number* x, bool new_x) {
    Visit(n, x, new_x);
    if (!have_jacobian_ && !failed_) {
      failed_ = !nonlinear_internal::Evaluate(problem_, cached_x_, &residuals_,
                                              &jacobian_, &last_failure_);
      have_residuals_ = have_jacobian_ = !failed_;
    }
    return !failed_;
  }

  const NonlinearProblem& problem_;
  const bool exact_hessian_;
  std::vector<std::pair<Index, Index>> jacobian_entries_;  // nonzeros of C
  Eigen::VectorXd x_;  // the start, then Ipopt's answer
  Eigen::VectorXd cached_x_, residuals_;
  Eigen::MatrixXd jacobian_;
  bool have_residuals_ = false, have_jacobian_ = false, failed_ = false;
  std::string last_failure_;
};

constexpr EnumName<Ipopt::ApplicationReturnStatus> kApplicationReturnStatusNames[] = {
    {Ipopt::Solve_Succeeded, "Solve_Succeeded"},
    {Ipopt::Solved_To_Acceptable_Level, "Solved_To_Acceptable_Level"},
    {Ipopt::Infeasible_Problem_Detected, "Infeasible_Problem_Detected"},
    {Ipopt::Search_Direction_Becomes_Too_Small, "Search_Direction_Becomes_Too_Small"},
    {Ipopt::Diverging_Iterates, "Diverging_Iterates"},
    {Ipopt::User_Requested_Stop, "User_Requested_Stop"},
    {Ipopt::Feasible_Point_Found, "Feasible_Point_Found"},
    {Ipopt::Maximum_Iterations_Exceeded, "Maximum_Iterations_Exceeded"},
    {Ipopt::Restoration_Failed, "Restoration_Failed"},
    {Ipopt::Error_In_Step_Computation, "Error_In_Step_Computation"},
    {Ipopt::Maximum_CpuTime_Exceeded, "Maximum_CpuTime_Exceeded"},
    {Ipopt::Not_Enough_Degrees_Of_Freedom, "Not_Enough_Degrees_Of_Freedom"},
    {Ipopt::Invalid_Problem_Definition, "Invalid_Problem_Definition"},
    {Ipopt::Invalid_Option, "Invalid_Option"},
    {Ipopt::Invalid_Number_Detected, "Invalid_Number_Detected"},
    {Ipopt::Unrecoverable_Exception, "Unrecoverable_Exception"},
    {Ipopt::NonIpopt_Exception_Thrown, "NonIpopt_Exception_Thrown"},
    {Ipopt::Insufficient_Memory, "Insufficient_Memory"},
    {Ipopt::Internal_Error, "Internal_Error"},
};

const char* StatusName(Ipopt::ApplicationReturnStatus status) {
  return NameIn(kApplicationReturnStatusNames, status, "unknown Ipopt status");
}

SolverStatus FromIpopt(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level:
      return SolverStatus::kSolved;
    case Ipopt::Maximum_Iterations_Exceeded:
    case Ipopt::Maximum_CpuTime_Exceeded:
      return SolverStatus::kNoConvergence;
    case Ipopt::Infeasible_Problem_Detected:
      return SolverStatus::kInfeasible;
    default:
      return SolverStatus::kFailed;
  }
}

// MUMPS (Ipopt's linear solver in Debian's build) keeps global state: one
// Ipopt solve at a time per process.
std::mutex& IpoptMutex() {
  static std::mutex mutex;
  return mutex;
}

// One run of Ipopt; see IpoptSolver::Solve.
nonlinear_internal::BackendResult RunIpopt(const NonlinearProblem& problem,
                                           const NonlinearSolverOptions& options,
                                           double gradient_scale) {
  std::lock_guard<std::mutex> lock(IpoptMutex());
  const Ipopt::SmartPtr<LeastSquaresNlp> nlp =
      new LeastSquaresNlp(problem, nonlinear_internal::StartingPoint(problem),
                          options.hessian == "gauss_newton");
  const Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  Ipopt::OptionsList& opts = *app->Options();
  opts.SetStringValue("sb", "yes");  // no banner
  opts.SetIntegerValue("print_level", options.verbose ? 5 : 0);
  opts.SetIntegerValue("max_iter", options.max_iterations);
  // tol applies to the scaled problem: scaling the objective by 1 / |J'r|_inf at
  // the start makes it a relative gradient tolerance, like the other backends'.
  opts.SetNumericValue("obj_scaling_factor", 1.0 / gradient_scale);
  opts.SetNumericValue("tol", std::max(options.gradient_tolerance, kMinTolerance));
  opts.SetNumericValue("constr_viol_tol", options.equality_tolerance);
  // Keep every iterate inside the bounds as given (Ipopt relaxes them by 1e-8
  // by default, and may then return a point slightly outside).
  opts.SetNumericValue("bound_relax_factor", 0.0);
  opts.SetStringValue("honor_original_bounds", "yes");
  opts.SetStringValue("jac_c_constant", "yes");
  if (options.hessian == "limited_memory") {
    opts.SetStringValue("hessian_approximation", "limited-memory");
  }

  // "" skips reading an ipopt.opt file from the working directory.
  Ipopt::ApplicationReturnStatus status = app->Initialize("");
  if (status == Ipopt::Solve_Succeeded) status = app->OptimizeTNLP(Ipopt::GetRawPtr(nlp));

  nonlinear_internal::BackendResult result;
  result.x = nlp->x();
  if (Ipopt::IsValid(app->Statistics())) {
    result.iterations = app->Statistics()->IterationCount();
  }
  result.status = FromIpopt(status);
  std::ostringstream msg;
  msg << "ipopt: " << StatusName(status);
  if (status == Ipopt::Solved_To_Acceptable_Level) {
    msg << " (only Ipopt's acceptable tolerances were met)";
  }
  if (result.status == SolverStatus::kFailed && !nlp->last_failure().empty()) {
    msg << " (last failed evaluation: " << nlp->last_failure() << ")";
  }
  result.message = msg.str();
  return result;
}

}  // namespace

NonlinearSolution IpoptSolver::Solve(const NonlinearProblem& problem) const {
  return nonlinear_internal::Solve("ipopt", problem, options_, RunIpopt);
}

}  // namespace femup
