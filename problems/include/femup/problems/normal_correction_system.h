// The correction-factor equations of a large model, compressed to one row per
// unknown. For every measured mode (lambda_j, phi_j) with shapes on all DOFs,
// the physical residual of the updated model is linear in the factors d:
//   K~ phi_j - lambda_j M~ phi_j = F_j - Z_j d  (as in correction_system.h),
// and the stacked form of correction_system.h with ALL FEM modes weights it by
// M^-1 (Phi Phi' = M^-1, method.md). This builds the same least-squares problem
// without the eigenbasis, from a sparse Cholesky factor of M:
//   G = sum_j Z_j' M^-1 Z_j,  h = sum_j Z_j' M^-1 F_j,  f = sum_j F_j' M^-1 F_j
// (with P M P' = L L', G = sum_j W_j' W_j for W_j = L^-1 P Z_j: a sparse
// triangular solve per column that touches only the elimination-tree
// ancestors of the column's DOFs, sparse_cholesky.h), and returns A (n x n)
// and b with A'A = G, A'b = h, so that for every x
//   ||A x - b||^2 + residual_offset = sum_j (Z_j x - F_j)' M^-1 (Z_j x - F_j),
// source_rows = (number of DOFs) x (number of modes). Memory is O(n^2 + nnz)
// instead of O(DOFs x modes x n).
//
// The price of the normal equations: A's small singular values are accurate
// only to about sqrt(machine epsilon) times the largest (column-scaled). A is
// the square root of the column-scaled G by Cholesky with complete pivoting
// (LAPACK's dpstrf, stable on a semidefinite matrix); pivots at or below
// n * eps * max are dropped (zero rows) and counted in `dropped`. Use correction_system.h
// where the dense form fits in memory.
#pragma once

#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/linear_problem.h"

namespace femup {

struct NormalCorrectionStats {
  int dropped = 0;                // pivots of G's factor below the threshold
  double seconds_factorise = 0;   // sparse Cholesky of M (analysis included)
  double seconds_analyse = 0;     // of which the ordering and symbolic analysis
  double seconds_assembly = 0;    // Z_j, L^-1 P Z_j and G, factorisation included
  double seconds_half_solve = 0;  // W_j = L^-1 P Z_j, all modes
  double seconds_gram = 0;        // G += W_j' W_j, all modes
  double seconds_compress = 0;    // pivoted Cholesky of G and A from it
  long long nnz_l = 0;            // entries of M's Cholesky factor
  long long nnz_z = 0;            // entries of all Z_j together
  long long nnz_w = 0;            // entries of all L^-1 P Z_j together
  double flops_factorise = 0;     // of M's Cholesky factorisation (CHOLMOD's count)
  double flops_gram = 0;          // multiplications and additions of G's lower triangle
  double flops_half_solve = 0;    // of the half solves L^-1 P Z_j (HalfSolveFlops)
};

struct NormalCorrectionOptions {
  // Threads of the sparse half solves and of G's products (0 = one per core).
  // The system is the same bits for any count. Negative: InputError.
  int threads = 0;
};

// Throws InputError for shapes that are not on every DOF, a model without
// parameters, or no state; a mass matrix that is not positive definite;
// negative threads.
LinearProblem BuildNormalCorrectionSystem(const ParametrisedModel& model,
                                          const std::vector<ModalData>& states,
                                          NormalCorrectionStats* stats = nullptr,
                                          const NormalCorrectionOptions& options = {});

}  // namespace femup
