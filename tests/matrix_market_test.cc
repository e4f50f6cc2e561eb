#include "femup/core/io/matrix_market.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "femup/core/errors.h"
#include "scratch_dir.h"

namespace femup {
namespace {

namespace fs = std::filesystem;

const std::string kDataDir = std::string(FEMUP_TEST_DATA_DIR) + "/mm";
const std::string kModelDir = kDataDir + "/model";

std::string DataFile(const std::string& name) { return kDataDir + "/" + name; }

using testing::ScratchDir;

std::string WriteText(const std::string& dir, const std::string& name,
                      const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> DirectoryEntries(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Runs `f`, expects an InputError and returns it.
InputError CatchInputError(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", "");
}

void ExpectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos)
      << "'" << text << "' does not contain '" << part << "'";
}

// Every entry of `actual` (sparse) equals `expected` exactly.
void ExpectEntries(const SparseMatrix& actual, const Eigen::MatrixXd& expected) {
  ASSERT_EQ(actual.rows(), expected.rows());
  ASSERT_EQ(actual.cols(), expected.cols());
  const Eigen::MatrixXd dense(actual);
  for (Eigen::Index i = 0; i < expected.rows(); ++i) {
    for (Eigen::Index j = 0; j < expected.cols(); ++j) {
      EXPECT_EQ(dense(i, j), expected(i, j)) << "entry (" << i << ", " << j << ")";
    }
  }
}

void ExpectEntries(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected) {
  ASSERT_EQ(actual.rows(), expected.rows());
  ASSERT_EQ(actual.cols(), expected.cols());
  for (Eigen::Index i = 0; i < expected.rows(); ++i) {
    for (Eigen::Index j = 0; j < expected.cols(); ++j) {
      EXPECT_EQ(actual(i, j), expected(i, j)) << "entry (" << i << ", " << j << ")";
    }
  }
}

std::uint64_t Bits(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof x);
  return bits;
}

// Stored entries as (row, col, bit pattern), in storage order.
std::vector<std::tuple<Eigen::Index, Eigen::Index, std::uint64_t>> StoredEntries(
    SparseMatrix a) {
  a.makeCompressed();
  std::vector<std::tuple<Eigen::Index, Eigen::Index, std::uint64_t>> out;
  for (Eigen::Index k = 0; k < a.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) {
      out.emplace_back(it.row(), it.col(), Bits(it.value()));
    }
  }
  return out;
}

// A finite double with uniformly random bits: every exponent, subnormals too.
double RandomDouble(std::mt19937_64& rng) {
  for (;;) {
    const std::uint64_t bits = rng();
    double x = 0;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isfinite(x)) return x;
  }
}

const double kAwkward[] = {-0.0,
                           0.1,
                           1.0 / 3.0,
                           std::numeric_limits<double>::denorm_min(),
                           -std::numeric_limits<double>::min(),
                           std::numeric_limits<double>::max(),
                           -std::numeric_limits<double>::max(),
                           std::nextafter(1.0, 2.0),
                           123456789012345678.0};

// ---------------------------------------------------------------------------
// Reading well-formed files: every number against the matrix written by hand.

TEST(ReadMatrixMarketTest, GeneralCoordinateWithCommentsBlankLinesAndDuplicates) {
  Eigen::MatrixXd expected(3, 4);
  expected << 1.5, 0, 0, -2,  //
      0, 0.25 + -0.15, 0, 0,  //
      3e-7, 0, 4.25, 1e20;
  const SparseMatrix a = ReadMatrixMarket(DataFile("general_3x4.mtx"));
  ExpectEntries(a, expected);
  EXPECT_EQ(a.nonZeros(), 6);  // the duplicate (2, 2) is one summed entry
  EXPECT_TRUE(a.isCompressed());
  ExpectEntries(ReadMatrixMarketDense(DataFile("general_3x4.mtx")), expected);
}

TEST(ReadMatrixMarketTest, SymmetricCoordinateMirrorsTheLowerTriangle) {
  Eigen::MatrixXd expected(4, 4);
  expected << 4, -1, 0, 0.5,  //
      -1, 4, -1, 0,           //
      0, -1, 4, -1,           //
      0.5, 0, -1, 2;
  const SparseMatrix a = ReadMatrixMarket(DataFile("symmetric_lower.mtx"));
  ExpectEntries(a, expected);
  EXPECT_EQ(a.nonZeros(), 12);
  ExpectEntries(ReadMatrixMarketDense(DataFile("symmetric_lower.mtx")), expected);
}

TEST(ReadMatrixMarketTest, SymmetricCoordinateStoredAsUpperTriangleIsMirroredToo) {
  const Eigen::MatrixXd lower(ReadMatrixMarket(DataFile("symmetric_lower.mtx")));
  ExpectEntries(ReadMatrixMarket(DataFile("symmetric_upper.mtx")), lower);
  ExpectEntries(ReadMatrixMarketDense(DataFile("symmetric_upper.mtx")), lower);
}

TEST(ReadMatrixMarketTest, ArrayGeneralIsColumnMajor) {
  Eigen::MatrixXd expected(2, 3);
  expected << 1, -3, 0,  //
      2, 4.5, 6e-3;
  ExpectEntries(ReadMatrixMarketDense(DataFile("array_general.mtx")), expected);
  const SparseMatrix a = ReadMatrixMarket(DataFile("array_general.mtx"));
  ExpectEntries(a, expected);
  EXPECT_EQ(a.nonZeros(), 5);  // the explicit 0 of an array file is not stored
}

