// Private: the sparse path of the modal analysis (shift-invert Lanczos on a
// sparse Cholesky factorisation). SolveModes (modal.cc) dispatches here.
#pragma once

#include "femup/core/fe/model.h"
#include "femup/core/linalg/modal.h"

namespace femup {
namespace internal {

// Lowest `options.num_modes` eigenpairs of K phi = lambda M phi nearest above
// options.shift, by shift-invert Lanczos on a sparse Cholesky factorisation of
// K - shift*M (CHOLMOD LL', supernodal when the analysed factorisation needs at
// least `supernodal_switch` flops per entry of L, simplicial below). Where that
// factorisation exists (the shift below the spectrum), the Lanczos process runs
// on the standard symmetric operator L^{-1} P M P' L^{-T} (Spectra
// SymEigsSolver: one product with M a step, Euclidean orthogonalisation);
// where K - shift*M is indefinite (the shift inside the spectrum), on
// SimplicialLDLT with the M-inner product (SymGEigsShiftSolver,
// GEigsMode::ShiftInvert). M is checked to be positive definite by its own
// factorisation (a diagonal M is read), beside K - shift*M's on
// options.threads threads from 10^4 DOFs.
//
// Only the lower triangles of K and M are read. Eigenvalues are ascending; the
// shapes are M-normalised (phi' M phi = 1) with the sign fixed so that the entry
// of largest magnitude is positive. Uses options.num_modes (1 <= k <= n - 1),
// shift, tolerance and max_iterations; the Krylov dimension is
// min(n, max(2k + 1, 20)).
//
// Throws InputError("modal analysis", ...) when the sizes differ, k is out of
// range, an entry is not finite, M is not positive definite ("mass matrix is not
// positive definite"), K - shift*M is singular to working precision (the shift
// is an eigenvalue, e.g. shift = 0 on a free-free model) or cannot be
// factorised stably, fewer than k eigenvalues lie above the shift (counted by
// Sylvester's law of inertia), or the iteration does not converge within
// options.max_iterations restarts.
// The default `supernodal_switch`: see sparse_eigen.cc for its measurement.
extern const double kSupernodalSwitch;

Modes SolveModesSparse(const SparseMatrix& K, const SparseMatrix& M,
                       const EigenOptions& options,
                       double supernodal_switch = kSupernodalSwitch);

}  // namespace internal
}  // namespace femup
