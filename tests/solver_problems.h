// Test fixtures shared by the solver tests: a matrix of standard normal draws
// from a fixed seed (the same numbers for the same seed on every run), and a
// linear problem with its unknowns named.
#pragma once

#include <Eigen/Dense>
#include <random>
#include <string>

#include "femup/problems/linear_problem.h"

namespace femup {
namespace fixtures {

// rows x cols entries of N(0, 1), drawn in storage (column-major) order from a
// std::mt19937_64 seeded with `seed`.
inline Eigen::MatrixXd RandomGaussian(int rows, int cols, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd a(rows, cols);
  for (int i = 0; i < a.size(); ++i) a.data()[i] = g(rng);
  return a;
}

// min ||A x - b|| over x, the unknowns named x1, x2, ...
inline LinearProblem NamedProblem(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  LinearProblem p;
  p.A = a;
  p.b = b;
  for (int j = 0; j < a.cols(); ++j) p.names.push_back("x" + std::to_string(j + 1));
  return p;
}

}  // namespace fixtures
}  // namespace femup