TEST(ReadMatrixMarketTest, ArraySymmetricHoldsTheLowerTriangleColumnByColumn) {
  Eigen::MatrixXd expected(3, 3);
  expected << 10, -2, 0,  //
      -2, 8, 1,           //
      0, 1, 5;
  ExpectEntries(ReadMatrixMarketDense(DataFile("array_symmetric.mtx")), expected);
  ExpectEntries(ReadMatrixMarket(DataFile("array_symmetric.mtx")), expected);
}

TEST(ReadMatrixMarketTest, IntegerField) {
  Eigen::MatrixXd expected(2, 2);
  expected << 7, 0,  //
      -12, 3;
  ExpectEntries(ReadMatrixMarket(DataFile("integer.mtx")), expected);
}

TEST(ReadMatrixMarketTest, CrlfLineEndingsByteOrderMarkTabsAndKeywordCase) {
  const ScratchDir scratch;
  const std::string& dir = scratch.path();
  std::string text = ReadText(DataFile("general_3x4.mtx"));
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const std::string path = WriteText(dir, "crlf.mtx", crlf);
  ExpectEntries(ReadMatrixMarket(path),
                Eigen::MatrixXd(ReadMatrixMarket(DataFile("general_3x4.mtx"))));

  const std::string odd = WriteText(dir, "odd.mtx",
                                    "\xEF\xBB\xBF%%MatrixMarket MATRIX Coordinate REAL "
                                    "General\r\n\t2\t2  1 \r\n  2\t1\t-6.5e-1\t\r\n");
  Eigen::MatrixXd expected(2, 2);
  expected << 0, 0,  //
      -0.65, 0;
  ExpectEntries(ReadMatrixMarket(odd), expected);
}

TEST(ReadMatrixMarketTest, NoFinalNewlineAndEmptyMatrix) {
  const ScratchDir scratch;
  const std::string& dir = scratch.path();
  const std::string path = WriteText(
      dir, "a.mtx", "%%MatrixMarket matrix coordinate real general\n1 1 1\n1 1 2.5");
  ExpectEntries(ReadMatrixMarket(path), Eigen::MatrixXd::Constant(1, 1, 2.5));
  const std::string empty =
      WriteText(dir, "b.mtx", "%%MatrixMarket matrix coordinate real general\n0 0 0\n");
  EXPECT_EQ(ReadMatrixMarket(empty).rows(), 0);
  EXPECT_EQ(ReadMatrixMarket(empty).cols(), 0);
  const std::string zeros =
      WriteText(dir, "c.mtx", "%%MatrixMarket matrix coordinate real general\n3 2 0\n");
  EXPECT_EQ(ReadMatrixMarket(zeros).rows(), 3);
  EXPECT_EQ(ReadMatrixMarket(zeros).cols(), 2);
  EXPECT_EQ(ReadMatrixMarket(zeros).nonZeros(), 0);
}

TEST(ReadMatrixMarketTest, ExtremeValuesAreReadExactly) {
  const ScratchDir scratch;
  const std::string& dir = scratch.path();
  const std::string path = WriteText(dir, "x.mtx",
                                     "%%MatrixMarket matrix array real general\n"
                                     "6 1\n"
                                     "4.9406564584124654e-324\n"
                                     "1.7976931348623157e308\n"
                                     "-2.2250738585072014E-308\n"
                                     "1e-400\n"
                                     "-0\n"
                                     ".5\n");
  const Eigen::MatrixXd a = ReadMatrixMarketDense(path);
  EXPECT_EQ(a(0), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(a(1), std::numeric_limits<double>::max());
  EXPECT_EQ(a(2), -std::numeric_limits<double>::min());
  EXPECT_EQ(a(3), 0.0);  // too small for a double: underflows to zero
  EXPECT_EQ(a(4), 0.0);
  EXPECT_TRUE(std::signbit(a(4)));
  EXPECT_EQ(a(5), 0.5);
}

TEST(ReadMatrixMarketTest, MissingFileNamesThePath) {
  const std::string path = DataFile("no_such_file.mtx");
  const InputError error = CatchInputError([&] { ReadMatrixMarket(path); });
  EXPECT_EQ(error.where(), path);
  ExpectContains(error.what(), "not found");
  EXPECT_EQ(CatchInputError([&] { ReadMatrixMarketDense(path); }).where(), path);
}

// ---------------------------------------------------------------------------
// Malformed files: each throws InputError naming the file and the line.

struct MalformedCase {
  const char* name;
  const char* text;
  int line;          // the line the error names
  const char* what;  // part of the message
};

void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.name; }

class MalformedFileTest : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(MalformedFileTest, ThrowsInputErrorWithFileAndLine) {
  const MalformedCase& c = GetParam();
  const ScratchDir scratch;
  const std::string& dir = scratch.path();
  const std::string path = WriteText(dir, std::string(c.name) + ".mtx", c.text);
  const std::string where = path + ":" + std::to_string(c.line);
  for (int dense = 0; dense < 2; ++dense) {
    const InputError error = CatchInputError([&] {
      if (dense) {
        ReadMatrixMarketDense(path);
      } else {
        ReadMatrixMarket(path);
      }
    });
    EXPECT_EQ(error.where(), where);
    ExpectContains(error.what(), where + ": ");
    ExpectContains(error.what(), c.what);
  }
}

