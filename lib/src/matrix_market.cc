// Matrix Market reader and writer, and the import of a model made of Matrix
// Market files.
//
// Reading follows https://math.nist.gov/MatrixMarket/formats.html with a few
// deliberate choices:
//  * Keywords of the banner are case-insensitive; a UTF-8 byte order mark, CRLF
//    line endings, blank lines and '%' comment lines (anywhere after the banner)
//    are accepted.
//  * Fields "real" and "integer" are read; "complex" and "pattern" are rejected,
//    as are the symmetries "skew-symmetric" and "hermitian".
//  * Values follow the C number syntax without hexadecimal, NaN or infinity.
//    Fortran 'D' exponents (1.0D+03) are not Matrix Market and are rejected with
//    a message that says so. A value too small for a double reads as zero; one
//    too large is rejected.
//  * Array format: one value per line, column-major; for "symmetric" only the
//    lower triangle (column by column) is stored.
//  * Coordinate format: one "row col value" per line, 1-based indices.
//    Duplicate entries are summed. In "symmetric" storage each off-diagonal
//    entry is mirrored. The standard stores the lower triangle; a file that
//    stores only the upper triangle is accepted too (it means the same matrix),
//    but a file that mixes entries above and below the diagonal is rejected,
//    because mirroring it would double the matrix off the diagonal (it is almost
//    always a full matrix mislabelled "symmetric").
//  * When read as sparse, an array file drops its exact zeros; a coordinate
//    file keeps what it lists (summed duplicates included).
#include "femup/matrix_market.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>

#include "femup/errors.h"
#include "file_io.h"
#include "text_util.h"

namespace femup {
namespace {

using Triplet = Eigen::Triplet<double>;
using internal::AtomicFile;
using internal::Tokens;

constexpr const char* kBannerHelp =
    "'%%MatrixMarket matrix coordinate|array real|integer general|symmetric'";

// ---------------------------------------------------------------------------
// Text helpers.

std::string Lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

// The text quoted in a message, shortened when long.
std::string Quote(std::string_view text) {
  constexpr size_t kMax = 60;
  std::string out = "'";
  if (text.size() > kMax) {
    out += std::string(text.substr(0, kMax));
    out += "...";
  } else {
    out += std::string(text);
  }
  while (!out.empty() && out.back() == '\r') out.pop_back();
  return out + "'";
}

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

// Checks the decimal number syntax [+-]digits[.digits][(e|E)[+-]digits] (with at
// least one mantissa digit). `exponent_letters` are the accepted exponent letters.
bool HasNumberSyntax(std::string_view t, std::string_view exponent_letters) {
  size_t i = 0;
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
  size_t digits = 0;
  while (i < t.size() && IsDigit(t[i])) ++i, ++digits;
  if (i < t.size() && t[i] == '.') {
    ++i;
    while (i < t.size() && IsDigit(t[i])) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < t.size() && exponent_letters.find(t[i]) != std::string_view::npos) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    size_t exponent_digits = 0;
    while (i < t.size() && IsDigit(t[i])) ++i, ++exponent_digits;
    if (exponent_digits == 0) return false;
  }
  return i == t.size();
}

bool IsIntegerSyntax(std::string_view t) {
  size_t i = 0;
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
  if (i == t.size()) return false;
  for (; i < t.size(); ++i) {
    if (!IsDigit(t[i])) return false;
  }
  return true;
}

bool IsNonFiniteWord(std::string_view t) {
  std::string s = Lower(t);
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.erase(0, 1);
  return s == "inf" || s == "infinity" || s.rfind("nan", 0) == 0;
}

// True when a number with valid syntax that does not fit a double is too large
// (rather than too small): the decimal exponent of its leading digit is >= 0.
bool OverflowsRatherThanUnderflows(std::string_view t) {
  long long position = 0;  // decimal exponent of the first nonzero digit, +1
  bool seen_nonzero = false;
  bool after_point = false;
  size_t i = 0;
  if (t[i] == '+' || t[i] == '-') ++i;
  for (; i < t.size() && t[i] != 'e' && t[i] != 'E'; ++i) {
    if (t[i] == '.') {
      after_point = true;
      continue;
    }
    if (!seen_nonzero && t[i] != '0') seen_nonzero = true;
    if (!after_point && seen_nonzero) ++position;
    if (after_point && !seen_nonzero) --position;
  }
  long long exponent = 0;
  if (i < t.size()) {
    ++i;
    bool negative = false;
    if (t[i] == '+' || t[i] == '-') negative = t[i++] == '-';
    for (; i < t.size(); ++i) {
      if (exponent < 1000000000LL) exponent = exponent * 10 + (t[i] - '0');
    }
    if (negative) exponent = -exponent;
  }
  return position + exponent > 0;
}

// ---------------------------------------------------------------------------
// The parser.

enum class Format { kCoordinate, kArray };
enum class Field { kReal, kInteger };

struct Parsed {
  Format format = Format::kCoordinate;
  bool symmetric = false;
  Eigen::Index rows = 0;
  Eigen::Index cols = 0;
  std::vector<Triplet> triplets;  // coordinate: as listed (mirrored)
  std::vector<double> values;     // array: as listed, column-major
};

// Which reader the text is for: the size limits differ (see the header).
enum class Target { kSparse, kDense };

class Reader {
 public:
  Reader(std::string_view text, std::string name, Target target)
      : text_(text), path_(std::move(name)), target_(target) {
    position_ = internal::AfterByteOrderMark(text_);
  }

