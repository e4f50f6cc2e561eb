// Plain least squares by the singular value decomposition of the column-scaled
// matrix of the free unknowns: the unique solution when A has full column rank,
// otherwise the minimum-norm one (in scaled variables), with a warning that
// names the directions the data cannot determine. The answer is then refined
// twice on the augmented system [I A; A' 0] [r; x] = [b; 0] with its residuals in
// long double, which recovers the digits a plain solve loses on ill-conditioned
// problems with a large residual (docs/validation.md: NIST's Wampler4 and 5).
#pragma once

#include <Eigen/QR>

#include "femup/solvers/linear_solver.h"

namespace femup {

class LstsqSolver : public LinearSolver {
 public:
  explicit LstsqSolver(const LinearSolverOptions& options) : options_(options) {}
  std::string name() const override { return "lstsq"; }
  LinearSolution Solve(const LinearProblem& problem) const override;

 private:
  LinearSolverOptions options_;
};

// Least squares of full column rank, for many problems of one size (a noise
// study's draws): lstsq's path without diagnostics. The column-scaled A is
// factorised by Householder QR (backward stable for least squares of full
// rank), and full column rank is proved with lstsq's own rule: R has A's
// singular values, s_max <= ||R||_F and s_min >= 1 / ||R^-1||_F, so
// tol * ||R||_F * ||R^-1||_F < 1 gives s_min > tol * s_max. Small matrices
// (at most kLoopColumns columns) are factorised by plain loops with the
// reflectors applied to b as they are made (LAPACK's dgeqr2 arithmetic): on a
// 20 x 12 matrix (the paper's noise draws) Eigen's HouseholderQR took 1.9 us
// against the loops' 1.0 us in a one-off timing driver, its time going to
// dispatching small products; larger ones by Eigen's blocked HouseholderQR. The work
// space is kept between calls: a solve of the same size as the last allocates nothing.
// Not thread-safe: one object per thread.
class FullRankLeastSquares {
 public:
  static constexpr int kLoopColumns = 32;

  FullRankLeastSquares(double relative_rank_tolerance, bool scale_columns)
      : tolerance_(relative_rank_tolerance), scale_columns_(scale_columns) {}
  // The minimiser of ||a z - b|| in *z; false (z unspecified) when a has fewer
  // rows than columns, a zero column (with scaling) or rank not provably full,
  // or the answer is not finite: the SVD path (LstsqSolver) then decides.
  bool Solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, Eigen::VectorXd* z);

 private:
  // R in the upper triangle of qr_ (k x k) and Q'b in rhs_, by loops.
  void FactoriseByLoops(Eigen::Index k);

  double tolerance_;
  bool scale_columns_;
  Eigen::VectorXd scale_, rhs_, workspace_, bound_;
  Eigen::MatrixXd scaled_, r_inverse_;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_;
};

}  // namespace femup