#define BANNER "%%MatrixMarket matrix coordinate real general\n"
#define ARRAY_BANNER "%%MatrixMarket matrix array real general\n"

const MalformedCase kMalformedCases[] = {
    {"empty_file", "", 1, "the file is empty"},
    {"no_banner", "3 3 1\n1 1 1\n", 1, "expected the banner"},
    {"misspelt_banner", "%%MatrixMarkt matrix coordinate real general\n1 1 1\n1 1 1\n", 1,
     "expected the banner"},
    {"short_banner", "%%MatrixMarket matrix coordinate real\n1 1 1\n1 1 1\n", 1,
     "the banner has 4 words, expected 5"},
    {"vector_object", "%%MatrixMarket vector coordinate real general\n1 1 1\n1 1 1\n", 1,
     "object 'vector' is not supported"},
    {"unknown_format", "%%MatrixMarket matrix sparse real general\n1 1 1\n1 1 1\n", 1,
     "format 'sparse' is not supported"},
    {"complex_field",
     "%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n", 1,
     "field 'complex' is not supported"},
    {"pattern_field", "%%MatrixMarket matrix coordinate pattern general\n1 1 1\n1 1\n", 1,
     "field 'pattern' is not supported"},
    {"skew_symmetric",
     "%%MatrixMarket matrix coordinate real skew-symmetric\n2 2 1\n2 1 1\n", 1,
     "symmetry 'skew-symmetric' is not supported"},
    {"hermitian", "%%MatrixMarket matrix coordinate real hermitian\n1 1 1\n1 1 1\n", 1,
     "symmetry 'hermitian' is not supported"},
    {"no_size_line", BANNER "% only a comment\n\n", 3, "ends before the size line"},
    {"size_line_two_values", BANNER "% comment\n3 3\n1 1 1\n", 3,
     "size line: expected 3 values (rows cols entries), found 2"},
    {"array_size_line_three_values", ARRAY_BANNER "2 2 4\n1\n2\n3\n4\n", 2,
     "size line: expected 2 values (rows cols), found 3"},
    {"size_not_a_number", BANNER "3 x 3\n", 2,
     "expected a nonnegative integer number of columns, found 'x'"},
    {"negative_size", BANNER "-3 3 0\n", 2,
     "expected a nonnegative integer number of rows"},
    {"size_too_large", BANNER "3000000000 3 0\n", 2, "is too large"},
    {"symmetric_not_square", "%%MatrixMarket matrix coordinate real symmetric\n3 4 1\n",
     2, "a symmetric matrix must be square"},
    {"fewer_entries", BANNER "3 3 3\n1 1 1\n2 2 2\n% end\n", 5,
     "the size line (line 2) declares 3 entries, the file ends after 2"},
    {"more_entries", BANNER "3 3 2\n1 1 1\n2 2 2\n\n3 3 3\n", 6,
     "more entries than the 2 declared"},
    {"array_fewer_entries", ARRAY_BANNER "2 2\n1\n2\n3\n", 5,
     "declares 4 entries, the file ends after 3"},
    {"array_more_entries", ARRAY_BANNER "1 2\n1\n2\n3\n", 5,
     "more entries than the 2 declared"},
    {"array_two_values_on_a_line", ARRAY_BANNER "2 2\n1 2\n3\n4\n", 3,
     "expected 1 value per line (array format, column by column), found 2"},
    {"entry_two_values", BANNER "3 3 2\n1 1 1\n2 2\n", 4,
     "expected 3 values (row col value), found 2"},
    {"entry_four_values", BANNER "3 3 1\n1 1 1 1\n", 3,
     "expected 3 values (row col value), found 4"},
    {"row_index_zero", BANNER "3 3 1\n0 1 1\n", 3,
     "row index '0' is out of range: expected 1..3 (indices are 1-based)"},
    {"column_index_too_large", BANNER "3 4 1\n1 5 1\n", 3,
     "column index '5' is out of range: expected 1..4"},
    {"row_index_not_integer", BANNER "3 3 1\n1.0 1 1\n", 3,
     "expected an integer row index, found '1.0'"},
    {"nan", BANNER "3 3 2\n1 1 1\n2 2 NaN\n", 4, "expected a finite value, found 'NaN'"},
    {"inf", ARRAY_BANNER "1 1\n-inf\n", 3, "expected a finite value, found '-inf'"},
    {"overflow", BANNER "3 3 1\n1 1 1e999\n", 3,
     "value '1e999' is too large for a double"},
    {"word", BANNER "3 3 1\n1 1 abc\n", 3, "expected a real number, found 'abc'"},
    {"decimal_comma", BANNER "3 3 1\n1 1 1,5\n", 3, "(the decimal separator is '.')"},
    {"fortran_d_exponent", BANNER "3 3 2\n1 1 1.0\n2 2 1.5D+03\n", 4,
     "value '1.5D+03' has a Fortran 'D' exponent, which Matrix Market does not allow"},
    {"fortran_lowercase_d", ARRAY_BANNER "1 1\n2d0\n", 3, "Fortran 'D' exponent"},
    {"hexadecimal", BANNER "3 3 1\n1 1 0x10\n", 3,
     "expected a real number, found '0x10'"},
    {"missing_exponent_digits", BANNER "3 3 1\n1 1 1e\n", 3,
     "expected a real number, found '1e'"},
    {"integer_field_real_value",
     "%%MatrixMarket matrix coordinate integer general\n2 2 1\n1 1 2.5\n", 3,
     "expected an integer value (the banner declares field 'integer'), found '2.5'"},
    {"symmetric_both_triangles",
     "%%MatrixMarket matrix coordinate real symmetric\n3 3 3\n1 1 1\n2 1 5\n1 3 5\n", 5,
     "lists entries both below (line 4) and above (line 5) the diagonal"},
    {"crlf_line_numbers", BANNER "\r\n% c\r\n2 2 1\r\n1 1 x\r\n", 5,
     "expected a real number, found 'x'"},
};