  Parsed Read() {
    ReadBanner();
    ReadSizeLine();
    if (parsed_.format == Format::kCoordinate) {
      ReadCoordinateEntries();
    } else {
      ReadArrayEntries();
    }
    return std::move(parsed_);
  }

 private:
  std::string Where(long long line) const { return path_ + ":" + std::to_string(line); }
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(Where(line_number_), what);
  }

  // Next line without its terminator; false at the end of the file.
  bool NextLine(std::string_view* line) {
    if (position_ >= text_.size()) return false;
    size_t end = text_.find('\n', position_);
    if (end == std::string_view::npos) end = text_.size();
    *line = text_.substr(position_, end - position_);
    position_ = end + 1;
    ++line_number_;
    return true;
  }

  // Next line that is neither blank nor a comment; false at the end of the file.
  bool NextDataLine(std::vector<std::string_view>* tokens) {
    std::string_view line;
    while (NextLine(&line)) {
      *tokens = Tokens(line);
      if (tokens->empty() || (*tokens)[0][0] == '%') continue;
      return true;
    }
    return false;
  }

  void ReadBanner() {
    std::string_view line;
    if (!NextLine(&line)) {
      line_number_ = 1;
      Fail("the file is empty; expected the banner " + std::string(kBannerHelp));
    }
    const auto tokens = Tokens(line);
    if (tokens.empty() || Lower(tokens[0]) != "%%matrixmarket") {
      Fail("expected the banner " + std::string(kBannerHelp) +
           " on the first line, found " + Quote(line));
    }
    if (tokens.size() != 5) {
      Fail("the banner has " + std::to_string(tokens.size()) +
           " words, expected 5: " + std::string(kBannerHelp));
    }
    const std::string object = Lower(tokens[1]);
    const std::string format = Lower(tokens[2]);
    const std::string field = Lower(tokens[3]);
    const std::string symmetry = Lower(tokens[4]);
    if (object != "matrix") {
      Fail("object " + Quote(tokens[1]) + " is not supported, expected 'matrix'");
    }
    if (format == "coordinate") {
      parsed_.format = Format::kCoordinate;
    } else if (format == "array") {
      parsed_.format = Format::kArray;
    } else {
      Fail("format " + Quote(tokens[2]) +
           " is not supported, expected 'coordinate' or 'array'");
    }
    if (field == "real") {
      field_ = Field::kReal;
    } else if (field == "integer") {
      field_ = Field::kInteger;
    } else if (field == "complex") {
      Fail(
          "field 'complex' is not supported: femup reads real matrices only "
          "(expected 'real' or 'integer')");
    } else if (field == "pattern") {
      Fail(
          "field 'pattern' is not supported: a pattern matrix has no values "
          "(expected 'real' or 'integer')");
    } else {
      Fail("field " + Quote(tokens[3]) +
           " is not supported, expected 'real' or 'integer'");
    }
    if (symmetry == "general") {
      parsed_.symmetric = false;
    } else if (symmetry == "symmetric") {
      parsed_.symmetric = true;
    } else {
      Fail("symmetry " + Quote(tokens[4]) +
           " is not supported, expected 'general' or 'symmetric'");
    }
  }

