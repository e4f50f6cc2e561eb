// Matrix Market files (https://math.nist.gov/MatrixMarket/formats.html): read
// and write real matrices, so that a user of any FE package can bring K, M and
// element matrices, and so that systems can be handed to other tools.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"

namespace femup {

// Size limits, checked on the size line before anything is allocated (so that a
// mistyped or damaged size line is an error rather than gigabytes of memory):
//  * Read dense, a matrix has at most kMatrixMarketMaxDenseEntries = 2^26 entries
//    (rows x cols; 512 MiB of doubles, e.g. 8192 x 8192), whatever the format.
//  * Read sparse, rows and columns are at most 2^31 - 1 (Eigen's index), and at
//    most kMatrixMarketFreeDimension = 2^22 (4,194,304) unless the file lists at
//    least one entry per kMatrixMarketDimensionPerEntry = 16 rows (or columns, the
//    larger of the two). A sparse matrix keeps one 4-byte index per column, and
//    assembling it one per row too, whether or not the rows hold entries, and
//    the assembly walks them all: so a file of a few lines costs at most
//    2 x 16 MiB of indices, and a matrix with more rows than that has its
//    entries to show for them (a stiffness or mass matrix has its diagonal).
//    An element matrix of a 10^6-DOF model in global DOFs, with a few entries,
//    is read; "1 2147483647 0" (8 GiB of indices for nothing) is refused. For an
//    array file the entries are rows x cols (the lower triangle for symmetric).
//  A build for fuzzing (FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION, scripts/fuzz.sh)
//  takes 2^20 dense entries and a free dimension of 2^16: the fuzzer otherwise
//  fills its corpus with legitimate size lines near the limits, each a second
//  of assembling empty rows under the sanitizers, and explores the reader at a
//  quarter of its speed. The checks themselves are the same code.
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
inline constexpr long long kMatrixMarketMaxDenseEntries = 1LL << 20;
inline constexpr long long kMatrixMarketFreeDimension = 1LL << 16;
#else
inline constexpr long long kMatrixMarketMaxDenseEntries = 1LL << 26;
inline constexpr long long kMatrixMarketFreeDimension = 1LL << 22;
#endif
inline constexpr long long kMatrixMarketDimensionPerEntry = 16;

// Reads a real or integer matrix, "coordinate" or "array", general or symmetric
// (the symmetric half is mirrored). Throws InputError naming the file and line
// on a missing file, a bad banner, a count mismatch, an index out of range, a
// non-finite value, a field (complex, pattern) that is not supported, or a size
// beyond the limits above.
SparseMatrix ReadMatrixMarket(const std::string& path);
// The same, returned dense (handy for right-hand sides and small systems).
Eigen::MatrixXd ReadMatrixMarketDense(const std::string& path);
// The same for text already in memory; `name` stands for the file in messages.
SparseMatrix ParseMatrixMarket(std::string_view text, const std::string& name);
Eigen::MatrixXd ParseMatrixMarketDense(std::string_view text, const std::string& name);

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