std::string CaseName(const ::testing::TestParamInfo<MalformedCase>& param_info) {
  return param_info.param.name;
}

INSTANTIATE_TEST_SUITE_P(AllCases, MalformedFileTest,
                         ::testing::ValuesIn(kMalformedCases), CaseName);

// ---------------------------------------------------------------------------
// Size limits (fuzzing, issue 25): a size line is checked before anything is
// allocated. The inputs are those of fuzz/regressions/matrix_market/.

TEST(MatrixMarketSizeLimitsTest, DenseReadRefusesMoreThan2To26Entries) {
  // Read dense, this allocated 8 GB; read sparse, it is a legitimate matrix.
  const std::string text = BANNER "100000 10000 1\n1 1 1.5\n";
  const InputError error =
      CatchInputError([&] { ParseMatrixMarketDense(text, "big.mtx"); });
  EXPECT_EQ(error.where(), "big.mtx:2");
  ExpectContains(error.what(),
                 "a 100000 x 10000 matrix read dense has 1000000000 entries");
  ExpectContains(error.what(), "expected at most 67108864");
  const SparseMatrix a = ParseMatrixMarket(text, "big.mtx");
  EXPECT_EQ(a.rows(), 100000);
  EXPECT_EQ(a.cols(), 10000);
  EXPECT_EQ(a.nonZeros(), 1);
  // Just above the limit (8192 x 8192 is the largest square matrix allowed).
  ExpectContains(CatchInputError([] {
                   ParseMatrixMarketDense(BANNER "8193 8192 0\n", "a.mtx");
                 }).what(),
                 "has 67117056 entries");
}

TEST(MatrixMarketSizeLimitsTest, SparseReadRefusesHugeDimensionsWithFewEntries) {
  // Each allocated 8 GiB of indices (Eigen's outer index, or the transposed
  // copy setFromTriplets makes).
  for (const char* size : {"1 2147483647 0", "2147483647 1 0", "4194305 1 0"}) {
    SCOPED_TRACE(size);
    const std::string text = BANNER + std::string(size) + "\n";
    // Read dense, 4194305 x 1 is within the dense limit (32 MiB).
    const int reads = std::string(size) == "4194305 1 0" ? 1 : 2;
    for (int dense = 0; dense < reads; ++dense) {
      const InputError error = CatchInputError([&] {
        if (dense) {
          ParseMatrixMarketDense(text, "huge.mtx");
        } else {
          ParseMatrixMarket(text, "huge.mtx");
        }
      });
      EXPECT_EQ(error.where(), "huge.mtx:2");
      ExpectContains(error.what(), "size line: a ");
    }
  }
  const InputError error =
      CatchInputError([] { ParseMatrixMarket(BANNER "1 2147483647 0\n", "huge.mtx"); });
  ExpectContains(error.what(),
                 "a 1 x 2147483647 matrix with 0 entries would need 8 GiB of row and "
                 "column indices; expected at most 4194304 rows and columns, or "
                 "more only with at least one entry per 16 rows (columns): here at least "
                 "134217728");
  // An array file with no entries (0 rows) says the same.
  ExpectContains(CatchInputError([] {
                   ParseMatrixMarket(ARRAY_BANNER "0 2147483647\n", "huge.mtx");
                 }).what(),
                 "a 0 x 2147483647 matrix with 0 entries");
  // Through the file reader, the path is named.
  const ScratchDir scratch;
  const std::string path =
      WriteText(scratch.path(), "huge.mtx", BANNER "2147483647 1 0\n");
  EXPECT_EQ(CatchInputError([&] { ReadMatrixMarket(path); }).where(), path + ":2");
  EXPECT_EQ(CatchInputError([&] { ReadMatrixMarketDense(path); }).where(), path + ":2");
}

TEST(MatrixMarketSizeLimitsTest, EmptyArraysWithAHugeDimensionAreReadAtOnce) {
  // 0 x 2147483647 holds no value and is within every limit. Read dense it used
  // to walk its 2^31 empty columns (seconds; minutes under the sanitizers), found
  // by the session-21 fuzzing campaign. Now it returns at once, either way round.
  const Eigen::MatrixXd wide =
      ParseMatrixMarketDense(ARRAY_BANNER "0 2147483647\n", "w.mtx");
  EXPECT_EQ(wide.rows(), 0);
  EXPECT_EQ(wide.cols(), 2147483647);
  const Eigen::MatrixXd tall =
      ParseMatrixMarketDense(ARRAY_BANNER "2147483647 0\n", "t.mtx");
  EXPECT_EQ(tall.rows(), 2147483647);
  EXPECT_EQ(tall.cols(), 0);
}

