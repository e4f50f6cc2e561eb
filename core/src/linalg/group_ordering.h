// Private: a fill-reducing ordering from the graph of groups of rows (the
// nodes of a finite element model, each holding several DOFs), used by the
// sparse Cholesky factor (sparse_cholesky.h) and the sparse eigensolver
// (sparse_eigen.cc). METIS on the group graph costs a fraction of METIS on
// the rows (a 6-DOF node graph has 6 times fewer vertices and about 36 times
// fewer edges), and the fill is about the same: a separator that cuts a node
// takes all its DOFs anyway. Also the CHOLMOD view of a lower triangle that the
// ordering and the sparse Cholesky factor both hand to CHOLMOD.
#pragma once

#include <cholmod.h>

#include <mutex>
#include <vector>

#include "femup/core/fe/model.h"

namespace femup::internal {

// A CHOLMOD header (no copy) over the lower triangle of a symmetric matrix of
// `rows` rows held as compressed columns: column pointers p (rows + 1), row
// indices i, values x, or a pattern when x is null. CHOLMOD reads it in place.
cholmod_sparse CholmodLowerView(int rows, int* p, int* i, double* x);

// A fill-reducing permutation of the rows of the symmetric matrix whose lower
// triangle `lower` holds (compressed), from a nested dissection of the graph
// of `groups` (one index >= 0 per row): the groups are ordered by METIS
// (through CHOLMOD, on `common`), then each group's rows in turn, in ascending
// order. perm[k] is the row eliminated k-th. Empty when METIS is not there or
// fails (the caller then orders the rows itself).
std::vector<int> GroupOrdering(const SparseMatrix& lower, const std::vector<int>& groups,
                               cholmod_common* common);

// The lock that every call which may reach METIS holds (cholmod_metis, and
// cholmod_analyze where CHOLMOD may choose nested dissection). METIS 5.1 draws
// its random numbers from one generator in global variables (GKlib's), seeded
// afresh by every ordering and not locked: two orderings at once on two
// threads take each other's draws, and either may come out other than it does
// alone. Every solve on such an ordering then rounds otherwise, and a fit
// whose misfit has several optima may end in another one, run to run (seen as
// a diagnosis that changed with the number of threads).
std::mutex& MetisMutex();

}  // namespace femup::internal
