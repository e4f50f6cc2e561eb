// Matrix Market files (https://math.nist.gov/MatrixMarket/formats.html): read
// and write real matrices, so that a user of any FE package can bring K, M and
// element matrices, and so that systems can be handed to other tools.
#pragma once

#include <string>
#include <vector>

#include "femup/model.h"
#include "femup/structure.h"

namespace femup {

// Reads a real or integer matrix, "coordinate" or "array", general or symmetric
// (the symmetric half is mirrored). Throws InputError naming the file and line
// on a missing file, a bad banner, a count mismatch, an index out of range, a
// non-finite value, or a field (complex, pattern) that is not supported.
SparseMatrix ReadMatrixMarket(const std::string& path);
// The same, returned dense (handy for right-hand sides and small systems).
Eigen::MatrixXd ReadMatrixMarketDense(const std::string& path);

// Writes coordinate real; `symmetric` stores the lower triangle only. Writes to a
// temporary file and renames it, so a failed write leaves nothing behind.
void WriteMatrixMarket(const std::string& path, const SparseMatrix& matrix,
                       bool symmetric);
void WriteMatrixMarket(const std::string& path, const Eigen::MatrixXd& matrix);

// A model from another FE code: global K and M, and elements (substructures)
// whose matrices carry the correction factors.
struct MatrixMarketElement {
  int id = 0;                   // 1-based
  std::string label;            // empty: "e<id>"
  std::string stiffness_file;   // may be empty (no stiffness factor possible)
  std::string mass_file;        // may be empty
  std::string added_mass_file;  // empty: the element mass is the added-mass basis
  // Global DOF (0-based) of each local row/column; empty when the files are
  // already in global DOFs.
  std::vector<int> dofs;
  bool wet = false;
};
struct MatrixMarketModelSpec {
  std::string stiffness_file;  // global K (free DOFs); empty: sum of elements
  std::string mass_file;       // global M; empty: sum of elements
  std::vector<MatrixMarketElement> elements;
  std::vector<std::string> dof_labels;  // empty: "d1", "d2", ...
};
// Relative paths are taken relative to `base_dir`. Throws InputError for
// missing files, size mismatches, asymmetric matrices, DOFs out of range.
Structure ImportMatrixMarketStructure(const MatrixMarketModelSpec& spec,
                                      const std::string& base_dir);

}  // namespace femup