TEST(MatrixMarketSizeLimitsTest, LargeSparseMatricesWithFewEntriesAreRead) {
  // An element matrix of a 10^6-DOF model in global DOFs: a few entries.
  const SparseMatrix a = ParseMatrixMarket(
      "%%MatrixMarket matrix coordinate real symmetric\n"
      "1000000 1000000 2\n1 1 4\n1000000 1 -1\n",
      "element.mtx");
  EXPECT_EQ(a.rows(), 1000000);
  EXPECT_EQ(a.nonZeros(), 3);
  EXPECT_EQ(a.coeff(0, 999999), -1.0);
  // A dimension above 2^22 with at least one entry per 16 columns passes the
  // size line (and the file must then hold the entries).
  ExpectContains(
      CatchInputError([] {
        ParseMatrixMarket(BANNER "32 20000000 1250000\n", "b.mtx");
      }).what(),
      "b.mtx:2: the size line (line 2) declares 1250000 entries, the file ends "
      "after 0");
}

#undef BANNER
#undef ARRAY_BANNER

// ---------------------------------------------------------------------------
// Writing.

TEST(WriteMatrixMarketTest, WritesFullPrecisionCoordinateText) {
  const ScratchDir scratch;
  const std::string& dir = scratch.path();
  Eigen::MatrixXd dense(2, 2);
  dense << 1, 0,  //
      0.1, -2;
  const std::string path = dir + "/a.mtx";
  WriteMatrixMarket(path, SparseMatrix(dense.sparseView()), false);
  EXPECT_EQ(ReadText(path),
            "%%MatrixMarket matrix coordinate real general\n"
            "% written by femup\n"
            "2 2 3\n"
            "1 1 1\n"
            "2 1 0.10000000000000001\n"
            "2 2 -2\n");
  WriteMatrixMarket(path, dense);
  EXPECT_EQ(ReadText(path),
            "%%MatrixMarket matrix array real general\n"
            "% written by femup\n"
            "2 2\n"
            "1\n"
            "0.10000000000000001\n"
            "0\n"
            "-2\n");
  EXPECT_EQ(DirectoryEntries(dir), std::vector<std::string>{"a.mtx"});
}

TEST(WriteMatrixMarketTest, SparseGeneralRoundTripIsBitExact) {
  std::mt19937_64 rng(20240611);
  const int rows = 37, cols = 23;
  std::vector<Eigen::Triplet<double>> triplets;
  std::uniform_int_distribution<int> row(0, rows - 1), col(0, cols - 1);
  for (int k = 0; k < 300; ++k)
    triplets.emplace_back(row(rng), col(rng), RandomDouble(rng));
  for (double x : kAwkward) triplets.emplace_back(row(rng), col(rng), x);
  triplets.emplace_back(rows - 1, cols - 1, 0.0);  // an explicitly stored zero
  SparseMatrix a(rows, cols);
  a.setFromTriplets(triplets.begin(), triplets.end(),
                    [](double, double b) { return b; });  // no sums: exact values

  const ScratchDir scratch;
  const std::string& dir = scratch.path();
  const std::string path = dir + "/a.mtx";
  WriteMatrixMarket(path, a, false);
  const SparseMatrix b = ReadMatrixMarket(path);
  ASSERT_EQ(b.rows(), rows);
  ASSERT_EQ(b.cols(), cols);
  EXPECT_EQ(StoredEntries(b), StoredEntries(a));
  const Eigen::MatrixXd d = ReadMatrixMarketDense(path);
  const Eigen::MatrixXd expected(a);
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) {
      // -0.0 + 0.0 is +0.0 in the dense sum; compare values, not bits, where zero.
      if (expected(i, j) == 0.0) {
        EXPECT_EQ(d(i, j), 0.0);
      } else {
        EXPECT_EQ(Bits(d(i, j)), Bits(expected(i, j))) << i << ", " << j;
      }
    }
  }
}

TEST(WriteMatrixMarketTest, SymmetricStoresTheLowerTriangleAndRoundTripsBitExact) {
  std::mt19937_64 rng(7);
  const int n = 19;
  std::vector<Eigen::Triplet<double>> triplets;
  std::uniform_int_distribution<int> index(0, n - 1);
  for (int k = 0; k < 80; ++k) {
    const int i = index(rng), j = index(rng);
    const double x = RandomDouble(rng);
    triplets.emplace_back(i, j, x);
    if (i != j) triplets.emplace_back(j, i, x);
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end(), [](double, double b) { return b; });
  ASSERT_TRUE(IsSymmetric(a, 0.0));

  const ScratchDir scratch;
  const std::string path = scratch.path() + "/s.mtx";
  WriteMatrixMarket(path, a, true);
  std::istringstream text(ReadText(path));
  std::string line;
  std::getline(text, line);
  EXPECT_EQ(line, "%%MatrixMarket matrix coordinate real symmetric");
  std::getline(text, line);  // comment
  long long rows = 0, cols = 0, count = 0;
  text >> rows >> cols >> count;
  EXPECT_EQ(rows, n);
  EXPECT_EQ(cols, n);
  long long lower = 0;
  for (const auto& [i, j, bits] : StoredEntries(a)) {
    if (i >= j) ++lower;
  }
  EXPECT_EQ(count, lower);
  long long i = 0, j = 0;
  std::string value;
  long long listed = 0;
  while (text >> i >> j >> value) {
    EXPECT_GE(i, j) << "entry above the diagonal in symmetric storage";
    ++listed;
  }
  EXPECT_EQ(listed, count);
  EXPECT_EQ(StoredEntries(ReadMatrixMarket(path)), StoredEntries(a));
}

