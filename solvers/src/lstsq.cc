#include "femup/solvers/lstsq.h"

#include <Eigen/SVD>
#include <sstream>

#include "linear_common.h"

namespace femup {

LinearSolution LstsqSolver::Solve(const LinearProblem& problem) const {
  const internal::Stopwatch clock;
  const internal::ReducedProblem r = internal::Reduce(problem);
  const int k = static_cast<int>(r.A.cols());

  LinearSolution solution;
  solution.identifiability = AnalyseIdentifiability(
      r.A, r.names, r.groups, options_.relative_rank_tolerance, options_.scale_columns);

  Eigen::VectorXd scale = Eigen::VectorXd::Ones(k);
  if (options_.scale_columns) {
    scale = r.A.colwise().norm().transpose();
    for (int j = 0; j < k; ++j) {
      if (scale[j] == 0) scale[j] = 1.0;
    }
  }
  const Eigen::MatrixXd as = r.A * scale.cwiseInverse().asDiagonal();
  Eigen::BDCSVD<Eigen::MatrixXd> svd(as, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double threshold =
      s.size() > 0 ? options_.relative_rank_tolerance * s.maxCoeff() : 0.0;
  int rank = 0;
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i) {
    if (s[i] > threshold) {
      inv[i] = 1.0 / s[i];
      ++rank;
    }
  }
  // z = D^-1 V S^+ U' b: the map from the weighted data to the answer.
  const Eigen::MatrixXd z_map = scale.cwiseInverse().asDiagonal() * svd.matrixV() *
                                inv.asDiagonal() * svd.matrixU().transpose();
  const Eigen::VectorXd z = z_map * r.b;
  solution.x = r.ToX(z);
  solution.residual = problem.A * solution.x - problem.b;
  const Eigen::VectorXd weighted_residual = r.weighted.A * solution.x - r.weighted.b;
  solution.summary.cost = 0.5 * weighted_residual.squaredNorm();
  solution.summary.iterations = 1;
  internal::FillUncertainty(problem, r.basis * z_map, weighted_residual, rank,
                            options_.confidence_level, &solution);

  std::ostringstream msg;
  if (rank == k) {
    solution.summary.status = SolverStatus::kSolved;
    msg << "least squares by SVD: full column rank (" << rank
        << (r.has_equalities ? " free combinations after the equalities)"
                             : " free unknowns)");
  } else {
    solution.summary.status = SolverStatus::kMinimumNorm;
    msg << "least squares by SVD: rank " << rank << " of " << k
        << " free unknowns; the minimum-norm solution is one of many. Add a constraint: ";
    for (std::size_t j = 0; j < solution.identifiability.null_directions.size(); ++j) {
      msg << (j ? "; " : "") << solution.identifiability.null_directions[j].description;
    }
    solution.summary.warnings.push_back(
        "rank deficient: the covariance covers only the combinations the data determine");
  }
  if (!options_.scale_columns && rank < k) {
    solution.summary.warnings.push_back(
        "columns were not scaled: the rank decision depends on the units of the "
        "unknowns; "
        "scale_columns = true may keep directions this one truncated");
  }
  solution.summary.message = msg.str();
  if (problem.has_bounds()) {
    solution.summary.warnings.push_back(
        "bounds ignored: lstsq does not take bounds (bvls, ceres and ipopt do)");
  }
  solution.summary.time_seconds = clock.Seconds();
  return solution;
}

}  // namespace femup