  // A nonnegative size that fits Eigen's sparse index.
  long long ParseSize(std::string_view token, const char* what) const {
    if (!IsIntegerSyntax(token) || token[0] == '-') {
      Fail(std::string("expected a nonnegative integer ") + what + ", found " +
           Quote(token));
    }
    long long value = 0;
    const char* first = token.data() + (token[0] == '+' ? 1 : 0);
    const auto result = std::from_chars(first, token.data() + token.size(), value);
    constexpr long long kMax = std::numeric_limits<int>::max();
    if (result.ec != std::errc() || value > kMax) {
      Fail(std::string(what) + " " + Quote(token) + " is too large (at most " +
           std::to_string(kMax) + ")");
    }
    return value;
  }

  void ReadSizeLine() {
    std::vector<std::string_view> tokens;
    const bool coordinate = parsed_.format == Format::kCoordinate;
    const std::string expected =
        coordinate ? "3 values (rows cols entries)" : "2 values (rows cols)";
    if (!NextDataLine(&tokens)) {
      Fail("the file ends before the size line; expected " + expected);
    }
    size_line_ = line_number_;
    if (tokens.size() != (coordinate ? 3u : 2u)) {
      Fail("size line: expected " + expected + ", found " +
           std::to_string(tokens.size()));
    }
    parsed_.rows = ParseSize(tokens[0], "number of rows");
    parsed_.cols = ParseSize(tokens[1], "number of columns");
    if (parsed_.symmetric && parsed_.rows != parsed_.cols) {
      Fail("a symmetric matrix must be square, the size line declares " +
           std::to_string(parsed_.rows) + " x " + std::to_string(parsed_.cols));
    }
    if (coordinate) {
      declared_ = ParseSize(tokens[2], "number of entries");
    } else if (parsed_.symmetric) {
      declared_ = parsed_.rows * (parsed_.rows + 1) / 2;
    } else {
      declared_ = parsed_.rows * parsed_.cols;
    }
    CheckSizeLimits();
  }

  // The size limits of the header, before anything is allocated.
  void CheckSizeLimits() const {
    const std::string size =
        std::to_string(parsed_.rows) + " x " + std::to_string(parsed_.cols);
    if (target_ == Target::kDense) {
      const long long entries = parsed_.rows * parsed_.cols;
      if (entries > kMatrixMarketMaxDenseEntries) {
        Fail("size line: a " + size + " matrix read dense has " +
             std::to_string(entries) + " entries (" +
             Bytes(8.0 * static_cast<double>(entries)) + "); expected at most " +
             std::to_string(kMatrixMarketMaxDenseEntries) + " (" +
             Bytes(8.0 * static_cast<double>(kMatrixMarketMaxDenseEntries)) + ")");
      }
      return;
    }
    const long long dimension = std::max(parsed_.rows, parsed_.cols);
    const long long allowed =
        std::max(kMatrixMarketFreeDimension, kMatrixMarketDimensionPerEntry * declared_);
    if (dimension > allowed) {
      Fail("size line: a " + size + " matrix with " + std::to_string(declared_) +
           " entries would need " +
           Bytes(4.0 * static_cast<double>(parsed_.rows + parsed_.cols)) +
           " of row and column indices; expected at most " +
           std::to_string(kMatrixMarketFreeDimension) +
           " rows and columns, or more only with at least one entry per " +
           std::to_string(kMatrixMarketDimensionPerEntry) +
           " rows (columns): here at least " +
           std::to_string((dimension + kMatrixMarketDimensionPerEntry - 1) /
                          kMatrixMarketDimensionPerEntry));
    }
  }

  static std::string Bytes(double bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
    int unit = 0;
    while (bytes >= 1024 && unit < 4) bytes /= 1024, ++unit;
    std::ostringstream out;
    out.precision(3);
    out << bytes << " " << units[unit];
    return out.str();
  }

  // The capacity worth reserving for `declared_` entries of at least
  // `min_chars` characters each (never more than the file can hold).
  size_t Capacity(size_t min_chars) const {
    const size_t left = position_ < text_.size() ? text_.size() - position_ : 0;
    const auto fits = static_cast<long long>(left / min_chars + 1);
    return static_cast<size_t>(std::min(declared_, fits));
  }

