// Universal File Format (UFF, also "universal file", .uff/.unv): read and write
// the datasets that carry vibration test data:
//   15  nodes (label, coordinate systems, colour, coordinates), single precision,
//   2411 nodes, double precision (the newer node dataset of FE and test codes),
//   55  data at nodes: mode shapes (normal and complex modes, frequency-response
//       shapes) with their frequency, modal mass and damping,
//   58  function at a nodal DOF: time histories, spectra, FRFs, coherences...,
//       real or complex, evenly or unevenly sampled, ASCII or binary ("58b").
//
// A UFF file is a sequence of datasets, each framed by a line holding "-1" in
// columns 1-6; the line after the opening "-1" gives the dataset number (I6).
// Every record has a Fortran layout (e.g. 58 record 7 is "3I10,3E13.5"), and
// the reader follows those layouts. Where the format leaves room it is
// tolerant: LF or CRLF line endings, trailing blanks or blanks trimmed, a
// short last line of values, Fortran 'D' exponents (1.0D+03), numbers written
// wider than their field as long as blanks separate them, text columns
// counted in characters for UTF-8 labels. Datasets other than 15, 55, 58 and
// 2411 (and 55 analysis types other than normal mode, complex mode and frequency
// response) are skipped and named in UffFile::notes. Anything else that does
// not fit the layout throws InputError naming the file, the line, the
// dataset, the record and the field.
//
// The binary variant 58b has a longer dataset-number line:
//   "    58b     1     2          11       16016     0     0           0           0"
// giving the byte ordering (1 little-endian, 2 big-endian), the floating-point
// format (2 = IEEE 754; 1 DEC VMS and 3 IBM are refused), the number of ASCII
// lines that follow (11: records 1-11) and the number of bytes of binary
// values after them. Values are 4-byte floats for single precision ordinate
// types and 8-byte doubles for double precision ones, in record-12 order.
#pragma once

#include <Eigen/Core>
#include <array>
#include <complex>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace femup {

// ---------------------------------------------------------------------------
// Nodes. Dataset 15: one record "4I10,3E13.5" per node (single precision).
// Dataset 2411: two records per node, "4I10" (label, export coordinate system,
// displacement coordinate system, colour) and "1P3D25.16" (the coordinates).

struct UffNode {
  int label = 0;
  int definition_cs = 0;    // coordinate system the coordinates are given in
  int displacement_cs = 0;  // coordinate system of the node's DOFs
  int color = 0;
  std::array<double, 3> xyz{0.0, 0.0, 0.0};
  long long line = 0;  // set on reading: the line of its (first) record
};

struct UffNodes {
  std::vector<UffNode> nodes;
  int dataset = 15;    // 15 or 2411: how it is written, set on reading
  long long line = 0;  // set on reading: the line of the dataset number
};

// ---------------------------------------------------------------------------
// Dataset 55: data at nodes. Only the analysis types below are read; others are
// skipped with a note.

enum class UffAnalysisType {
  kNormalMode = 2,          // record 8: frequency, modal mass, damping ratios
  kComplexFirstOrder = 3,   // record 8: eigenvalue, modal A, modal B (complex)
  kFrequencyResponse = 5,   // record 8: frequency
  kComplexSecondOrder = 7,  // as kComplexFirstOrder
};

struct UffModeShape {
  // Records 1-5, free text (80 columns). The format wants "NONE" rather than a
  // blank line; an empty string is written as "NONE".
  std::array<std::string, 5> id_lines{"NONE", "NONE", "NONE", "NONE", "NONE"};
  // Record 6.
  int model_type = 1;  // 0 unknown, 1 structural, 2 heat transfer, 3 fluid flow
  UffAnalysisType analysis_type = UffAnalysisType::kNormalMode;
  // 1 scalar, 2 translations (3 DOF), 3 translations and rotations (6 DOF),
  // 4 symmetric tensor, 5 general tensor. Kept as read; not checked against
  // the number of values per node.
  int data_characteristic = 2;
  int specific_data_type = 8;  // 8 displacement, 11 velocity, 12 acceleration, ...
  bool complex_data = false;   // data type 5 (complex) rather than 2 (real)
  // Record 7.
  int load_case = 0;
  int mode_number = 0;  // for kFrequencyResponse: the frequency step number
  // Record 8. For kNormalMode and kFrequencyResponse:
  double frequency_hz = 0.0;
  double modal_mass = 0.0;                // kNormalMode only
  double viscous_damping_ratio = 0.0;     // kNormalMode only
  double hysteretic_damping_ratio = 0.0;  // kNormalMode only
  // For the complex-mode types:
  std::complex<double> eigenvalue{0.0, 0.0};
  std::complex<double> modal_a{0.0, 0.0};
  std::complex<double> modal_b{0.0, 0.0};
  // Records 9 and 10, one pair per node: nodes[i] and values.row(i). The
  // number of columns is the number of values per node (3 for translations,
  // 6 with rotations). Real data have zero imaginary parts.
  std::vector<int> nodes;
  Eigen::MatrixXcd values;
  // Set on reading: the line of the dataset number and of each node's record 9.
  long long line = 0;
  std::vector<long long> node_lines;
};

// ---------------------------------------------------------------------------
// Dataset 58: function at a nodal DOF.

// Record 7 field 1.
enum class UffOrdinateType {
  kRealSingle = 2,
  kRealDouble = 4,
  kComplexSingle = 5,
  kComplexDouble = 6,
};

