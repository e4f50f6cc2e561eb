#include "gram_least_squares.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "femup/core/linalg/dense_kernels.h"
#include "femup/core/linalg/symmetric_spectrum.h"

namespace femup::internal {
namespace {

// Steps of refinement with long-double residuals, as lstsq's SVD route.
constexpr int kRefinementSteps = 2;

}  // namespace

double GramRankTolerance(double relative_tolerance, Eigen::Index unknowns) {
  return std::max(relative_tolerance, std::sqrt(static_cast<double>(unknowns) *
                                                std::numeric_limits<double>::epsilon()));
}

bool LeastSquaresByGram(const ReducedProblem& reduced, double relative_tolerance,
                        bool scale_columns, LeastSquaresDecomposition* out) {
  const Eigen::MatrixXd& a = reduced.A;
  const Eigen::Index n = a.cols();
  if (n == 0 || !a.allFinite()) return false;
  const Eigen::VectorXd scale = IdentifiabilityScale(a, scale_columns);
  const Eigen::MatrixXd scaled = a * scale.cwiseInverse().asDiagonal();
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(n, n);  // lower triangle used
  RankUpdateLower(scaled, 1.0, 0.0, gram);

  Eigen::VectorXd w;  // ascending
  if (!SymmetricEigenvalues(gram, &w)) return false;
  const double w_max = w[n - 1];
  if (!(w_max > 0) || !std::isfinite(w_max)) return false;
  Eigen::VectorXd s(n);  // descending
  for (Eigen::Index i = 0; i < n; ++i) s[i] = std::sqrt(std::max(w[n - 1 - i], 0.0));
  const double relative = GramRankTolerance(relative_tolerance, n);
  int rank = 0;
  while (rank < n && s[rank] > relative * s[0]) ++rank;
  // The threshold is at least sqrt(eps) > 1e-8, so a full-rank matrix here never
  // reaches the condition number (1e8) whose warning needs the weakest vector.
  const int wanted = static_cast<int>(n - rank);
  Eigen::VectorXd w_small;
  Eigen::MatrixXd v_small;  // ascending: column 0 the smallest
  if (!SmallestEigenpairs(gram, wanted, &w_small, &v_small)) return false;

  double unscaled = std::numeric_limits<double>::infinity();
  if (!scale_columns) {
    if (rank == n) unscaled = s[0] / s[n - 1];
  } else {
    // A' A = D G D: its eigenvalues, values only.
    Eigen::MatrixXd raw = scale.asDiagonal() * gram * scale.asDiagonal();
    Eigen::VectorXd raw_w;
    if (!SymmetricEigenvalues(std::move(raw), &raw_w)) return false;
    const double top = raw_w[n - 1], bottom = raw_w[0];
    const double floor = static_cast<double>(n) * std::numeric_limits<double>::epsilon();
    if (top > 0 && bottom > floor * top) unscaled = std::sqrt(top / bottom);
  }
  out->identifiability =
      AnalyseIdentifiability(a, s, v_small.rowwise().reverse(), unscaled, reduced.names,
                             reduced.groups, relative, scale_columns);
  out->rank = out->identifiability.rank;
  if (out->rank != rank) return false;  // the report counts as this route does

  // G + w_max N N' on the dropped directions N, and P = I - N N'.
  const Eigen::MatrixXd null = v_small.leftCols(n - rank);
  if (null.cols() > 0) gram.selfadjointView<Eigen::Lower>().rankUpdate(null, w_max);
  // L L' of it in gram's lower triangle.
  if (!CholeskyLower(gram)) return false;
  auto project = [&null](Eigen::MatrixXd x) {
    if (null.cols() > 0) x.noalias() -= null * (null.transpose() * x);
    return x;
  };
  auto pseudo_solve = [&](const Eigen::VectorXd& g) -> Eigen::VectorXd {
    Eigen::VectorXd x = project(g);
    gram.triangularView<Eigen::Lower>().solveInPlace(x);
    gram.triangularView<Eigen::Lower>().adjoint().solveInPlace(x);
    return project(x);
  };

  // z = D^-1 G^+ D^-1 A' b, then refined: z += D^-1 G^+ D^-1 A' (b - A z) with
  // the residual and A' r in long double.
  using VectorLd = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
  using MatrixLd = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  Eigen::VectorXd z = pseudo_solve(scaled.transpose() * reduced.b).cwiseQuotient(scale);
  const MatrixLd al = a.cast<long double>();
  const VectorLd bl = reduced.b.cast<long double>();
  for (int step = 0; step < kRefinementSteps; ++step) {
    const VectorLd r = bl - al * z.cast<long double>();
    const Eigen::VectorXd g = (al.transpose() * r).cast<double>().cwiseQuotient(scale);
    z += pseudo_solve(g).cwiseQuotient(scale);
  }
  if (!z.allFinite()) return false;
  out->z = std::move(z);
  // Cov(z) / sigma^2 = D^-1 P (L L')^-1 P D^-1 = (D^-1 P L^-T)(D^-1 P L^-T)'.
  if (!InvertLowerTriangular(gram)) return false;
  Eigen::MatrixXd root = gram.triangularView<Eigen::Lower>().transpose();
  out->z_root = scale.cwiseInverse().asDiagonal() * project(std::move(root));
  return out->z_root.allFinite();
}

}  // namespace femup::internal