  double ParseValue(std::string_view token) const {
    if (field_ == Field::kInteger && !IsIntegerSyntax(token)) {
      if (HasNumberSyntax(token, "eE")) {
        Fail("expected an integer value (the banner declares field 'integer'), found " +
             Quote(token));
      }
      Fail("expected an integer value, found " + Quote(token));
    }
    if (!HasNumberSyntax(token, "eE")) {
      if (HasNumberSyntax(token, "eEdD")) {
        std::string fixed(token);
        for (char& c : fixed) {
          if (c == 'd' || c == 'D') c = 'E';
        }
        Fail("value " + Quote(token) +
             " has a Fortran 'D' exponent, which Matrix Market does not allow; write " +
             Quote(fixed) + " instead");
      }
      if (IsNonFiniteWord(token)) {
        Fail("expected a finite value, found " + Quote(token));
      }
      if (token.find(',') != std::string_view::npos) {
        Fail("expected a real number, found " + Quote(token) +
             " (the decimal separator is '.')");
      }
      Fail("expected a real number, found " + Quote(token));
    }
    const char* first = token.data() + (token[0] == '+' ? 1 : 0);
    const char* last = token.data() + token.size();
    double value = 0;
    const auto result = std::from_chars(first, last, value);
    if (result.ec == std::errc::result_out_of_range) {
      if (OverflowsRatherThanUnderflows(token)) {
        Fail("value " + Quote(token) +
             " is too large for a double (at most about 1.8e308)");
      }
      return token[0] == '-' ? -0.0 : 0.0;  // underflows: reads as zero
    }
    if (result.ec != std::errc() || result.ptr != last || !std::isfinite(value)) {
      Fail("expected a real number, found " + Quote(token));
    }
    return value;
  }

  long long ParseIndex(std::string_view token, const char* what, long long size) const {
    if (!IsIntegerSyntax(token)) {
      Fail(std::string("expected an integer ") + what + " index, found " + Quote(token));
    }
    long long value = 0;
    const char* first = token.data() + (token[0] == '+' ? 1 : 0);
    const auto result = std::from_chars(first, token.data() + token.size(), value);
    if (result.ec != std::errc() || value < 1 || value > size) {
      Fail(std::string(what) + " index " + Quote(token) +
           " is out of range: expected 1.." + std::to_string(size) +
           " (indices are 1-based)");
    }
    return value;
  }

  [[noreturn]] void FailTooFew(long long found) {
    Fail("the size line (line " + std::to_string(size_line_) + ") declares " +
         std::to_string(declared_) + " entries, the file ends after " +
         std::to_string(found));
  }

  void FailIfMore() {
    std::vector<std::string_view> tokens;
    if (NextDataLine(&tokens)) {
      Fail("more entries than the " + std::to_string(declared_) +
           " declared on the size line (line " + std::to_string(size_line_) + ")");
    }
  }

  void ReadCoordinateEntries() {
    parsed_.triplets.reserve(Capacity(6) * (parsed_.symmetric ? 2 : 1));
    long long first_below = 0;  // line of the first entry below the diagonal
    long long first_above = 0;
    std::vector<std::string_view> tokens;
    for (long long k = 0; k < declared_; ++k) {
      if (!NextDataLine(&tokens)) FailTooFew(k);
      if (tokens.size() != 3) {
        Fail("expected 3 values (row col value), found " + std::to_string(tokens.size()));
      }
      const long long i = ParseIndex(tokens[0], "row", parsed_.rows);
      const long long j = ParseIndex(tokens[1], "column", parsed_.cols);
      const double v = ParseValue(tokens[2]);
      parsed_.triplets.emplace_back(static_cast<int>(i - 1), static_cast<int>(j - 1), v);
      if (parsed_.symmetric && i != j) {
        parsed_.triplets.emplace_back(static_cast<int>(j - 1), static_cast<int>(i - 1),
                                      v);
        long long& first = i > j ? first_below : first_above;
        if (first == 0) first = line_number_;
        if (first_below != 0 && first_above != 0) {
          Fail("symmetric storage lists entries both below (line " +
               std::to_string(first_below) + ") and above (line " +
               std::to_string(first_above) +
               ") the diagonal; a symmetric file stores one triangle only (the lower "
               "one, by the standard). Declare the matrix 'general' if the file holds "
               "all of it");
        }
      }
    }
    FailIfMore();
  }