// Records 8-11: the data characteristics of one axis (abscissa, ordinate or
// its numerator, ordinate denominator, z axis), "I10,3I5,2(1X,20A1)".
struct UffAxis {
  // 0 unknown, 1 general, 8 displacement, 11 velocity, 12 acceleration,
  // 13 excitation force, 15 pressure, 17 time, 18 frequency, ...
  int specific_data_type = 0;
  int length_exponent = 0;       // units exponents of length, force and
  int force_exponent = 0;        // temperature
  int temperature_exponent = 0;  //
  std::string label = "NONE";    // at most 20 characters
  std::string units = "NONE";    // at most 20 characters
};

struct UffFunction {
  // Records 1-5: id lines (free text, 80 columns; record 3 is often a date).
  std::array<std::string, 5> id_lines{"NONE", "NONE", "NONE", "NONE", "NONE"};
  // Record 6, "2(I5,I10),2(1X,10A1,I10,I4)".
  // 0 general, 1 time response, 2 auto spectrum, 3 cross spectrum, 4 FRF,
  // 5 transmissibility, 6 coherence, 7 auto correlation, 8 cross correlation,
  // 9 PSD, 10 ESD, 11 probability density, 12 spectrum, ...
  int function_type = 0;
  int function_id = 0;
  int version = 0;  // version or sequence number
  int load_case = 0;
  std::string response_entity = "NONE";  // at most 10 characters
  int response_node = 0;
  int response_direction = 0;  // 0 scalar, +-1..3 X,Y,Z, +-4..6 rotations
  std::string reference_entity = "NONE";
  int reference_node = 0;
  int reference_direction = 0;
  // Record 7, "3I10,3E13.5".
  UffOrdinateType ordinate_type = UffOrdinateType::kRealDouble;
  bool even_spacing = true;
  // For even spacing x_k = abscissa_start + k * abscissa_increment. For uneven
  // spacing the format wants zeros here, and that is what is written.
  double abscissa_start = 0.0;
  double abscissa_increment = 0.0;
  double z_axis_value = 0.0;
  // Records 8-11.
  UffAxis abscissa_axis;
  UffAxis ordinate_axis;     // the ordinate, or its numerator
  UffAxis denominator_axis;  // ordinate denominator (e.g. force for an FRF)
  UffAxis z_axis;
  // Record 12. x: the abscissa of each point (filled on reading also for even
  // spacing; not written for even spacing). y: the ordinates; for real
  // ordinate types the imaginary parts are zero (the writer insists).
  Eigen::VectorXd x;
  Eigen::VectorXcd y;
  // Written as 58b (binary, little-endian IEEE) rather than ASCII; set on
  // reading when the dataset was binary.
  bool binary = false;
  long long line = 0;  // set on reading: the line of the dataset number

  bool IsComplex() const {
    return ordinate_type == UffOrdinateType::kComplexSingle ||
           ordinate_type == UffOrdinateType::kComplexDouble;
  }
  bool IsDoublePrecision() const {
    return ordinate_type == UffOrdinateType::kRealDouble ||
           ordinate_type == UffOrdinateType::kComplexDouble;
  }
};

// ---------------------------------------------------------------------------
// Files.

using UffDataset = std::variant<UffNodes, UffModeShape, UffFunction>;

// Where a dataset of a file begins, read or skipped.
struct UffDatasetHeader {
  int number = 0;       // 15, 55, 58, 2411, 2412, ...
  bool binary = false;  // "58b"
  long long line = 0;   // the line of the dataset number (after the opening "-1")
  int index = -1;       // its place in UffFile::datasets; -1: skipped
};

struct UffFile {
  std::vector<UffDataset> datasets;       // in file order
  std::vector<UffDatasetHeader> headers;  // every dataset of the file, in order
  // One line per dataset that was skipped (unsupported dataset number or
  // analysis type) or read with a tolerated irregularity, e.g.
  // "data.uff: line 120: dataset 2411 is not supported; skipped".
  std::vector<std::string> notes;

  std::vector<const UffNodes*> Nodes() const;
  std::vector<const UffModeShape*> ModeShapes() const;
  std::vector<const UffFunction*> Functions() const;
};

// Reads every dataset of the file at `path`. Throws InputError for a missing
// file and for malformed datasets (message: "<path>: line N: dataset 58
// record 7: ...").
UffFile ReadUff(const std::string& path);
// The same for text already in memory; `name` stands for the file in messages.
UffFile ParseUff(std::string_view contents, const std::string& name);

// Writes the datasets with the record layouts of the format (LF line endings,
// 80-column id lines; double precision function values in 20 columns with 12
// significant digits, the format's E20.12; 2411 coordinates in 25 columns with
// 17 significant digits, E25.16; single precision values, the
// abscissa of uneven functions and all dataset 15/55 values in 13 columns with
// 6 significant digits, E13.5), binary functions as 58b little-endian IEEE
// with the end marker right after the values, as pyuff writes and reads them. The file is
// written to a temporary and renamed, so a failure leaves nothing behind. Throws
// InputError naming the path, the dataset (0-based index) and the field for a value that
// does not fit its field: text too long, an integer too wide, a non-finite number, a size
// that disagrees, imaginary parts in a real function.
void WriteUff(const std::string& path, const std::vector<UffDataset>& datasets);
// The same, to a string (binary datasets included as raw bytes); `name` stands
// for the file in messages.
std::string FormatUff(const std::vector<UffDataset>& datasets, const std::string& name);

// Node or other labels as a reader reads them: sorted, repeats dropped, runs
// joined ("1-10, 15, 20-22"); "none" when there are none.
std::string LabelRanges(std::vector<int> labels);

}  // namespace femup
