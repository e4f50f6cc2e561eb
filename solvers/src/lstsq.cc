#include "femup/solvers/lstsq.h"

#include <Eigen/SVD>
#include <chrono>
#include <sstream>

#include "femup/errors.h"

namespace femup {

LinearSolution LstsqSolver::Solve(const LinearProblem& problem) const {
  const auto start = std::chrono::steady_clock::now();
  const std::string invalid = problem.Validate();
  if (!invalid.empty()) throw InputError("linear problem", invalid);

  const std::vector<int> free = problem.FreeUnknowns();
  const int nfree = static_cast<int>(free.size());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(problem.num_unknowns());
  Eigen::VectorXd rhs = problem.b;
  for (const auto& [index, value] : problem.fixed) {
    x[index] = value;
    rhs -= problem.A.col(index) * value;
  }
  Eigen::MatrixXd a(problem.num_rows(), nfree);
  std::vector<std::string> names, groups;
  for (int k = 0; k < nfree; ++k) {
    a.col(k) = problem.A.col(free[k]);
    if (!problem.names.empty()) names.push_back(problem.names[free[k]]);
    if (!problem.groups.empty()) groups.push_back(problem.groups[free[k]]);
  }

  LinearSolution solution;
  solution.identifiability = AnalyseIdentifiability(
      a, names, groups, options_.relative_rank_tolerance, options_.scale_columns);

  Eigen::VectorXd scale = Eigen::VectorXd::Ones(nfree);
  if (options_.scale_columns) {
    scale = a.colwise().norm().transpose();
    for (int k = 0; k < nfree; ++k) {
      if (scale[k] == 0) scale[k] = 1.0;
    }
  }
  const Eigen::MatrixXd as = a * scale.cwiseInverse().asDiagonal();
  Eigen::BDCSVD<Eigen::MatrixXd> svd(as, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double threshold =
      s.size() > 0 ? options_.relative_rank_tolerance * s.maxCoeff() : 0.0;
  Eigen::VectorXd utb = svd.matrixU().transpose() * rhs;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(s.size());
  int rank = 0;
  for (Eigen::Index i = 0; i < s.size(); ++i) {
    if (s[i] > threshold) {
      y[i] = utb[i] / s[i];
      ++rank;
    }
  }
  const Eigen::VectorXd xs = svd.matrixV() * y;
  for (int k = 0; k < nfree; ++k) x[free[k]] = xs[k] / scale[k];

  solution.x = x;
  solution.residual = problem.A * x - problem.b;
  solution.summary.cost = 0.5 * solution.residual.squaredNorm();
  solution.summary.iterations = 1;
  std::ostringstream msg;
  if (rank == nfree) {
    solution.summary.status = SolverStatus::kSolved;
    msg << "least squares by SVD: full column rank (" << rank << " free unknowns)";
  } else {
    solution.summary.status = SolverStatus::kMinimumNorm;
    msg << "least squares by SVD: rank " << rank << " of " << nfree
        << " free unknowns; the minimum-norm solution is one of many. Add a constraint: ";
    for (std::size_t k = 0; k < solution.identifiability.null_directions.size(); ++k) {
      msg << (k ? "; " : "") << solution.identifiability.null_directions[k].description;
    }
  }
  solution.summary.message = msg.str();
  solution.summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

}  // namespace femup