  void ReadArrayEntries() {
    parsed_.values.reserve(Capacity(2));
    std::vector<std::string_view> tokens;
    for (long long k = 0; k < declared_; ++k) {
      if (!NextDataLine(&tokens)) FailTooFew(k);
      if (tokens.size() != 1) {
        Fail("expected 1 value per line (array format, column by column), found " +
             std::to_string(tokens.size()));
      }
      parsed_.values.push_back(ParseValue(tokens[0]));
    }
    FailIfMore();
  }

  std::string_view text_;
  std::string path_;
  Target target_;
  size_t position_ = 0;
  long long line_number_ = 0;
  long long size_line_ = 0;
  long long declared_ = 0;
  Field field_ = Field::kReal;
  Parsed parsed_;
};

// Calls f(i, j, value) for each value of an array file, in file order.
template <typename F>
void ForEachArrayValue(const Parsed& p, F f) {
  // An empty matrix has no value: without this, "0 2147483647" read dense walks
  // 2^31 empty columns (seconds, found by the session-21 fuzzing campaign).
  if (p.rows == 0 || p.cols == 0) return;
  size_t k = 0;
  for (Eigen::Index j = 0; j < p.cols; ++j) {
    for (Eigen::Index i = p.symmetric ? j : 0; i < p.rows; ++i) f(i, j, p.values[k++]);
  }
}

// ---------------------------------------------------------------------------
// Writing.

void AppendNumber(std::string* out, double value) {
  char buffer[40];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value,
                                    std::chars_format::general, 17);
  out->append(buffer, result.ptr);
}

void AppendIndex(std::string* out, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out->append(buffer, result.ptr);
}

constexpr size_t kFlushSize = 1 << 20;

// ---------------------------------------------------------------------------
// Import helpers.

// An InputError from the reader, prefixed with the spec field that named the file.
[[noreturn]] void Rethrow(const InputError& error, const std::string& field) {
  std::string what = error.what();
  const std::string prefix = error.where() + ": ";
  if (what.compare(0, prefix.size(), prefix) == 0) what.erase(0, prefix.size());
  throw InputError(field + ": " + error.where(), what);
}

std::string Resolve(const std::string& file, const std::string& base_dir) {
  const std::filesystem::path path(file);
  if (path.is_absolute() || base_dir.empty()) return path.string();
  return (std::filesystem::path(base_dir) / path).string();
}

std::string SizeText(const SparseMatrix& a) {
  return std::to_string(a.rows()) + " x " + std::to_string(a.cols());
}

// Reads a symmetric square matrix named by `field`.
SparseMatrix ReadSymmetric(const std::string& path, const std::string& field) {
  SparseMatrix a;
  try {
    a = ReadMatrixMarket(path);
  } catch (const InputError& error) {
    Rethrow(error, field);
  }
  if (a.rows() != a.cols()) {
    throw InputError(field + ": " + path,
                     "matrix is " + SizeText(a) + ", expected a square matrix");
  }
  if (!IsSymmetric(a)) {
    throw InputError(field + ": " + path,
                     "matrix is not symmetric (to a relative tolerance of 1e-10)");
  }
  return a;
}

// One matrix file of an element, as stored (local or global DOFs).
struct ElementFile {
  const char* name;  // the spec field: "stiffness_file", ...
  std::string path;  // resolved; empty when the spec names no file
  SparseMatrix matrix;
  bool present() const { return !path.empty(); }
};
enum ElementSlot { kStiffnessSlot, kMassSlot, kAddedMassSlot, kNumSlots };

}  // namespace

// ---------------------------------------------------------------------------

SparseMatrix ReadMatrixMarket(const std::string& path) {
  return ParseMatrixMarket(internal::ReadFileText(path, "Matrix Market file"), path);
}

Eigen::MatrixXd ReadMatrixMarketDense(const std::string& path) {
  return ParseMatrixMarketDense(internal::ReadFileText(path, "Matrix Market file"), path);
}

SparseMatrix ParseMatrixMarket(std::string_view text, const std::string& name) {
  Parsed p = Reader(text, name, Target::kSparse).Read();
  SparseMatrix a(p.rows, p.cols);
  if (p.format == Format::kCoordinate) {
    a.setFromTriplets(p.triplets.begin(), p.triplets.end());  // sums duplicates
  } else {
    std::vector<Triplet> triplets;
    ForEachArrayValue(p, [&](Eigen::Index i, Eigen::Index j, double v) {
      if (v == 0.0) return;
      triplets.emplace_back(static_cast<int>(i), static_cast<int>(j), v);
      if (p.symmetric && i != j)
        triplets.emplace_back(static_cast<int>(j), static_cast<int>(i), v);
    });
    a.setFromTriplets(triplets.begin(), triplets.end());
  }
  a.makeCompressed();
  return a;
}