TEST(WriteMatrixMarketTest, DenseRoundTripIsBitExact) {
  std::mt19937_64 rng(99);
  Eigen::MatrixXd a(9, 4);
  for (Eigen::Index k = 0; k < a.size(); ++k) a(k) = RandomDouble(rng);
  for (size_t k = 0; k < std::size(kAwkward); ++k)
    a(static_cast<Eigen::Index>(k)) = kAwkward[k];
  const ScratchDir scratch;
  const std::string path = scratch.path() + "/d.mtx";
  WriteMatrixMarket(path, a);
  const Eigen::MatrixXd b = ReadMatrixMarketDense(path);
  ASSERT_EQ(b.rows(), a.rows());
  ASSERT_EQ(b.cols(), a.cols());
  for (Eigen::Index k = 0; k < a.size(); ++k) EXPECT_EQ(Bits(b(k)), Bits(a(k))) << k;
  EXPECT_EQ(ReadText(path).rfind("%%MatrixMarket matrix array real general\n", 0), 0u);
}

TEST(WriteMatrixMarketTest, OverwritesAnExistingFile) {
  const ScratchDir scratch;
  const std::string& dir = scratch.path();
  const std::string path = WriteText(dir, "a.mtx", "old content that is longer than new");
  WriteMatrixMarket(path, Eigen::MatrixXd::Constant(1, 1, 3.0));
  ExpectEntries(ReadMatrixMarketDense(path), Eigen::MatrixXd::Constant(1, 1, 3.0));
  EXPECT_EQ(DirectoryEntries(dir), std::vector<std::string>{"a.mtx"});
}

TEST(WriteMatrixMarketTest, FailuresLeaveNothingBehind) {
  const ScratchDir scratch;
  const std::string& dir = scratch.path();
  const std::string existing = WriteText(dir, "keep.mtx", "previous content");
  const std::string fresh = dir + "/new.mtx";

  Eigen::MatrixXd nan = Eigen::MatrixXd::Ones(2, 2);
  nan(1, 0) = std::nan("");
  ExpectContains(CatchInputError([&] { WriteMatrixMarket(existing, nan); }).what(),
                 "entry (2, 1)");
  ExpectContains(CatchInputError([&] {
                   WriteMatrixMarket(fresh, SparseMatrix(nan.sparseView()), false);
                 }).what(),
                 "not finite");

  Eigen::MatrixXd asymmetric(2, 2);
  asymmetric << 1, 2,  //
      3, 4;
  const InputError error = CatchInputError(
      [&] { WriteMatrixMarket(existing, SparseMatrix(asymmetric.sparseView()), true); });
  EXPECT_EQ(error.where(), existing);
  ExpectContains(error.what(), "not symmetric");
  CatchInputError([&] {
    WriteMatrixMarket(fresh, SparseMatrix(Eigen::MatrixXd::Ones(2, 3).sparseView()),
                      true);
  });

  const std::string missing_dir = dir + "/no_such_dir/a.mtx";
  EXPECT_EQ(CatchInputError([&] { WriteMatrixMarket(missing_dir, asymmetric); }).where(),
            missing_dir);

  EXPECT_EQ(ReadText(existing), "previous content");
  EXPECT_EQ(DirectoryEntries(dir), std::vector<std::string>{"keep.mtx"});
}

// ---------------------------------------------------------------------------
// Importing a model (tests/data/mm/model/README.md describes it).

MatrixMarketModelSpec ChainSpec() {
  MatrixMarketModelSpec spec;
  spec.stiffness_file = "k.mtx";
  spec.mass_file = "m.mtx";
  MatrixMarketElement e1;
  e1.id = 1;
  e1.stiffness_file = "e1_k.mtx";
  e1.mass_file = "e1_m.mtx";
  e1.dofs = {0};
  MatrixMarketElement e2;
  e2.id = 2;
  e2.label = "middle";
  e2.stiffness_file = "e2_k.mtx";
  e2.mass_file = "e2_m.mtx";
  e2.added_mass_file = "e2_added_mass.mtx";
  e2.dofs = {0, 1};
  e2.wet = true;
  MatrixMarketElement e3;
  e3.id = 3;
  e3.stiffness_file = "e3_k.mtx";
  e3.mass_file = "e3_m.mtx";
  e3.wet = true;
  spec.elements = {e1, e2, e3};
  return spec;
}

Eigen::MatrixXd Matrix3(std::initializer_list<double> values) {
  Eigen::MatrixXd a(3, 3);
  auto it = values.begin();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) a(i, j) = *it++;
  }
  return a;
}

