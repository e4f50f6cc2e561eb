// Linear solvers: one interface, one factory. A solver takes a LinearProblem
// and returns a LinearSolution whose summary carries the outcome; only unusable
// input (sizes, NaN, unknown names, lower > upper) throws InputError, before any
// work.
//
//   lstsq     least squares by SVD of the column-scaled matrix, refined with
//             residuals in long double; minimum-norm when rank deficient. Fixed
//             values and equalities (eliminated exactly). A large compressed
//             problem (source_rows > 0) goes through its Gram matrix instead
//             (gram_min_unknowns below).
//   tsvd      truncated SVD; the truncation index given or chosen (GCV, L-curve,
//             discrepancy). Fixed values and equalities.
//   tikhonov  min ||A x - b||^2 + lambda^2 ||L (x - x0)||^2, L the identity or a
//             difference operator; lambda given or chosen (L-curve corner, GCV,
//             discrepancy principle, quasi-optimality). Fixed values and equalities.
//   bvls      bounded least squares by a primal active-set method (Stark-Parker
//             BVLS generalised to equalities); fixed values, equalities, bounds.
//   ceres     the same bounded problem on Ceres (augmented Lagrangian for equalities).
//   ipopt     the same bounded problem on Ipopt (equalities native).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/invalid.h"
#include "femup/problems/linear_problem.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/regularisation.h"
#include "femup/solvers/solver_summary.h"

namespace femup {

struct LinearSolverOptions {
  // Singular values below relative_rank_tolerance * s_max (of the column-scaled
  // matrix) count as zero.
  double relative_rank_tolerance = 1e-10;
  // Scale the columns of A to unit norm before the decomposition (the answer is
  // mapped back). Keeps the rank decision independent of parameter units.
  bool scale_columns = true;
  // tsvd: number of singular values kept; 0 = chosen by `regularisation`.
  int truncation = 0;
  RegularisationOptions regularisation;  // tikhonov and tsvd
  // Iterative solvers (bvls, ceres, ipopt).
  int max_iterations = 1000;
  double kkt_tolerance = 1e-8;  // relative; answers above it are not "solved"
  double confidence_level = 0.95;
  // false: the caller needs only x, the residual and the summary (many repeated
  // solves, e.g. a noise study's draws). lstsq then skips the identifiability
  // analysis, the covariance and the intervals, and solves a provably
  // full-column-rank system by Householder QR with column pivoting (on the
  // column-scaled matrix, no refinement: the answer agrees with the SVD path's
  // to about cond^2 * machine epsilon); anything else goes the SVD path. Other
  // solvers ignore it.
  bool diagnostics = true;
  // lstsq: a compressed problem (LinearProblem::source_rows > 0, such as the
  // M^-1-weighted correction system) with at least this many free unknowns is
  // solved through its Gram matrix instead of an SVD of A: its eigenvalues,
  // the eigenvectors of the few below the rank threshold, and a Cholesky
  // factor (about 3 n^3 flops against 22 n^3). A compressed A carries only the
  // Gram matrix's accuracy, so nothing is lost; the rank threshold there is
  // max(relative_rank_tolerance, sqrt(n eps)), below which a singular value is
  // rounding. Must be >= 1.
  int gram_min_unknowns = 200;
  Invalid Validate() const;  // ok when valid, else the field and what is wrong
};

struct LinearSolution {
  Eigen::VectorXd x;                // every unknown, fixed ones at their values
  Eigen::VectorXd residual;         // A x - b (unweighted)
  Identifiability identifiability;  // of the free-unknown system that was solved
  // Linearised uncertainty from the data noise (all unknowns; zero rows and
  // columns for fixed ones): the covariance of the estimator (for regularised
  // solvers, of the regularised estimator: it excludes the bias), standard
  // errors and a confidence interval at `confidence_level` (Student t with
  // m - n degrees of freedom when the noise is estimated from the residual,
  // normal when it is known). Empty when it cannot be computed.
  Eigen::MatrixXd covariance;
  Eigen::VectorXd standard_error, interval_lower, interval_upper;
  double confidence_level = 0.95;
  bool noise_estimated = true;  // false when the problem gave weights or a covariance
  // Regularised solvers: the resolution matrix R (x_reg = R x_true + noise term, so
  // (R - I) x_true is the bias) and the first-order bias estimate (R - I) x.
  Eigen::MatrixXd resolution;
  Eigen::VectorXd bias_estimate;
  RegularisationReport regularisation;  // tikhonov and tsvd: the parameter choice
  SolverSummary summary;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  virtual LinearSolution Solve(const LinearProblem& problem) const = 0;
};

// Names the factory knows: lstsq, tsvd, tikhonov, bvls, ceres, ipopt.
std::vector<std::string> AvailableLinearSolvers();
// Throws InputError("solver.name", ...) for an unknown name and
// InputError("solver.<field>", ...) for invalid options.
std::unique_ptr<LinearSolver> CreateLinearSolver(const std::string& name,
                                                 const LinearSolverOptions& options = {});

}  // namespace femup
