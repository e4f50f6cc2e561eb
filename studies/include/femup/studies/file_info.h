// `femup info FILE`: what a data file holds, as femup's own readers see it.
//   UFF (.uff, .unv): every dataset with its number and line; for 58 the
//     function type, response and reference node and direction, axis labels and
//     units, number of points, sample rate or frequency step; for 55 the
//     analysis type, mode number, frequency (and damping, eigenvalue for
//     complex modes), nodes and directions; for 15 and 2411 the number of nodes
//     and the extent of their coordinates; datasets femup does not read are
//     listed as skipped.
//   CSV time series (.csv): the time column and the channels with the units
//     their names give ("acc1 [m/s^2]", "acc1 (g)"), sample rate, rows.
//   Matrix Market (.mtx): size, stored entries, symmetry, field, and whether
//     femup reads it (real or integer, general or symmetric).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "femup/core/io/csv_series.h"
#include "femup/core/io/uff.h"

namespace femup {

struct MatrixMarketInfo {
  std::string object;    // "matrix"
  std::string format;    // "coordinate" or "array"
  std::string field;     // "real", "integer", "complex", "pattern"
  std::string symmetry;  // "general", "symmetric", "skew-symmetric", "hermitian"
  long long rows = 0, cols = 0;
  long long entries = 0;   // entries stored in the file (one triangle if symmetric)
  bool readable = false;   // femup's reader takes it
  long long nonzeros = 0;  // of the whole matrix as read (when readable)
  std::string problem;     // why not, when not readable
};

struct CsvInfo {
  CsvSeries series;
  std::string time_units;          // from the time column's name, or empty
  std::vector<std::string> names;  // channel names without their units
  std::vector<std::string> units;  // per channel, empty when the name has none
};

struct FileInfo {
  std::string path;
  std::string format;  // "uff", "csv" or "matrix_market"
  std::optional<UffFile> uff;
  std::optional<CsvInfo> csv;
  std::optional<MatrixMarketInfo> matrix;
};

// Reads the file with the reader its extension names (.uff / .unv, .csv, .mtx;
// any case). Throws InputError naming the file for an unknown extension, a
// missing file, and what the readers refuse (with the line).
FileInfo DescribeFile(const std::string& path);
// Plain text, one line per dataset (UFF) or item.
std::string FileInfoReport(const FileInfo& info);
// The same as a JSON document (pretty-printed, ends with a newline).
std::string FileInfoJson(const FileInfo& info);

// "acc1 [m/s^2]" -> name "acc1", units "m/s^2"; also "(g)". No units: the
// name as it is and "".
void SplitNameAndUnits(const std::string& column, std::string* name, std::string* units);

}  // namespace femup
