#include "femup/solvers/lstsq.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <sstream>

#include "gram_least_squares.h"
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

constexpr const char* kGramRoute =
    "least squares through the Gram matrix of the compressed system (its eigenvalues and "
    "a Cholesky factor)";

// The column-scaled SVD route: A D^-1 = U S V', z = D^-1 V S^+ U' b refined,
// Cov(z) / sigma^2 = (D^-1 V S^+)(D^-1 V S^+)' (U's columns are orthonormal).
internal::LeastSquaresDecomposition BySvd(const internal::ReducedProblem& r,
                                          const LinearSolverOptions& options) {
  const Eigen::Index k = r.A.cols();
  const Eigen::VectorXd scale = IdentifiabilityScale(r.A, options.scale_columns);
  const Eigen::MatrixXd as = r.A * scale.cwiseInverse().asDiagonal();
  // One SVD for the solve and, when it holds all of V (at least as many rows
  // as columns), for the identifiability analysis too.
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(as, Eigen::ComputeThinU | Eigen::ComputeThinV);
  internal::LeastSquaresDecomposition d;
  d.identifiability =
      r.A.rows() >= k
          ? AnalyseIdentifiability(r.A, svd, r.names, r.groups,
                                   options.relative_rank_tolerance, options.scale_columns)
          : AnalyseIdentifiability(r.A, r.names, r.groups,
                                   options.relative_rank_tolerance,
                                   options.scale_columns);
  const Eigen::VectorXd& s = svd.singularValues();
  const double threshold =
      s.size() > 0 ? options.relative_rank_tolerance * s.maxCoeff() : 0.0;
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i) {
    if (s[i] > threshold) {
      inv[i] = 1.0 / s[i];
      ++d.rank;
    }
  }
  d.z_root = scale.cwiseInverse().asDiagonal() * svd.matrixV() * inv.asDiagonal();
  d.z = Refine(r.A, r.b, scale, svd.matrixU(), inv, svd.matrixV(),
               d.z_root * (svd.matrixU().transpose() * r.b));
  return d;
}

}  // namespace

