#include "femup/solvers/tsvd.h"

#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <sstream>

#include "femup/core/errors.h"
#include "linear_common.h"

namespace femup {

namespace {

// Menger curvature of three points (the discrete L-curve corner).
double Menger(double x1, double y1, double x2, double y2, double x3, double y3) {
  const double a = std::hypot(x2 - x1, y2 - y1), b = std::hypot(x3 - x2, y3 - y2),
               c = std::hypot(x3 - x1, y3 - y1);
  const double cross = (x2 - x1) * (y3 - y1) - (y2 - y1) * (x3 - x1);
  if (a * b * c == 0) return 0.0;
  // Positive for a turn like the L-curve's corner (residual down, norm up).
  return -2 * cross / (a * b * c);
}

}  // namespace

LinearSolution TsvdSolver::Solve(const LinearProblem& problem) const {
  const internal::Stopwatch clock;
  if (const Invalid bad = options_.regularisation.Validate())
    throw InputError("solver.regularisation", bad.ToString());
  const internal::ReducedProblem r = internal::Reduce(problem, name());
  const int m = problem.data_rows();

  LinearSolution solution;
  solution.identifiability = AnalyseIdentifiability(
      r.A, r.names, r.groups, options_.relative_rank_tolerance, true);
  Eigen::BDCSVD<Eigen::MatrixXd> svd(r.A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  const Eigen::VectorXd beta = svd.matrixU().transpose() * r.b;
  int rank = 0;
  while (rank < s.size() && s[rank] > options_.relative_rank_tolerance * s[0]) ++rank;
  if (rank == 0) {
    solution.summary.status = SolverStatus::kFailed;
    solution.summary.message = "tsvd: the matrix is zero";
    return solution;
  }
  const double delta0_sq =
      std::max(0.0, r.b.squaredNorm() - beta.squaredNorm()) + problem.residual_offset;
  // Residual and solution norms for k = 1..rank.
  std::vector<double> res(rank + 1), norm(rank + 1);
  double tail = beta.squaredNorm(), head = 0;
  for (int k = 0; k <= rank; ++k) {
    if (k > 0) {
      tail -= beta[k - 1] * beta[k - 1];
      head += (beta[k - 1] / s[k - 1]) * (beta[k - 1] / s[k - 1]);
    }
    res[k] = std::sqrt(std::max(0.0, tail) + delta0_sq);
    norm[k] = std::sqrt(head);
  }
  const RegularisationOptions& ro = options_.regularisation;
  RegularisationReport& rep = solution.regularisation;
  rep.parameter_choice = options_.truncation > 0 ? "fixed" : ro.parameter_choice;
  auto gcv = [&](int k) {
    const double dof = m - k;
    return dof > 0 ? res[k] * res[k] / (dof * dof)
                   : std::numeric_limits<double>::infinity();
  };
  int chosen = 0;
  std::ostringstream note;
  if (options_.truncation > 0) {
    chosen = std::min(options_.truncation, rank);
    if (options_.truncation > rank)
      note << "truncation " << options_.truncation << " exceeds the numerical rank "
           << rank << "; " << rank << " used";
  } else if (ro.parameter_choice == "gcv") {
    chosen = 1;
    for (int k = 2; k <= rank; ++k) {
      if (gcv(k) < gcv(chosen)) chosen = k;
    }
  } else if (ro.parameter_choice == "discrepancy") {
    const double target = ro.discrepancy_factor * ro.noise_norm;
    chosen = rank;
    for (int k = 1; k <= rank; ++k) {
      if (res[k] <= target) {
        chosen = k;
        break;
      }
    }
    if (res[rank] > target)
      note << "discrepancy principle: even k = " << rank << " leaves a residual "
           << res[rank] << " above the target " << target;
  } else if (ro.parameter_choice == "quasi_optimality") {
    chosen = 1;
    for (int k = 2; k <= rank; ++k) {
      if (std::abs(beta[k - 1] / s[k - 1]) < std::abs(beta[chosen - 1] / s[chosen - 1]))
        chosen = k;
    }
  } else if (ro.parameter_choice == "lcurve") {
    chosen = rank;
    double best = -std::numeric_limits<double>::infinity();
    for (int k = 2; k < rank; ++k) {
      if (res[k - 1] <= 0 || res[k + 1] <= 0 || norm[k - 1] <= 0) continue;
      const double c =
          Menger(std::log(res[k - 1]), std::log(norm[k - 1]), std::log(res[k]),
                 std::log(norm[k]), std::log(res[k + 1]), std::log(norm[k + 1]));
      if (c > best) {
        best = c;
        chosen = k;
      }
    }
    if (rank < 3) note << "L-curve: fewer than three points; k = rank used";
  } else {
    throw InputError(
        "solver.truncation",
        "tsvd with the fixed rule needs truncation > 0 (the number of singular "
        "values kept)");
  }
  rep.truncation = chosen;
  rep.note = note.str();
  for (int k = 1; k <= rank; ++k) {
    rep.grid_lambda.push_back(s[k - 1]);  // the k-th singular value plays lambda's part
    rep.grid_residual_norm.push_back(res[k]);
    rep.grid_solution_norm.push_back(norm[k]);
    rep.grid_gcv.push_back(gcv(k));
  }

  const Eigen::MatrixXd uk = svd.matrixU().leftCols(chosen);
  const Eigen::MatrixXd vk = svd.matrixV().leftCols(chosen);
  const Eigen::MatrixXd z_map =
      vk * s.head(chosen).cwiseInverse().asDiagonal() * uk.transpose();
  const Eigen::VectorXd z = z_map * r.b;
  const Eigen::VectorXd weighted_residual = internal::SetAnswer(problem, r, z, &solution);
  internal::FillUncertainty(problem, r.Lift(z_map), weighted_residual, chosen,
                            options_.confidence_level, &solution);
  const Eigen::MatrixXd rz = vk * vk.transpose();  // resolution in z
  solution.resolution = r.basis * rz * r.basis.transpose();
  const Eigen::VectorXd zt = r.basis.transpose() * (solution.x - r.particular);
  solution.bias_estimate =
      r.basis * ((rz - Eigen::MatrixXd::Identity(rz.rows(), rz.cols())) * zt);

  std::ostringstream msg;
  msg << "truncated SVD: " << chosen << " of " << r.A.cols() << " singular values kept ("
      << rep.parameter_choice << ")";
  internal::FinishRegularised(msg.str(), r, clock.Seconds(), &solution);
  return solution;
}

}  // namespace femup
