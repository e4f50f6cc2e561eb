// The bounded dense random least-squares problem that solvers_bench.cc and
// peer_compare.cc share, so that the Google Benchmark numbers and the scipy
// comparison time the same problems.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <string>

#include "femup/problems/linear_problem.h"

namespace femup_bench {

// A (m x n) with independent N(0, 1) entries, b = A x_true + 0.1 e with x_true
// and e N(0, 1), box -1 <= x <= 1. About a third of x_true lies outside the box,
// so roughly that fraction of the bounds is active at the optimum. Draws A
// (column-major), then x_true, then e, from std::mt19937_64(seed): the same
// problem for a seed on one platform (std::normal_distribution is not specified
// bit for bit across standard libraries).
inline femup::LinearProblem RandomBoundedProblem(int m, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto draw = [&](Eigen::Index rows, Eigen::Index cols) {
    Eigen::MatrixXd out(rows, cols);
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] = normal(rng);
    return out;
  };
  femup::LinearProblem p;
  p.A = draw(m, n);
  const Eigen::VectorXd x_true = draw(n, 1);
  p.b = p.A * x_true + 0.1 * draw(m, 1);
  for (int j = 0; j < n; ++j) p.names.push_back("x" + std::to_string(j + 1));
  p.lower = Eigen::VectorXd::Constant(n, -1.0);
  p.upper = Eigen::VectorXd::Constant(n, 1.0);
  return p;
}

// Unknowns of `x` on a bound of `p` (within 1e-9, as the KKT check counts them).
inline int ActiveBounds(const femup::LinearProblem& p, const Eigen::VectorXd& x) {
  int count = 0;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    if (x[j] <= p.lower[j] + 1e-9 || x[j] >= p.upper[j] - 1e-9) ++count;
  }
  return count;
}

}  // namespace femup_bench