LinearSolution LstsqSolver::Solve(const LinearProblem& problem) const {
  const internal::Stopwatch clock;
  const internal::ReducedProblem r = internal::Reduce(problem, name());
  const int k = static_cast<int>(r.A.cols());

  if (!options_.diagnostics) {
    Eigen::VectorXd z;
    FullRankLeastSquares qr(options_.relative_rank_tolerance, options_.scale_columns);
    if (qr.Solve(r.A, r.b, &z)) {
      LinearSolution solution;
      internal::SetAnswer(problem, r, z, &solution);
      solution.summary.status = SolverStatus::kSolved;
      solution.summary.message = "least squares by Householder QR: full column rank (" +
                                 std::to_string(k) + " free unknowns); diagnostics off";
      solution.summary.warnings = r.warnings;
      solution.summary.time_seconds = clock.Seconds();
      return solution;
    }
  }

  LinearSolution solution;
  // No free unknown or a non-finite entry: the analysis throws its own
  // InputError, before any decomposition.
  if (k == 0 || !r.A.allFinite()) {
    AnalyseIdentifiability(r.A, r.names, r.groups, options_.relative_rank_tolerance,
                           options_.scale_columns);
  }
  internal::LeastSquaresDecomposition d;
  const bool by_gram = problem.source_rows > 0 && k >= options_.gram_min_unknowns &&
                       r.A.rows() >= k &&
                       internal::LeastSquaresByGram(r, options_.relative_rank_tolerance,
                                                    options_.scale_columns, &d);
  if (!by_gram) d = BySvd(r, options_);
  const int rank = d.rank;
  solution.identifiability = std::move(d.identifiability);
  const Eigen::VectorXd weighted_residual =
      internal::SetAnswer(problem, r, d.z, &solution);
  internal::FillUncertainty(problem, r.Lift(d.z_root), weighted_residual, rank,
                            options_.confidence_level, &solution);

  std::ostringstream msg;
  if (rank == k) {
    solution.summary.status = SolverStatus::kSolved;
    msg << (by_gram ? kGramRoute : "least squares by SVD") << ": full column rank ("
        << rank
        << (r.has_equalities ? " free combinations after the equalities)"
                             : " free unknowns)");
  } else {
    solution.summary.status = SolverStatus::kMinimumNorm;
    msg << (by_gram ? kGramRoute : "least squares by SVD") << ": rank " << rank << " of "
        << k
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

void FullRankLeastSquares::FactoriseByLoops(Eigen::Index k) {
  const Eigen::Index m = scaled_.rows();
  double* q = scaled_.data();
  double* c = rhs_.data();
  // Column-major: column j starts at q + j * m.
  auto apply = [m](const double* v, double tau, Eigen::Index j0, double* col) {
    // col(j0:m) -= tau * v * (v' col(j0:m)), v = [1; v(1:)]
    double s = col[j0];
    for (Eigen::Index i = j0 + 1; i < m; ++i) s += v[i] * col[i];
    s *= tau;
    col[j0] -= s;
    for (Eigen::Index i = j0 + 1; i < m; ++i) col[i] -= s * v[i];
  };
  for (Eigen::Index j = 0; j < k; ++j) {
    double* x = q + j * m;
    const double alpha = x[j];
    double tail = 0;
    for (Eigen::Index i = j + 1; i < m; ++i) tail += x[i] * x[i];
    if (tail <= std::numeric_limits<double>::min()) continue;  // nothing to reflect
    const double beta = -std::copysign(std::sqrt(alpha * alpha + tail), alpha);
    const double tau = (beta - alpha) / beta;
    const double inv = 1.0 / (alpha - beta);
    for (Eigen::Index i = j + 1; i < m; ++i) x[i] *= inv;
    x[j] = beta;
    for (Eigen::Index jj = j + 1; jj < k; ++jj) apply(x, tau, j, q + jj * m);
    apply(x, tau, j, c);
  }
}

bool FullRankLeastSquares::Solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                 Eigen::VectorXd* z) {
  const Eigen::Index k = a.cols();
  if (k == 0 || a.rows() < k || b.size() != a.rows()) return false;
  scale_.setOnes(k);
  if (scale_columns_) {
    for (Eigen::Index j = 0; j < k; ++j) {
      scale_[j] = a.col(j).norm();
      if (scale_[j] == 0) return false;
    }
  }
  scaled_.noalias() = a * scale_.cwiseInverse().asDiagonal();
  rhs_ = b;
  const bool loops = k <= kLoopColumns;
  if (loops) {
    FactoriseByLoops(k);
  } else {
    qr_.compute(scaled_);
    qr_.householderQ().setLength(k).adjoint().applyThisOnTheLeft(rhs_, workspace_);
  }
  const Eigen::MatrixXd& factor = loops ? scaled_ : qr_.matrixQR();
  const auto upper = factor.topLeftCorner(k, k);
  double r_norm2 = 0;
  for (Eigen::Index j = 0; j < k; ++j) {
    if (!(std::abs(upper(j, j)) > 0)) return false;
    r_norm2 += upper.col(j).head(j + 1).squaredNorm();
  }
  // First a cheap bound on ||R^-1||_F (Higham, Accuracy and Stability of
  // Numerical Algorithms, 2nd ed., section 8.3): |R^-1| <= M(R)^-1 entrywise,
  // M(R) the comparison matrix (|r_ii| on the diagonal, -|r_ij| above), so
  // ||R^-1||_inf <= ||M(R)^-1 e||_inf, ||R^-1||_1 <= ||M(R)^-T e||_inf, and
  // ||R^-1||_F <= sqrt(k ||R^-1||_1 ||R^-1||_inf). Two triangular solves with
  // one right-hand side each; when the bound proves the rank the exact norm
  // would too. Otherwise (the bound can be pessimistic) ||R^-1||_F itself.
  // Both solves in column (axpy) form: independent updates, no chain of
  // dependent sums.
  bound_.setOnes(k);
  for (Eigen::Index l = k - 1; l >= 0; --l) {  // M(R) y = e, backwards
    bound_[l] /= std::abs(upper(l, l));
    const double y = bound_[l];
    const double* column = upper.data() + l * upper.outerStride();
    for (Eigen::Index i = 0; i < l; ++i) bound_[i] += std::abs(column[i]) * y;
  }
  const double norm_inf = bound_.maxCoeff();
  bound_.setOnes(k);
  for (Eigen::Index l = 0; l < k; ++l) {  // M(R)' y = e, forwards
    bound_[l] /= std::abs(upper(l, l));
    const double y = bound_[l];
    for (Eigen::Index i = l + 1; i < k; ++i) bound_[i] += std::abs(upper(l, i)) * y;
  }
  const double norm_1 = bound_.maxCoeff();
  double r_inverse_norm2 = static_cast<double>(k) * norm_1 * norm_inf;
  if (!(tolerance_ * std::sqrt(r_norm2 * r_inverse_norm2) < 1.0)) {
    r_inverse_.setIdentity(k, k);
    upper.triangularView<Eigen::Upper>().solveInPlace(r_inverse_);
    r_inverse_norm2 = r_inverse_.squaredNorm();
    if (!(tolerance_ * std::sqrt(r_norm2 * r_inverse_norm2) < 1.0)) return false;
  }
  // z = D^-1 R^-1 (Q' b)(1:k)
  upper.triangularView<Eigen::Upper>().solveInPlace(rhs_.head(k));
  z->resize(k);
  *z = rhs_.head(k).cwiseQuotient(scale_);
  return z->allFinite();
}

}  // namespace femup