TEST(ImportMatrixMarketStructureTest, ChainWithGlobalMatrices) {
  const Structure s = ImportMatrixMarketStructure(ChainSpec(), kModelDir);
  ExpectEntries(s.stiffness, Matrix3({300, -200, 0, -200, 500, -300, 0, -300, 350}));
  ExpectEntries(s.mass, Matrix3({6.5, 1, 0, 1, 10, 2, 0, 2, 6}));
  EXPECT_EQ(s.dof_labels, (std::vector<std::string>{"d1", "d2", "d3"}));
  EXPECT_FALSE(s.description.empty());
  ASSERT_EQ(s.elements.size(), 3u);

  const ElementMatrices& e1 = s.elements[0];
  EXPECT_EQ(e1.id, 1);
  EXPECT_EQ(e1.label, "e1");
  EXPECT_FALSE(e1.wet);
  ExpectEntries(e1.stiffness, Matrix3({100, 0, 0, 0, 0, 0, 0, 0, 0}));
  ExpectEntries(e1.mass, Matrix3({2, 0, 0, 0, 0, 0, 0, 0, 0}));
  ExpectEntries(e1.added_mass_basis, Matrix3({2, 0, 0, 0, 0, 0, 0, 0, 0}));

  const ElementMatrices& e2 = s.elements[1];
  EXPECT_EQ(e2.id, 2);
  EXPECT_EQ(e2.label, "middle");
  EXPECT_TRUE(e2.wet);
  ExpectEntries(e2.stiffness, Matrix3({200, -200, 0, -200, 200, 0, 0, 0, 0}));
  ExpectEntries(e2.mass, Matrix3({4, 1, 0, 1, 4, 0, 0, 0, 0}));
  ExpectEntries(e2.added_mass_basis, Matrix3({0.5, 0, 0, 0, 0.5, 0, 0, 0, 0}));

  const ElementMatrices& e3 = s.elements[2];
  EXPECT_EQ(e3.id, 3);
  EXPECT_EQ(e3.label, "e3");
  EXPECT_TRUE(e3.wet);
  ExpectEntries(e3.stiffness, Matrix3({0, 0, 0, 0, 300, -300, 0, -300, 300}));
  ExpectEntries(e3.mass, Matrix3({0, 0, 0, 0, 6, 2, 0, 2, 6}));
  ExpectEntries(e3.added_mass_basis, Matrix3({0, 0, 0, 0, 6, 2, 0, 2, 6}));
}

TEST(ImportMatrixMarketStructureTest, SumsElementsWhenGlobalMatricesAreMissing) {
  MatrixMarketModelSpec spec = ChainSpec();
  spec.stiffness_file.clear();
  spec.mass_file.clear();
  spec.dof_labels = {"n1:ux", "n2:ux", "n3:ux"};
  const Structure s = ImportMatrixMarketStructure(spec, kModelDir);
  ExpectEntries(s.stiffness, Matrix3({300, -200, 0, -200, 500, -300, 0, -300, 300}));
  ExpectEntries(s.mass, Matrix3({6, 1, 0, 1, 10, 2, 0, 2, 6}));
  EXPECT_EQ(s.dof_labels, spec.dof_labels);
}

TEST(ImportMatrixMarketStructureTest, OnlyLocalElementsAndDefaults) {
  MatrixMarketModelSpec spec;
  MatrixMarketElement a;  // id 0: takes its position, 1
  a.stiffness_file = "e2_k.mtx";
  a.dofs = {2, 0};
  MatrixMarketElement b;
  b.mass_file = "e1_m.mtx";
  b.dofs = {1};
  spec.elements = {a, b};
  const Structure s = ImportMatrixMarketStructure(spec, kModelDir);
  ASSERT_EQ(s.elements.size(), 2u);
  EXPECT_EQ(s.elements[0].id, 1);
  EXPECT_EQ(s.elements[1].id, 2);
  EXPECT_EQ(s.elements[1].label, "e2");
  ExpectEntries(s.stiffness, Matrix3({200, 0, -200, 0, 0, 0, -200, 0, 200}));
  ExpectEntries(s.mass, Matrix3({0, 0, 0, 0, 2, 0, 0, 0, 0}));
  ExpectEntries(s.elements[0].mass, Eigen::MatrixXd::Zero(3, 3));  // no mass file
  ExpectEntries(s.elements[1].stiffness, Eigen::MatrixXd::Zero(3, 3));
}

// The size taken from the elements' largest DOF is limited as a size line is:
// one element at DOF 72812093 made a model of 72,812,094 DOFs (gigabytes of
// labels and indices; found by the session-21 fuzzing campaign,
// fuzz/regressions/study/matrix_market_element_dof_huge.yaml).
TEST(ImportMatrixMarketStructureTest, ASizeFromOneHugeDofIsAnError) {
  MatrixMarketModelSpec spec;
  MatrixMarketElement a;
  a.stiffness_file = "e1_k.mtx";
  a.mass_file = "e1_m.mtx";
  a.dofs = {72812093};
  spec.elements = {a};
  const InputError error =
      CatchInputError([&] { ImportMatrixMarketStructure(spec, kModelDir); });
  EXPECT_EQ(error.where(), "model.elements");
  ExpectContains(error.what(),
                 "the largest DOF in the elements' dofs (72812093) makes a model of "
                 "72812094 DOFs, of which the elements reach 1; expected at most 4194304 "
                 "DOFs");
  // Within the free dimension it is read.
  a.dofs = {100000};
  spec.elements = {a};
  EXPECT_EQ(ImportMatrixMarketStructure(spec, kModelDir).dof_labels.size(), 100001u);
}

