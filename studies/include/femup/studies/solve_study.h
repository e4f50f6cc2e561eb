// A general linear inverse problem from files, on any linear solver: the
// framework is not tied to correction factors. A and b (and optionally bounds,
// a reference solution) are read from Matrix Market (.mtx) or CSV (.csv:
// numbers separated by commas, one matrix row per line, an optional header
// line of names for A's columns).
#pragma once

#include <string>
#include <vector>

#include "femup/problems/linear_problem.h"
#include "femup/solvers/linear_solver.h"

namespace femup {

// A dense matrix from .mtx or .csv; `names` (may be null) receives a CSV
// header's names. Throws InputError naming the file, line and field. NaN is
// refused; -inf/inf only where `allow_infinite` (bounds), in CSV files.
Eigen::MatrixXd ReadMatrixFile(const std::string& path, std::vector<std::string>* names,
                               bool allow_infinite = false);

struct SolveFiles {
  std::string a, b;          // required
  std::string lower, upper;  // optional vectors (n)
  std::string truth;         // optional reference solution (n), for the report
  double data_sigma = 0;     // > 0: the noise standard deviation of b (weights 1/sigma)
};

struct SolveResult {
  LinearProblem problem;
  std::string solver;
  LinearSolution solution;
  Eigen::VectorXd truth;  // empty when not given
};

SolveResult RunSolve(const SolveFiles& files, const std::string& solver,
                     const LinearSolverOptions& options);

}  // namespace femup
