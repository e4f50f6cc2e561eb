// Private: the sparse path of the modal analysis (shift-invert Lanczos on a
// sparse Cholesky factorisation). SolveModes (modal.cc) dispatches here.
#pragma once

#include "femup/core/fe/model.h"
#include "femup/core/linalg/modal.h"

namespace femup {
namespace internal {

// Lowest `options.num_modes` eigenpairs of K phi = lambda M phi nearest above
// options.shift, by shift-invert Lanczos (Spectra SymGEigsShiftSolver,
// GEigsMode::ShiftInvert) on a sparse Cholesky factorisation of K - shift*M
// (CHOLMOD LL', supernodal when the analysed factorisation needs at least
// `supernodal_switch` flops per entry of L, simplicial below; SimplicialLDLT
// when K - shift*M is not positive definite, i.e. when the shift lies inside
// the spectrum). One symbolic analysis serves K - shift*M and the check that M
// is positive definite (a diagonal M is checked without factorising).
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
