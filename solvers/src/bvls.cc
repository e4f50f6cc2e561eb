#include "femup/solvers/bvls.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "femup/errors.h"
#include "femup/solvers/kkt.h"
#include "linear_common.h"

namespace femup {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Orthonormal basis of null(E) (all of R^n when E has no row).
Eigen::MatrixXd NullSpace(const Eigen::MatrixXd& e, int n) {
  if (e.rows() == 0) return Eigen::MatrixXd::Identity(n, n);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(e, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  int rank = 0;
  const double tol = s.size() > 0 ? 1e-12 * s[0] * std::max(e.rows(), e.cols()) : 0.0;
  while (rank < s.size() && s[rank] > tol) ++rank;
  return svd.matrixV().rightCols(n - rank);
}

struct ActiveSet {
  Eigen::VectorXd x;
  std::vector<int> state;  // -1 at lower bound, +1 at upper, 0 free
  int iterations = 0;
  bool converged = false;
};

// min 0.5 ||A x - b||^2  s.t.  E x = e (kept by every step),  l <= x <= u,
// from a feasible x. Steps solve the free unknowns' least-squares problem in
// null(E_F) (minimum-norm step when that is rank deficient).
ActiveSet SolveActiveSet(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                         const Eigen::MatrixXd& e, const Eigen::VectorXd& l,
                         const Eigen::VectorXd& u, Eigen::VectorXd x,
                         int max_iterations) {
  const int n = static_cast<int>(a.cols());
  ActiveSet out;
  out.state.assign(n, 0);
  for (int j = 0; j < n; ++j) {
    if (x[j] <= l[j]) {
      x[j] = l[j];
      out.state[j] = -1;
    } else if (x[j] >= u[j]) {
      x[j] = u[j];
      out.state[j] = 1;
    }
  }
  // Multiplier sign tolerance, relative to the gradient's scale.
  const double gscale =
      (a.transpose() * b).cwiseAbs().maxCoeff() + a.cwiseAbs().maxCoeff() * 1e-300;
  const double mtol = 1e-12 * std::max(gscale, std::numeric_limits<double>::min());
  bool at_subspace_minimum = false;
  int last_freed = -1;
  for (out.iterations = 0; out.iterations < max_iterations; ++out.iterations) {
    std::vector<int> f;
    for (int j = 0; j < n; ++j) {
      if (out.state[j] == 0) f.push_back(j);
    }
    const int nf = static_cast<int>(f.size());
    if (!at_subspace_minimum && nf > 0) {
      Eigen::MatrixXd af(a.rows(), nf), ef(e.rows(), nf);
      for (int k = 0; k < nf; ++k) {
        af.col(k) = a.col(f[k]);
        ef.col(k) = e.col(f[k]);
      }
      const Eigen::MatrixXd nsp = NullSpace(ef, nf);
      const Eigen::VectorXd rhs = b - a * x;
      Eigen::VectorXd step = Eigen::VectorXd::Zero(nf);
      if (nsp.cols() > 0) {
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(af * nsp);
        step = nsp * cod.solve(rhs);
      }
      double alpha = 1.0;
      int block = -1, side = 0;
      for (int k = 0; k < nf; ++k) {
        const int j = f[k];
        if (step[k] < 0 && std::isfinite(l[j])) {
          const double t = (l[j] - x[j]) / step[k];
          if (t < alpha) alpha = t, block = j, side = -1;
        } else if (step[k] > 0 && std::isfinite(u[j])) {
          const double t = (u[j] - x[j]) / step[k];
          if (t < alpha) alpha = t, block = j, side = 1;
        }
      }
      alpha = std::max(alpha, 0.0);
      for (int k = 0; k < nf; ++k) x[f[k]] += alpha * step[k];
      if (block >= 0) {
        x[block] = side < 0 ? l[block] : u[block];
        out.state[block] = side;
        if (block == last_freed && alpha == 0.0) {
          // Freeing that bound does not help (degenerate): stop here and let the
          // KKT check judge the point.
          break;
        }
        continue;
      }
      at_subspace_minimum = true;
    }
    // Multipliers at the subspace minimum: gradient g = A'(A x - b) = E' mu + z.
    const Eigen::VectorXd g = a.transpose() * (a * x - b);
    Eigen::VectorXd mu = Eigen::VectorXd::Zero(e.rows());
    if (e.rows() > 0 && nf > 0) {
      Eigen::MatrixXd eft(nf, e.rows());
      Eigen::VectorXd gf(nf);
      for (int k = 0; k < nf; ++k) {
        eft.row(k) = e.col(f[k]).transpose();
        gf[k] = g[f[k]];
      }
      mu = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(eft).solve(gf);
    }
    const Eigen::VectorXd z = g - e.transpose() * mu;
    int worst = -1;
    double worst_violation = mtol;
    for (int j = 0; j < n; ++j) {
      if (out.state[j] == 0 || l[j] == u[j]) continue;
      const double violation = out.state[j] < 0 ? -z[j] : z[j];
      if (violation > worst_violation) worst_violation = violation, worst = j;
    }
    if (worst < 0) {
      out.converged = true;
      break;
    }
    out.state[worst] = 0;
    last_freed = worst;
    at_subspace_minimum = false;
  }
  out.x = x;
  return out;
}

}  // namespace

LinearSolution BvlsSolver::Solve(const LinearProblem& problem) const {
  const internal::Stopwatch clock;
  const std::string invalid = problem.Validate();
  if (!invalid.empty()) throw InputError("linear problem", invalid);
  const int n = problem.num_unknowns();
  const WeightedSystem w = Weighted(problem);
  const std::vector<int> free = problem.FreeUnknowns();
  const int nf = static_cast<int>(free.size());

  // The free unknowns' problem: fixed values moved to the right-hand sides.
  Eigen::VectorXd xfixed = Eigen::VectorXd::Zero(n);
  for (const auto& [i, value] : problem.fixed) xfixed[i] = value;
  Eigen::MatrixXd a(w.A.rows(), nf), e(problem.equality_matrix.rows(), nf);
  Eigen::VectorXd l(nf), u(nf);
  for (int k = 0; k < nf; ++k) {
    a.col(k) = w.A.col(free[k]);
    if (e.rows() > 0) e.col(k) = problem.equality_matrix.col(free[k]);
    l[k] = problem.lower.size() > 0 ? problem.lower[free[k]] : -kInf;
    u[k] = problem.upper.size() > 0 ? problem.upper[free[k]] : kInf;
  }
  const Eigen::VectorXd b = w.b - w.A * xfixed;
  const Eigen::VectorXd d =
      e.rows() > 0
          ? Eigen::VectorXd(problem.equality_rhs - problem.equality_matrix * xfixed)
          : Eigen::VectorXd();

  LinearSolution solution;
  Eigen::VectorXd start(nf);
  for (int k = 0; k < nf; ++k) start[k] = std::clamp(0.0, l[k], u[k]);
  if (problem.prior.size() > 0) {
    for (int k = 0; k < nf; ++k)
      start[k] = std::clamp(problem.prior[free[k]], l[k], u[k]);
  }
  int iterations = 0;
  if (e.rows() > 0) {
    // Phase 1: a point of the box closest to C x = d (bounded least squares).
    const ActiveSet phase1 = SolveActiveSet(e, d, Eigen::MatrixXd(0, nf), l, u, start,
                                            options_.max_iterations);
    iterations += phase1.iterations;
    const double violation = (e * phase1.x - d).norm();
    if (violation > 1e-9 * (1.0 + d.norm() + e.norm() * phase1.x.norm())) {
      solution.x = xfixed;
      for (int k = 0; k < nf; ++k) solution.x[free[k]] = phase1.x[k];
      solution.residual = problem.A * solution.x - problem.b;
      solution.summary.status = SolverStatus::kInfeasible;
      std::ostringstream msg;
      msg << "bvls: no x within the bounds satisfies the equalities (least violation |C "
             "x - "
             "d| = "
          << violation << ")";
      solution.summary.message = msg.str();
      solution.summary.iterations = iterations;
      solution.summary.time_seconds = clock.Seconds();
      return solution;
    }
    start = phase1.x;
  }
  const ActiveSet result = SolveActiveSet(a, b, e, l, u, start, options_.max_iterations);
  iterations += result.iterations;

  solution.x = xfixed;
  for (int k = 0; k < nf; ++k) solution.x[free[k]] = result.x[k];
  solution.residual = problem.A * solution.x - problem.b;
  const Eigen::VectorXd weighted_residual = w.A * solution.x - w.b;
  solution.summary.cost = 0.5 * weighted_residual.squaredNorm();
  solution.summary.iterations = iterations;

  // Linearised uncertainty with the active bounds held: the least-squares map of
  // the unknowns off their bounds within the equalities.
  std::vector<int> off;
  for (int k = 0; k < nf; ++k) {
    if (result.state[k] == 0) off.push_back(k);
  }
  Eigen::MatrixXd aoff(a.rows(), off.size()), eoff(e.rows(), off.size());
  for (std::size_t k = 0; k < off.size(); ++k) {
    aoff.col(k) = a.col(off[k]);
    eoff.col(k) = e.col(off[k]);
  }
  const Eigen::MatrixXd nsp = NullSpace(eoff, static_cast<int>(off.size()));
  Eigen::MatrixXd x_map = Eigen::MatrixXd::Zero(n, a.rows());
  int rank = 0;
  if (nsp.cols() > 0) {
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(aoff * nsp);
    cod.setThreshold(options_.relative_rank_tolerance);
    rank = static_cast<int>(cod.rank());
    const Eigen::MatrixXd local = nsp * cod.pseudoInverse();
    for (std::size_t k = 0; k < off.size(); ++k) x_map.row(free[off[k]]) = local.row(k);
  }
  internal::FillUncertainty(problem, x_map, weighted_residual, rank,
                            options_.confidence_level, &solution);
  if (off.size() < static_cast<std::size_t>(nf))
    solution.summary.warnings.push_back(
        "the covariance holds the active bounds fixed; it ignores that a bound may "
        "release");

  // Optimality, checked independently of the iteration above.
  const Eigen::VectorXd gradient = w.A.transpose() * weighted_residual;
  const double scale = (w.A.transpose() * w.b).cwiseAbs().maxCoeff();
  const KktReport kkt = CheckKkt(solution.x, gradient, problem.lower, problem.upper,
                                 problem.equality_matrix, problem.equality_rhs,
                                 problem.fixed, scale > 0 ? scale : 1.0);
  solution.summary.kkt_residual = kkt.residual();
  std::ostringstream msg;
  const int at_bounds = nf - static_cast<int>(off.size());
  if (!result.converged || kkt.residual() > options_.kkt_tolerance) {
    solution.summary.status = SolverStatus::kNoConvergence;
    msg << "bvls: " << (result.converged ? "stopped" : "iteration limit reached")
        << " short of the optimum (" << kkt.Describe() << ")";
  } else if (rank < static_cast<int>(nsp.cols())) {
    solution.summary.status = SolverStatus::kMinimumNorm;
    msg << "bvls: optimal, but the unknowns off their bounds are rank deficient (rank "
        << rank << " of " << nsp.cols() << "): the answer is one of many";
  } else {
    solution.summary.status = SolverStatus::kSolved;
    msg << "bvls: optimal after " << iterations << " active-set iterations; " << at_bounds
        << " unknown(s) at a bound";
  }
  solution.summary.message = msg.str();
  solution.summary.time_seconds = clock.Seconds();
  return solution;
}

}  // namespace femup
