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

}  // namespace femup::internal