Eigen::MatrixXd ParseMatrixMarketDense(std::string_view text, const std::string& name) {
  Parsed p = Reader(text, name, Target::kDense).Read();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(p.rows, p.cols);
  if (p.format == Format::kCoordinate) {
    for (const Triplet& t : p.triplets) a(t.row(), t.col()) += t.value();
  } else {
    ForEachArrayValue(p, [&](Eigen::Index i, Eigen::Index j, double v) {
      a(i, j) = v;
      if (p.symmetric) a(j, i) = v;
    });
  }
  return a;
}

void WriteMatrixMarket(const std::string& path, const SparseMatrix& matrix,
                       bool symmetric) {
  // Check everything before touching the file system.
  if (symmetric) {
    if (matrix.rows() != matrix.cols()) {
      throw InputError(path, "cannot write a " + SizeText(matrix) +
                                 " matrix as 'symmetric': it is not square");
    }
    if (!IsSymmetric(matrix)) {
      throw InputError(path,
                       "cannot write the matrix as 'symmetric': it is not symmetric "
                       "(write it as general)");
    }
  }
  long long count = 0;
  for (Eigen::Index k = 0; k < matrix.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(matrix, k); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw InputError(path, "cannot write entry (" + std::to_string(it.row() + 1) +
                                   ", " + std::to_string(it.col() + 1) +
                                   "): it is not finite (NaN or infinite)");
      }
      if (!symmetric || it.row() >= it.col()) ++count;
    }
  }

  AtomicFile file(path);
  std::string text = "%%MatrixMarket matrix coordinate real ";
  text += symmetric ? "symmetric\n" : "general\n";
  text += "% written by femup\n";
  AppendIndex(&text, matrix.rows());
  text += ' ';
  AppendIndex(&text, matrix.cols());
  text += ' ';
  AppendIndex(&text, count);
  text += '\n';
  for (Eigen::Index k = 0; k < matrix.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(matrix, k); it; ++it) {
      if (symmetric && it.row() < it.col()) continue;
      AppendIndex(&text, it.row() + 1);
      text += ' ';
      AppendIndex(&text, it.col() + 1);
      text += ' ';
      AppendNumber(&text, it.value());
      text += '\n';
      if (text.size() >= kFlushSize) file.Write(&text);
    }
  }
  file.Write(&text);
  file.Commit();
}

void WriteMatrixMarket(const std::string& path, const Eigen::MatrixXd& matrix) {
  for (Eigen::Index j = 0; j < matrix.cols(); ++j) {
    for (Eigen::Index i = 0; i < matrix.rows(); ++i) {
      if (!std::isfinite(matrix(i, j))) {
        throw InputError(path, "cannot write entry (" + std::to_string(i + 1) + ", " +
                                   std::to_string(j + 1) +
                                   "): it is not finite (NaN or infinite)");
      }
    }
  }
  AtomicFile file(path);
  std::string text = "%%MatrixMarket matrix array real general\n% written by femup\n";
  AppendIndex(&text, matrix.rows());
  text += ' ';
  AppendIndex(&text, matrix.cols());
  text += '\n';
  for (Eigen::Index j = 0; j < matrix.cols(); ++j) {
    for (Eigen::Index i = 0; i < matrix.rows(); ++i) {
      AppendNumber(&text, matrix(i, j));
      text += '\n';
      if (text.size() >= kFlushSize) file.Write(&text);
    }
  }
  file.Write(&text);
  file.Commit();
}

