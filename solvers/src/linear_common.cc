#include "linear_common.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/linalg/dense_kernels.h"
#include "femup/solvers/uncertainty.h"

namespace femup::internal {

Eigen::MatrixXd ReducedProblem::ToX(const Eigen::VectorXd& z) const {
  return particular + basis * z;
}

Eigen::MatrixXd ReducedProblem::Lift(const Eigen::MatrixXd& m) const {
  if (has_equalities) return basis * m;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(basis.rows(), m.cols());
  for (std::size_t k = 0; k < free.size(); ++k)
    out.row(free[k]) = m.row(static_cast<Eigen::Index>(k));
  return out;
}

ReducedProblem Reduce(const LinearProblem& problem, const std::string& solver) {
  if (const Invalid bad = problem.Validate())
    throw InputError("linear problem", bad.ToString());
  ReducedProblem r;
  if (problem.has_bounds()) {
    r.warnings.push_back("bounds ignored: " + solver +
                         " does not take bounds (bvls, ceres and ipopt do)");
  }
  const int n = problem.num_unknowns();
  r.weighted = Weighted(problem);
  r.free = problem.FreeUnknowns();
  const int nf = static_cast<int>(r.free.size());
  r.particular = Eigen::VectorXd::Zero(n);
  for (const auto& [i, value] : problem.fixed) r.particular[i] = value;

  Eigen::MatrixXd select = Eigen::MatrixXd::Zero(n, nf);  // free unknowns -> x
  for (int k = 0; k < nf; ++k) select(r.free[k], k) = 1.0;

  if (problem.has_equalities()) {
    r.has_equalities = true;
    const Eigen::MatrixXd c = problem.equality_matrix * select;
    const Eigen::VectorXd d =
        problem.equality_rhs - problem.equality_matrix * r.particular;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(c, Eigen::ComputeFullV);
    const Eigen::VectorXd& s = svd.singularValues();
    int rank = 0;
    const double tol = s.size() > 0 ? 1e-12 * s[0] * std::max(c.rows(), c.cols()) : 0.0;
    while (rank < s.size() && s[rank] > tol) ++rank;
    Eigen::VectorXd xf = Eigen::VectorXd::Zero(nf);  // minimum-norm particular solution
    const Eigen::MatrixXd v = svd.matrixV();
    Eigen::JacobiSVD<Eigen::MatrixXd> thin(c, Eigen::ComputeThinU | Eigen::ComputeThinV);
    for (int i = 0; i < rank; ++i) xf += v.col(i) * (thin.matrixU().col(i).dot(d) / s[i]);
    r.particular += select * xf;
    r.basis = select * v.rightCols(nf - rank);
    for (int k = 0; k < nf - rank; ++k) {
      r.names.push_back("combination[" + std::to_string(k) + "]");
      r.groups.push_back("combination");
    }
  } else {
    r.basis = select;
    for (int k = 0; k < nf; ++k) {
      if (!problem.names.empty()) r.names.push_back(problem.names[r.free[k]]);
      if (!problem.groups.empty()) r.groups.push_back(problem.groups[r.free[k]]);
    }
  }
  if (r.has_equalities) {
    r.A = r.weighted.A * r.basis;
  } else {  // basis selects columns: gather them (the same numbers, no product)
    r.A.resize(r.weighted.A.rows(), nf);
    for (int k = 0; k < nf; ++k) r.A.col(k) = r.weighted.A.col(r.free[k]);
  }
  r.b = r.weighted.b - r.weighted.A * r.particular;
  return r;
}

void FillUncertainty(const LinearProblem& problem, const Eigen::MatrixXd& x_map,
                     const Eigen::VectorXd& weighted_residual, double parameters_used,
                     double confidence_level, LinearSolution* solution) {
  const double m = problem.data_rows();
  solution->confidence_level = confidence_level;
  solution->noise_estimated = !problem.noise_known();
  double variance = 1.0, dof = 0.0;
  if (solution->noise_estimated) {
    dof = m - parameters_used;
    if (dof < 0.5) {
      solution->summary.warnings.push_back(
          "no uncertainty: the data leave no degree of freedom to estimate the noise "
          "(give data_sigma or weights)");
      return;
    }
    variance = (weighted_residual.squaredNorm() + problem.residual_offset) / dof;
  }
  // X X' by a symmetric rank update (half the flops of a general product; the
  // BLAS's dsyrk), then the upper triangle from the lower: exactly symmetric.
  const Eigen::Index n = x_map.rows();
  solution->covariance.resize(n, n);
  const Eigen::MatrixXd x_transposed = x_map.transpose();
  RankUpdateLower(x_transposed, variance, 0.0, solution->covariance);
  Eigen::MatrixXd& c = solution->covariance;
  for (Eigen::Index j = 1; j < n; ++j) {  // a loop: no aliasing of c with c'
    for (Eigen::Index i = 0; i < j; ++i) c(i, j) = c(j, i);
  }
  SetIntervals(dof, solution);
}

Eigen::VectorXd SetAnswer(const LinearProblem& problem, const ReducedProblem& reduced,
                          const Eigen::VectorXd& z, LinearSolution* solution) {
  solution->x = reduced.ToX(z);
  solution->residual = problem.A * solution->x - problem.b;
  Eigen::VectorXd weighted_residual =
      reduced.weighted.A * solution->x - reduced.weighted.b;
  solution->summary.cost = 0.5 * weighted_residual.squaredNorm();
  solution->summary.iterations = 1;
  return weighted_residual;
}

void FinishRegularised(const std::string& message, const ReducedProblem& reduced,
                       double seconds, LinearSolution* solution) {
  SolverSummary& summary = solution->summary;
  summary.status = SolverStatus::kSolved;
  summary.message = message;
  if (!solution->regularisation.note.empty())
    summary.warnings.push_back(solution->regularisation.note);
  summary.warnings.insert(summary.warnings.end(), reduced.warnings.begin(),
                          reduced.warnings.end());
  summary.time_seconds = seconds;
}

}  // namespace femup::internal
