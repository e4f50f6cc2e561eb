#include "femup/solvers/bvls.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "femup/core/errors.h"
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

// min ||M s - r||, the minimum-norm s when M is rank deficient. Householder QR
// when its diagonal shows full column rank by a wide margin; otherwise (and for
// a wide M) the complete orthogonal decomposition, which decides the rank.
Eigen::VectorXd LeastSquares(const Eigen::MatrixXd& m, const Eigen::VectorXd& r) {
  if (m.cols() == 0) return Eigen::VectorXd(0);
  if (m.rows() >= m.cols()) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(m);
    const Eigen::VectorXd diagonal = qr.matrixQR().diagonal().cwiseAbs();
    constexpr double kMargin = 1e-8;  // far above the decomposition's n * epsilon
    if (diagonal.minCoeff() > kMargin * diagonal.maxCoeff()) return qr.solve(r);
  }
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(m).solve(r);
}

struct ActiveSet {
  Eigen::VectorXd x;
  std::vector<int> state;  // -1 at lower bound, +1 at upper, 0 free
  int iterations = 0;
  bool converged = false;
};

// min 0.5 ||A x - b||^2  s.t.  E x = e (kept by every step),  l <= x <= u,
// from a feasible x. Steps solve the free unknowns' least-squares problem in
// null(E_F) (minimum-norm step when that is rank deficient). A may be the
// triangular factor R of the problem's A = Q R with Q' b for b (same minimisers,
// same gradient A' (A x - b) = R' (R x - Q' b)).
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
      Eigen::MatrixXd af(a.rows(), nf);
      for (int k = 0; k < nf; ++k) af.col(k) = a.col(f[k]);
      const Eigen::VectorXd rhs = b - a * x;
      Eigen::VectorXd step = Eigen::VectorXd::Zero(nf);
      if (e.rows() == 0) {
        step = LeastSquares(af, rhs);
      } else {
        Eigen::MatrixXd ef(e.rows(), nf);
        for (int k = 0; k < nf; ++k) ef.col(k) = e.col(f[k]);
        const Eigen::MatrixXd nsp = NullSpace(ef, nf);
        if (nsp.cols() > 0) step = nsp * LeastSquares(af * nsp, rhs);
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
  if (const Invalid bad = problem.Validate())
    throw InputError("linear problem", bad.ToString());
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

  // A = Q R (Householder, thin) for a tall A: min ||A x - b|| and min ||R x - c||,
  // c = Q' b, have the same minimisers (the costs differ by ||b - Q c||^2, also
  // when A is rank deficient), so the iterations work on n x n instead of m x n.
  Eigen::MatrixXd r;
  Eigen::VectorXd c;
  if (a.rows() > nf && nf > 0) {
    const Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(a);  // in place
    r = qr.matrixQR().topRows(nf).triangularView<Eigen::Upper>();
    c = (qr.householderQ().adjoint() * b).head(nf);
    a.resize(0, 0);
  } else {
    r = std::move(a);
    c = b;
  }

  LinearSolution solution;
  // Start (as Stark and Parker's BVLS) from the unconstrained least-squares
  // answer clipped to the box: mostly the right active set already. Rank
  // deficient, the answer closest to the prior (clipped) or to 0.
  Eigen::VectorXd base(nf);
  for (int k = 0; k < nf; ++k) base[k] = std::clamp(0.0, l[k], u[k]);
  if (problem.prior.size() > 0) {
    for (int k = 0; k < nf; ++k) base[k] = std::clamp(problem.prior[free[k]], l[k], u[k]);
  }
  Eigen::VectorXd start;
  if (e.rows() == 0) {
    start = base + LeastSquares(r, c - r * base);
  } else {
    // Within the equalities: their point closest to `base`, then least squares
    // in null(C).
    const Eigen::VectorXd on_equalities =
        base +
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(e).solve(d - e * base);
    const Eigen::MatrixXd nsp = NullSpace(e, nf);
    start = on_equalities;
    if (nsp.cols() > 0) start += nsp * LeastSquares(r * nsp, c - r * on_equalities);
  }
  start = start.cwiseMax(l).cwiseMin(u);
  int iterations = 0;
  if (e.rows() > 0) {
    // Phase 1: a point of the box closest to C x = d (bounded least squares),
    // from the clipped start (its clipping may have left the equalities).
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
  const ActiveSet result = SolveActiveSet(r, c, e, l, u, start, options_.max_iterations);
  iterations += result.iterations;

  solution.x = xfixed;
  for (int k = 0; k < nf; ++k) solution.x[free[k]] = result.x[k];
  solution.residual = problem.A * solution.x - problem.b;
  const Eigen::VectorXd weighted_residual = w.A * solution.x - w.b;
  solution.summary.cost = 0.5 * weighted_residual.squaredNorm();
  solution.summary.iterations = iterations;

  // Linearised uncertainty with the active bounds held: the least-squares map of
  // the unknowns off their bounds within the equalities, x_off = N (A_off N)^+ b_w.
  // With A = Q R that map is N (R_off N)^+ Q', and as Q' Q = I the n-column
  // N (R_off N)^+ gives FillUncertainty the same X X' without any m x m work.
  std::vector<int> off;
  for (int k = 0; k < nf; ++k) {
    if (result.state[k] == 0) off.push_back(k);
  }
  Eigen::MatrixXd roff(r.rows(), off.size()), eoff(e.rows(), off.size());
  for (std::size_t k = 0; k < off.size(); ++k) {
    roff.col(k) = r.col(off[k]);
    eoff.col(k) = e.col(off[k]);
  }
  const Eigen::MatrixXd nsp = NullSpace(eoff, static_cast<int>(off.size()));
  Eigen::MatrixXd x_map = Eigen::MatrixXd::Zero(n, r.rows());
  int rank = 0;
  if (nsp.cols() > 0) {
    const Eigen::MatrixXd reduced = roff * nsp;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(reduced.rows(),
                                                                reduced.cols());
    cod.setThreshold(options_.relative_rank_tolerance);  // before the decomposition
    cod.compute(reduced);
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