// Element matrices absent from the spec become n x n zero matrices; an element
// with id 0 takes its position in the list (1-based) as id. Ids and labels must
// be unique, and so must DOF labels and each element's `dofs`.
Structure ImportMatrixMarketStructure(const MatrixMarketModelSpec& spec,
                                      const std::string& base_dir) {
  const int num_elements = static_cast<int>(spec.elements.size());
  auto element_field = [](int e, const std::string& name) {
    return "model.elements[" + std::to_string(e) + "]." + name;
  };

  // Global matrices.
  SparseMatrix stiffness;
  SparseMatrix mass;
  std::string stiffness_path;
  std::string mass_path;
  if (!spec.stiffness_file.empty()) {
    stiffness_path = Resolve(spec.stiffness_file, base_dir);
    stiffness = ReadSymmetric(stiffness_path, "model.stiffness_file");
  }
  if (!spec.mass_file.empty()) {
    mass_path = Resolve(spec.mass_file, base_dir);
    mass = ReadSymmetric(mass_path, "model.mass_file");
  }

  // Element files, as stored (local or global).
  std::vector<std::array<ElementFile, kNumSlots>> files(num_elements);
  for (int e = 0; e < num_elements; ++e) {
    const MatrixMarketElement& element = spec.elements[e];
    const std::string* names[kNumSlots] = {&element.stiffness_file, &element.mass_file,
                                           &element.added_mass_file};
    files[e] = {ElementFile{"stiffness_file", "", {}}, ElementFile{"mass_file", "", {}},
                ElementFile{"added_mass_file", "", {}}};
    for (int slot = 0; slot < kNumSlots; ++slot) {
      ElementFile& file = files[e][slot];
      if (names[slot]->empty()) continue;
      file.path = Resolve(*names[slot], base_dir);
      file.matrix = ReadSymmetric(file.path, element_field(e, file.name));
    }
  }

  // The number of DOFs: every source that fixes it must agree.
  long long n = -1;
  std::string n_source;
  auto fix_size = [&](long long size, const std::string& where, const std::string& what) {
    if (n < 0) {
      n = size;
      n_source = what;
      return;
    }
    if (size != n) {
      throw InputError(where, what + " gives " + std::to_string(size) + " DOFs, but " +
                                  n_source + " gives " + std::to_string(n));
    }
  };
  if (!spec.dof_labels.empty()) {
    fix_size(static_cast<long long>(spec.dof_labels.size()), "model.dof_labels",
             "model.dof_labels (" + std::to_string(spec.dof_labels.size()) + " labels)");
  }
  if (!spec.stiffness_file.empty()) {
    fix_size(stiffness.rows(), "model.stiffness_file: " + stiffness_path,
             "the global stiffness matrix (" + SizeText(stiffness) + ")");
  }
  if (!spec.mass_file.empty()) {
    fix_size(mass.rows(), "model.mass_file: " + mass_path,
             "the global mass matrix (" + SizeText(mass) + ")");
  }
  for (int e = 0; e < num_elements; ++e) {
    const std::vector<int>& dofs = spec.elements[e].dofs;
    for (const ElementFile& file : files[e]) {
      if (!file.present()) continue;
      const std::string field = element_field(e, file.name);
      const std::string where = field + ": " + file.path;
      if (dofs.empty()) {
        fix_size(file.matrix.rows(), where,
                 field + " (" + SizeText(file.matrix) + ", global DOFs)");
      } else if (file.matrix.rows() != static_cast<Eigen::Index>(dofs.size())) {
        const std::string d = std::to_string(dofs.size());
        throw InputError(where, "matrix is " + SizeText(file.matrix) + ", expected " + d +
                                    " x " + d + " (one row per entry of " +
                                    element_field(e, "dofs") + ")");
      }
    }
  }
  if (n < 0) {
    // Only local element matrices: the DOFs are those the elements reach.
    for (const MatrixMarketElement& element : spec.elements) {
      for (int dof : element.dofs) n = std::max<long long>(n, dof + 1LL);
    }
    n_source = "the largest DOF in the elements' dofs";
  }
  if (n < 0) {
    throw InputError(
        "model",
        "has no stiffness_file, no mass_file and no element matrices: nothing "
        "to import");
  }

  // Elements in global DOFs.
  Structure structure;
  structure.type = "matrix_market";
  std::map<int, int> ids;             // id -> position in spec.elements
  std::map<std::string, int> labels;  // label -> position
  for (int e = 0; e < num_elements; ++e) {
    const MatrixMarketElement& element = spec.elements[e];
    ElementMatrices out;
    out.id = element.id == 0 ? e + 1 : element.id;
    if (out.id < 0) {
      throw InputError(element_field(e, "id"),
                       "is " + std::to_string(element.id) + ", expected a positive id");
    }
    if (const auto [it, added] = ids.emplace(out.id, e); !added) {
      throw InputError(element_field(e, "id"), "id " + std::to_string(out.id) +
                                                   " is already used by model.elements[" +
                                                   std::to_string(it->second) + "]");
    }
    out.label = element.label.empty() ? "e" + std::to_string(out.id) : element.label;
    if (const auto [it, added] = labels.emplace(out.label, e); !added) {
      throw InputError(element_field(e, "label"),
                       "label '" + out.label + "' is already used by model.elements[" +
                           std::to_string(it->second) + "]");
    }
    std::set<int> seen;
    for (size_t k = 0; k < element.dofs.size(); ++k) {
      const int dof = element.dofs[k];
      const std::string where = element_field(e, "dofs[" + std::to_string(k) + "]");
      if (dof < 0 || dof >= n) {
        throw InputError(where, "global DOF " + std::to_string(dof) +
                                    " is out of range: the model has " +
                                    std::to_string(n) + " DOFs (0-based, 0.." +
                                    std::to_string(n - 1) + ")");
      }
      if (!seen.insert(dof).second) {
        throw InputError(where, "global DOF " + std::to_string(dof) + " is listed twice");
      }
    }
    auto to_global = [&](const ElementFile& file) {
      SparseMatrix global(n, n);
      if (!file.present()) return global;
      const SparseMatrix& local = file.matrix;
      if (element.dofs.empty()) return local;
      std::vector<Triplet> triplets;
      triplets.reserve(static_cast<size_t>(local.nonZeros()));
      for (Eigen::Index k = 0; k < local.outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(local, k); it; ++it) {
          triplets.emplace_back(element.dofs[it.row()], element.dofs[it.col()],
                                it.value());
        }
      }
      global.setFromTriplets(triplets.begin(), triplets.end());
      return global;
    };
    out.stiffness = to_global(files[e][kStiffnessSlot]);
    out.mass = to_global(files[e][kMassSlot]);
    out.added_mass_basis = files[e][kAddedMassSlot].present()
                               ? to_global(files[e][kAddedMassSlot])
                               : out.mass;
    out.wet = element.wet;
    structure.elements.push_back(std::move(out));
  }

  // Global matrices missing from the spec: sums of the elements.
  auto sum_of = [&](ElementSlot slot, const char* field, const char* kind) {
    SparseMatrix sum(n, n);
    bool any = false;
    for (int e = 0; e < num_elements; ++e) {
      if (!files[e][slot].present()) continue;
      const ElementMatrices& element = structure.elements[e];
      sum += slot == kStiffnessSlot ? element.stiffness : element.mass;
      any = true;
    }
    if (!any) {
      throw InputError(field, std::string("is empty and no element has a ") + kind +
                                  " file: nothing to form the global matrix from");
    }
    return sum;
  };
  structure.stiffness = spec.stiffness_file.empty()
                            ? sum_of(kStiffnessSlot, "model.stiffness_file", "stiffness")
                            : std::move(stiffness);
  structure.mass = spec.mass_file.empty() ? sum_of(kMassSlot, "model.mass_file", "mass")
                                          : std::move(mass);
  structure.stiffness.makeCompressed();
  structure.mass.makeCompressed();

  // DOF labels.
  if (spec.dof_labels.empty()) {
    for (long long i = 0; i < n; ++i) {
      structure.dof_labels.push_back("d" + std::to_string(i + 1));
    }
  } else {
    std::set<std::string> seen;
    for (size_t i = 0; i < spec.dof_labels.size(); ++i) {
      const std::string where = "model.dof_labels[" + std::to_string(i) + "]";
      if (spec.dof_labels[i].empty()) throw InputError(where, "is empty");
      if (!seen.insert(spec.dof_labels[i]).second) {
        throw InputError(where, "label '" + spec.dof_labels[i] + "' is used twice");
      }
    }
    structure.dof_labels = spec.dof_labels;
  }

  std::ostringstream description;
  description << "Matrix Market model: " << n << " DOFs, " << num_elements
              << " elements; K "
              << (spec.stiffness_file.empty() ? "= sum of element stiffnesses"
                                              : "from " + spec.stiffness_file)
              << ", M "
              << (spec.mass_file.empty() ? "= sum of element masses"
                                         : "from " + spec.mass_file);
  structure.description = description.str();
  return structure;
}

}  // namespace femup