TEST(ImportMatrixMarketStructureTest, AbsolutePathsIgnoreBaseDir) {
  MatrixMarketModelSpec spec = ChainSpec();
  spec.stiffness_file = kModelDir + "/k.mtx";
  for (auto& e : spec.elements) {
    e.stiffness_file = kModelDir + "/" + e.stiffness_file;
    e.mass_file = kModelDir + "/" + e.mass_file;
    if (!e.added_mass_file.empty())
      e.added_mass_file = kModelDir + "/" + e.added_mass_file;
  }
  spec.mass_file = kModelDir + "/m.mtx";
  const Structure s = ImportMatrixMarketStructure(spec, "/nonexistent/base");
  ExpectEntries(s.stiffness, Matrix3({300, -200, 0, -200, 500, -300, 0, -300, 350}));
}

// Runs the import of a modified chain and returns the error message.
std::string ImportError(const std::function<void(MatrixMarketModelSpec*)>& change) {
  MatrixMarketModelSpec spec = ChainSpec();
  change(&spec);
  return CatchInputError([&] { ImportMatrixMarketStructure(spec, kModelDir); }).what();
}

TEST(ImportMatrixMarketStructureTest, ErrorsNameTheFieldAndTheFile) {
  std::string m = ImportError([](auto* s) { s->elements[1].mass_file = "missing.mtx"; });
  ExpectContains(m, "model.elements[1].mass_file: " + kModelDir + "/missing.mtx");
  ExpectContains(m, "not found");

  m = ImportError([](auto* s) { s->stiffness_file = "missing_k.mtx"; });
  ExpectContains(m, "model.stiffness_file: " + kModelDir + "/missing_k.mtx");

  // A reader error keeps its line number.
  m = ImportError([](auto* s) { s->elements[2].added_mass_file = "bad_line4.mtx"; });
  ExpectContains(
      m, "model.elements[2].added_mass_file: " + kModelDir + "/bad_line4.mtx:4: ");
  ExpectContains(m, "expected 3 values (row col value), found 2");

  // A local matrix whose size disagrees with its dofs.
  m = ImportError([](auto* s) { s->elements[1].dofs = {0, 1, 2}; });
  ExpectContains(m, "model.elements[1].stiffness_file: " + kModelDir + "/e2_k.mtx");
  ExpectContains(m, "matrix is 2 x 2, expected 3 x 3");

  // A global matrix of the wrong size.
  m = ImportError([](auto* s) { s->elements[2].mass_file = "e2_m.mtx"; });
  ExpectContains(m, "model.elements[2].mass_file: " + kModelDir + "/e2_m.mtx");
  ExpectContains(m, "gives 2 DOFs");

  m = ImportError([](auto* s) { s->mass_file = "e2_m.mtx"; });
  ExpectContains(m, "model.mass_file: " + kModelDir + "/e2_m.mtx");

  m = ImportError([](auto* s) { s->elements[0].dofs = {3}; });
  ExpectContains(m, "model.elements[0].dofs[0]: global DOF 3 is out of range");
  m = ImportError([](auto* s) { s->elements[1].dofs = {-1, 0}; });
  ExpectContains(m, "model.elements[1].dofs[0]: global DOF -1 is out of range");
  m = ImportError([](auto* s) { s->elements[1].dofs = {1, 1}; });
  ExpectContains(m, "model.elements[1].dofs[1]: global DOF 1 is listed twice");

  m = ImportError(
      [](auto* s) { s->elements[1].stiffness_file = "../asymmetric_2x2.mtx"; });
  ExpectContains(m, "model.elements[1].stiffness_file: ");
  ExpectContains(m, "asymmetric_2x2.mtx: matrix is not symmetric");
  m = ImportError([](auto* s) { s->stiffness_file = "../general_3x4.mtx"; });
  ExpectContains(m, "model.stiffness_file: ");
  ExpectContains(m, "expected a square matrix");

  m = ImportError([](auto* s) { s->dof_labels = {"a", "b"}; });
  ExpectContains(m, "model.dof_labels");
  m = ImportError([](auto* s) { s->dof_labels = {"a", "b", "a"}; });
  ExpectContains(m, "model.dof_labels[2]: label 'a' is used twice");

  m = ImportError([](auto* s) { s->elements[2].id = 1; });
  ExpectContains(m, "model.elements[2].id: id 1 is already used by model.elements[0]");
  m = ImportError([](auto* s) { s->elements[2].label = "middle"; });
  ExpectContains(m, "model.elements[2].label: label 'middle' is already used");
  m = ImportError([](auto* s) { s->elements[0].id = -4; });
  ExpectContains(m, "model.elements[0].id");

  m = ImportError([](auto* s) {
    s->stiffness_file.clear();
    for (auto& e : s->elements) e.stiffness_file.clear();
  });
  ExpectContains(m, "model.stiffness_file: is empty and no element has a stiffness file");

  m = ImportError([](auto* s) { *s = MatrixMarketModelSpec(); });
  ExpectContains(m, "nothing to import");
}

}  // namespace
}  // namespace femup
