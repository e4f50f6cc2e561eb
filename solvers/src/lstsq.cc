#include "femup/solvers/lstsq.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <sstream>

#include "linear_common.h"

namespace femup {

namespace {

// Steps of iterative refinement of the least-squares answer (see Refine).
constexpr int kRefinementSteps = 2;

// Iterative refinement on the augmented system [I A; A' 0] [r; z] = [b; 0]
// (Bjorck 1967), with its residuals f = b - r - A z and g = -A' r computed in long
// double and the corrections solved with the SVD already at hand,
// A D^-1 = U S V' (D = diag(scale); `inv` holds S^+). A plain solve loses digits to
// the kappa^2 |r| term of the least-squares sensitivity when the residual is
// large; each step gains up to log10(1 / (kappa eps)) digits, and two steps bring
// the answer to the least-squares solution of the data as given (NIST's Wampler4
// and Wampler5: from 8.4 and 6.4 to 13.6 and 13.9 correct digits). On a rank-
// deficient matrix the corrections stay in the kept singular directions.
Eigen::VectorXd Refine(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                       const Eigen::VectorXd& scale, const Eigen::MatrixXd& u,
                       const Eigen::VectorXd& inv, const Eigen::MatrixXd& v,
                       Eigen::VectorXd z) {
  using VectorLd = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
  using MatrixLd = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  const MatrixLd al = a.cast<long double>();
  const VectorLd bl = b.cast<long double>();
  Eigen::VectorXd r = (bl - al * z.cast<long double>()).cast<double>();
  for (int step = 0; step < kRefinementSteps; ++step) {
    const VectorLd rl = r.cast<long double>();
    const Eigen::VectorXd f = (bl - rl - al * z.cast<long double>()).cast<double>();
    // g in the scaled unknowns: (A D^-1)' r = D^-1 A' r.
    const Eigen::VectorXd g =
        (-(al.transpose() * rl)).cast<double>().cwiseQuotient(scale);
    const Eigen::VectorXd c = inv.asDiagonal() * (v.transpose() * g);
    const Eigen::VectorXd utf = u.transpose() * f;
    z += (v * (inv.asDiagonal() * (utf - c))).cwiseQuotient(scale);
    r += u * c + f - u * utf;
  }
  return z;
}

// Without diagnostics: the least-squares answer by column-pivoted Householder
// QR of the column-scaled A when A is of full column rank by the SVD path's own
// rule, which the QR proves with norms of R: s_max <= ||R||_F and
// s_min >= 1 / ||R^-1||_F, so tol * ||R||_F * ||R^-1||_F < 1 gives
// s_min > tol * s_max. Returns false (nothing done) when that cannot be shown;
// the SVD path then decides.
bool SolveFullRankByQr(const internal::ReducedProblem& r, double tolerance,
                       bool scale_columns, Eigen::VectorXd* z) {
  const Eigen::Index k = r.A.cols();
  if (k == 0 || r.A.rows() < k) return false;
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(k);
  if (scale_columns) {
    scale = r.A.colwise().norm().transpose();
    for (Eigen::Index j = 0; j < k; ++j) {
      if (scale[j] == 0) return false;
    }
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(r.A *
                                                       scale.cwiseInverse().asDiagonal());
  const Eigen::MatrixXd upper =
      qr.matrixR().topLeftCorner(k, k).triangularView<Eigen::Upper>();
  for (Eigen::Index j = 0; j < k; ++j) {
    if (!(std::abs(upper(j, j)) > 0)) return false;
  }
  const Eigen::MatrixXd r_inverse =
      upper.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(k, k));
  const double r_norm = upper.norm();
  if (!(tolerance * r_norm * r_inverse.norm() < 1.0)) return false;
  *z = qr.solve(r.b).cwiseQuotient(scale);
  return z->allFinite();
}

}  // namespace

LinearSolution LstsqSolver::Solve(const LinearProblem& problem) const {
  const internal::Stopwatch clock;
  const internal::ReducedProblem r = internal::Reduce(problem, name());
  const int k = static_cast<int>(r.A.cols());

  if (!options_.diagnostics) {
    Eigen::VectorXd z;
    if (SolveFullRankByQr(r, options_.relative_rank_tolerance, options_.scale_columns,
                          &z)) {
      LinearSolution solution;
      solution.x = r.ToX(z);
      solution.residual = problem.A * solution.x - problem.b;
      const Eigen::VectorXd weighted_residual = r.weighted.A * solution.x - r.weighted.b;
      solution.summary.cost = 0.5 * weighted_residual.squaredNorm();
      solution.summary.iterations = 1;
      solution.summary.status = SolverStatus::kSolved;
      solution.summary.message =
          "least squares by column-pivoted QR: full column rank (" + std::to_string(k) +
          " free unknowns); diagnostics off";
      solution.summary.warnings = r.warnings;
      solution.summary.time_seconds = clock.Seconds();
      return solution;
    }
  }

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
  const Eigen::VectorXd z =
      Refine(r.A, r.b, scale, svd.matrixU(), inv, svd.matrixV(), z_map * r.b);
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
  solution.summary.warnings.insert(solution.summary.warnings.end(), r.warnings.begin(),
                                   r.warnings.end());
  solution.summary.time_seconds = clock.Seconds();
  return solution;
}

}  // namespace femup
