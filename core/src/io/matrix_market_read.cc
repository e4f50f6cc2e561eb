// Matrix Market reading: the parser (banner, size line with the size limits of
// the header, coordinate and array entries) and the entry points
// ParseMatrixMarket, ParseMatrixMarketDense, ReadMatrixMarket and
// ReadMatrixMarketDense.
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
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/io/matrix_market.h"
#include "io/file_io.h"
#include "text_util.h"

namespace femup {
namespace {

using Triplet = Eigen::Triplet<double>;
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

}  // namespace femup
