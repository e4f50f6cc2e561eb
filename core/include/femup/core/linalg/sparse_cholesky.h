// A sparse Cholesky factorisation P A P' = L L' of a symmetric positive
// definite matrix (CHOLMOD, fill-reducing ordering by nested dissection or
// AMD), with the half solve W = L^-1 P B for a SPARSE right-hand side B whose
// cost is that of the columns of L reachable from B's pattern (the
// elimination-tree ancestors of its rows), not that of n.
//
// Its use: weighted inner products B' A^-1 C = (L^-1 P B)' (L^-1 P C) of
// columns with small support, as the "all FEM modes" weighting M^-1 of the
// correction-factor equations (problems/normal_correction_system.h), without
// ever forming A^-1 or solving for dense columns.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "femup/core/fe/model.h"

namespace femup {

struct SparseCholeskyOptions {
  enum class Ordering {
    kAuto,              // CHOLMOD's default choice (AMD, METIS if AMD fills badly)
    kAmd,               // approximate minimum degree
    kNestedDissection,  // METIS nested dissection (short elimination tree paths:
                        // sparse half-solves stay sparse)
  };
  Ordering ordering = Ordering::kNestedDissection;
  // Name used in error messages ("model.mass").
  std::string name = "matrix";
  // Empty, or one group per row (0-based, e.g. the node a DOF belongs to):
  // with nested dissection the ordering is then found on the graph of the
  // groups (METIS on a graph 6 times smaller for a space frame's 6-DOF nodes)
  // and each group's rows are eliminated together, in their own order. A size
  // other than the matrix's or a negative group: InputError.
  std::vector<int> groups;
  // Threads of the sparse half-solve with several columns (blocks of columns
  // on each): 0 = one per core. The result is the same bits for any count.
  // Negative: InputError.
  int threads = 0;
};

// Summary of the factor.
struct SparseCholeskyInfo {
  long long n = 0;
  long long nnz_a = 0;  // entries of A's lower triangle
  long long nnz_l = 0;  // entries of L
  // Floating-point operations of the numerical factorisation for the ordering
  // chosen (CHOLMOD's count from its analysis: sum of the squares of L's
  // column counts, a simplicial LL').
  double flops = 0;
  double seconds_analyse = 0, seconds_factorise = 0;
};

class SparseCholesky {
 public:
  // Factorises A (only the lower triangle is read). Throws InputError naming
  // options.name when A is not square, holds a non-finite entry, or is not
  // positive definite (the message gives the DOF where the factorisation broke
  // down).
  explicit SparseCholesky(const SparseMatrix& a,
                          const SparseCholeskyOptions& options = {});
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  Eigen::Index size() const;
  const SparseCholeskyInfo& info() const;

  // x = A^-1 b for dense b (columns).
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& b) const;
  // y = L^-1 P b for dense b (columns): then b' A^-1 c = y_b' y_c.
  Eigen::MatrixXd HalfSolve(const Eigen::MatrixXd& b) const;
  // W = L^-1 P B for sparse B, column by column, touching only the columns of
  // L reachable from each column's pattern (the several-right-hand-side solve
  // below with one of them). Each call has its own work space, so calls may
  // run concurrently.
  SparseMatrix HalfSolve(const SparseMatrix& b) const;
  // W_j = L^-1 P B_j for several right-hand sides B_j that share one sparsity
  // pattern (the same outer and inner index arrays; values may differ, zeros
  // included): each column's reach in L is found once for all of them and L is
  // read once per column for all of them. The W_j share one pattern too.
  // Blocks of columns run on `threads` threads (SparseCholeskyOptions).
  // Throws InputError when the B_j differ in size or pattern.
  std::vector<SparseMatrix> HalfSolve(const std::vector<SparseMatrix>& b) const;
  // The floating-point operations of a half solve whose result has w's
  // pattern (its rows are L's columns the substitution ran through), for
  // `right_hand_sides` right-hand sides of that pattern: per entry in row c, a
  // division and a multiplication and a subtraction for each of the other
  // entries of L's column c, per right-hand side. InputError when w's rows are
  // not the factor's size or right_hand_sides < 1.
  double HalfSolveFlops(const SparseMatrix& w, int right_hand_sides) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace femup
