// The UFF reader: numbers, the dataset loop (headers, skipping unsupported
// datasets) and the generic records every dataset is made of (numeric records,
// value blocks, ID lines, text columns). The records of each dataset family are
// read in uff_datasets_*.cc.
//
// Reading works on the whole file in memory (binary 58b values may contain any
// byte, so lines are cut from a byte position rather than by a line stream).
// Numeric records are read blank-separated first; when blanks do not separate
// the values (a Fortran field filled to its width, e.g. "-1.234567890123E-100"
// after another value) they are read again by the columns of the record's
// layout. Text records (58 record 6 and records 8-11) are read by columns,
// counted in characters so that UTF-8 units such as "m/s²" keep their place.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "femup/core/errors.h"
#include "io/uff_internal.h"
#include "text_util.h"

namespace femup::uff_internal {
namespace {

using internal::IsBlank;
using internal::Tokens;

// ---------------------------------------------------------------------------
// Numbers.

enum class NumberStatus { kOk, kBad, kNotFinite, kTooLarge };

// A whole token as a finite double. Accepts a leading '+', Fortran 'D'
// exponents (1.0D+03) and the Fortran form without exponent letter that
// E-editing uses for three-digit exponents (0.12345-105). A value too small
// for a double reads as zero; one too large is kTooLarge.
NumberStatus ParseReal(std::string_view token, double* value) {
  if (token.empty()) return NumberStatus::kBad;
  // from_chars would take "nan" and "inf"; UFF values are plain numbers.
  std::string word;
  for (char c : token)
    word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string_view unsigned_word =
      std::string_view(word).substr(word[0] == '+' || word[0] == '-' ? 1 : 0);
  if (unsigned_word == "nan" || unsigned_word == "inf" || unsigned_word == "infinity") {
    return NumberStatus::kNotFinite;
  }
  std::string buffer;
  buffer.reserve(token.size() + 1);
  bool has_exponent_letter = false;
  for (size_t i = 0; i < token.size(); ++i) {
    char c = token[i];
    if (c == 'd' || c == 'D' || c == 'e') c = 'E';
    if (!((c >= '0' && c <= '9') || c == '.' || c == 'E' || c == '+' || c == '-')) {
      return NumberStatus::kBad;
    }
    if (c == 'E') has_exponent_letter = true;
    if ((c == '+' || c == '-') && i > 0 && !has_exponent_letter) {
      const char previous = token[i - 1];
      if ((previous >= '0' && previous <= '9') || previous == '.') {
        buffer.push_back('E');
        has_exponent_letter = true;
      }
    }
    buffer.push_back(c);
  }
  const char* first = buffer.data();
  const char* last = buffer.data() + buffer.size();
  if (*first == '+') {
    ++first;
    if (first == last || *first == '-' || *first == '+') return NumberStatus::kBad;
  }
  double parsed = 0.0;
  const auto result = std::from_chars(first, last, parsed, std::chars_format::general);
  if (result.ptr != last) return NumberStatus::kBad;
  if (result.ec == std::errc::result_out_of_range) {
    const size_t e = buffer.find_first_of("eE");
    if (e != std::string::npos && e + 1 < buffer.size() && buffer[e + 1] == '-') {
      *value = (*first == '-') ? -0.0 : 0.0;
      return NumberStatus::kOk;
    }
    return NumberStatus::kTooLarge;
  }
  if (result.ec != std::errc()) return NumberStatus::kBad;
  if (!std::isfinite(parsed)) return NumberStatus::kNotFinite;
  *value = parsed;
  return NumberStatus::kOk;
}

// A whole token as an int (leading '+' allowed).
bool ParseInt(std::string_view token, int* value) {
  if (token.empty()) return false;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (*first == '+') ++first;
  if (first == last || *first == '+') return false;
  long long parsed = 0;
  const auto result = std::from_chars(first, last, parsed);
  if (result.ec != std::errc() || result.ptr != last) return false;
  if (parsed < std::numeric_limits<int>::min() ||
      parsed > std::numeric_limits<int>::max()) {
    return false;
  }
  *value = static_cast<int>(parsed);
  return true;
}

std::string NumberProblem(NumberStatus status, std::string_view token) {
  switch (status) {
    case NumberStatus::kNotFinite:
      return "expected a finite number, found " + Quote(token);
    case NumberStatus::kTooLarge:
      return "number " + Quote(token) + " is too large for a double";
    default:
      return "expected a number, found " + Quote(token);
  }
}

// ---------------------------------------------------------------------------

std::string FieldList(const std::vector<Field>& fields) {
  std::string out;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) out += ", ";
    out += fields[i].name;
  }
  return out;
}

}  // namespace

UffFile Reader::Read() {
  position_ = internal::AfterByteOrderMark(text_);
  std::string_view line;
  while (NextLine(&line)) {
    if (Trim(line).empty()) continue;
    if (Trim(line) != "-1") {
      Fail(line_, "expected '    -1' opening a dataset, found " + Quote(TrimRight(line)));
    }
    ReadDataset();
  }
  return std::move(file_);
}

// Next line of record `record`; a missing line is a truncated dataset.
std::string_view Reader::RecordLine(const std::string& record) {
  std::string_view line;
  if (!NextLine(&line)) {
    FailIn(line_ + 1, record, "the file ends here; the dataset is truncated");
  }
  if (Trim(line) == "-1") {
    FailIn(line_, record, "found the end marker '-1' instead; the dataset is truncated");
  }
  return line;
}

// Next non-blank line of a dataset of records, false at its closing "-1"; a
// file that ends first is a truncated dataset.
bool Reader::NextLineBeforeEnd(std::string_view* line) {
  while (NextLine(line)) {
    if (Trim(*line) == "-1") return false;
    if (!Trim(*line).empty()) return true;
  }
  FailIn(line_ + 1, "end", "the file ends before the '    -1' closing the dataset");
}

// Skips blank lines and expects the closing "-1".
void Reader::ExpectEnd(const std::string& after) {
  std::string_view line;
  while (NextLine(&line)) {
    if (Trim(line).empty()) continue;
    if (Trim(line) == "-1") return;
    FailIn(line_, "end",
           "expected '    -1' closing the dataset after " + after + ", found " +
               Quote(TrimRight(line)));
  }
  FailIn(line_ + 1, "end", "the file ends before the '    -1' closing the dataset");
}

Reader::Header Reader::ReadHeader() {
  Header header;
  std::string_view line;
  if (!NextLine(&line)) {
    Fail(line_ + 1, "the file ends after '-1'; expected a dataset number");
  }
  header.line = line_;
  std::string_view rest = line;
  while (!rest.empty() && IsBlank(rest.front())) rest.remove_prefix(1);
  size_t digits = 0;
  while (digits < rest.size() && rest[digits] >= '0' && rest[digits] <= '9') ++digits;
  if (digits == 0 || !ParseInt(rest.substr(0, digits), &header.number)) {
    Fail(line_,
         "expected a dataset number (I6) after '-1', found " + Quote(TrimRight(line)));
  }
  rest.remove_prefix(digits);
  if (!rest.empty() && (rest.front() == 'b' || rest.front() == 'B')) {
    header.binary = true;
    const auto tokens = Tokens(rest.substr(1));
    static const char* const kNames[] = {"byte ordering", "floating-point format",
                                         "number of ASCII lines", "number of bytes"};
    const std::string where = "dataset " + std::to_string(header.number) + "b header";
    if (tokens.size() < 4) {
      Fail(line_,
           where +
               ": expected at least 4 fields after 'b' (byte ordering, "
               "floating-point format, number of ASCII lines, number of bytes), got " +
               std::to_string(tokens.size()));
    }
    int values[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < 4; ++i) {
      if (!ParseInt(tokens[i], &values[i]) || values[i] < 0) {
        Fail(line_, where + ": field " + std::to_string(i + 1) + " (" + kNames[i] +
                        "): expected a nonnegative integer, found " + Quote(tokens[i]));
      }
    }
    header.byte_ordering = values[0];
    header.fp_format = values[1];
    header.ascii_lines = values[2];
    header.bytes = values[3];
  } else if (!rest.empty() && !IsBlank(rest.front())) {
    Fail(line_,
         "expected a dataset number (I6) after '-1', found " + Quote(TrimRight(line)));
  }
  return header;
}

void Reader::ReadDataset() {
  const Header header = ReadHeader();
  dataset_ = "dataset " + std::to_string(header.number) + (header.binary ? "b" : "");
  UffDatasetHeader entry;
  entry.number = header.number;
  entry.binary = header.binary;
  entry.line = header.line;
  const int index = static_cast<int>(file_.datasets.size());
  if (header.number == 58) {
    UffFunction f = Read58(header);
    f.line = header.line;
    file_.datasets.emplace_back(std::move(f));
  } else if (!header.binary && (header.number == 15 || header.number == 2411)) {
    UffNodes nodes = header.number == 15 ? Read15() : Read2411();
    nodes.line = header.line;
    file_.datasets.emplace_back(std::move(nodes));
  } else if (!header.binary && header.number == 55) {
    UffModeShape shape;
    shape.line = header.line;
    if (Read55(&shape)) file_.datasets.emplace_back(std::move(shape));
  } else {
    Note(header.line, dataset_ + " is not supported; skipped");
    Skip(header);
  }
  if (static_cast<int>(file_.datasets.size()) > index) entry.index = index;
  file_.headers.push_back(entry);
}

// Skips an unsupported dataset: by the counts of a binary header, else up to
// the next "-1" line.
void Reader::Skip(const Header& header) {
  std::string_view line;
  if (header.binary) {
    for (int i = 0; i < header.ascii_lines; ++i) {
      if (!NextLine(&line)) {
        FailIn(line_ + 1, "header",
               "the file ends within the " + std::to_string(header.ascii_lines) +
                   " ASCII lines the header declares");
      }
    }
    SkipBytes(static_cast<size_t>(header.bytes), "binary data");
    ExpectEnd("the binary data");
    return;
  }
  while (NextLine(&line)) {
    if (Trim(line) == "-1") return;
  }
  FailIn(line_ + 1, "end", "the file ends before the '    -1' closing the dataset");
}

void Reader::SkipBytes(size_t count, const std::string& what) {
  if (text_.size() - std::min(position_, text_.size()) < count) {
    FailIn(line_ + 1, what,
           "the header declares " + std::to_string(count) + " bytes, the file has " +
               std::to_string(text_.size() - std::min(position_, text_.size())) +
               " left; the dataset is truncated");
  }
  line_ +=
      std::count(text_.begin() + static_cast<std::ptrdiff_t>(position_),
                 text_.begin() + static_cast<std::ptrdiff_t>(position_ + count), '\n');
  position_ += count;
}

// --- Generic records ------------------------------------------------------

// A record of numeric fields. Blank-separated values first; when their
// count or syntax does not fit, the columns of the layout.
std::vector<Value> Reader::NumericRecord(std::string_view line,
                                         const std::vector<Field>& fields,
                                         const std::string& record) {
  std::vector<Value> values(fields.size());
  const auto tokens = Tokens(line);
  std::string problem;  // first problem of the blank-separated reading
  if (tokens.size() == fields.size()) {
    for (size_t i = 0; i < fields.size() && problem.empty(); ++i) {
      problem = ParseField(tokens[i], fields[i], i, &values[i]);
    }
    if (problem.empty()) return values;
  }
  if (ByColumns(line, fields, &values)) return values;
  if (problem.empty()) {
    problem = "expected " + std::to_string(fields.size()) + " fields (" +
              FieldList(fields) + "), got " + std::to_string(tokens.size());
  }
  FailIn(line_, record, problem);
}

// Empty string if `token` is a valid value for `field`, else the problem.
std::string Reader::ParseField(std::string_view token, const Field& field, size_t index,
                               Value* value) {
  const std::string label =
      "field " + std::to_string(index + 1) + " (" + field.name + "): ";
  if (field.integer) {
    if (!ParseInt(token, &value->integer)) {
      return label + "expected an integer, found " + Quote(token);
    }
    value->real = value->integer;
    return "";
  }
  const NumberStatus status = ParseReal(token, &value->real);
  if (status != NumberStatus::kOk) return label + NumberProblem(status, token);
  return "";
}

bool Reader::ByColumns(std::string_view line, const std::vector<Field>& fields,
                       std::vector<Value>* values) {
  size_t position = 0;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (position >= line.size()) return false;
    const std::string_view slice =
        Trim(line.substr(position, static_cast<size_t>(fields[i].width)));
    position += static_cast<size_t>(fields[i].width);
    if (slice.empty() || !ParseField(slice, fields[i], i, &(*values)[i]).empty()) {
      return false;
    }
  }
  return position >= line.size() || Trim(line.substr(position)).empty();
}

// Appends the values of one line of a value block to `out`, at most
// `wanted` of them. `widths` is the repeating column layout used when
// blanks do not separate the values. `first_index` numbers the values in
// messages (1-based within the block).
void Reader::ValueLine(std::string_view line, const std::vector<int>& widths,
                       size_t wanted, size_t first_index, const std::string& record,
                       std::vector<double>* out) {
  const auto tokens = Tokens(line);
  std::vector<double> parsed;
  parsed.reserve(tokens.size());
  std::string problem;
  for (size_t i = 0; i < tokens.size(); ++i) {
    double v = 0.0;
    const NumberStatus status = ParseReal(tokens[i], &v);
    if (status != NumberStatus::kOk) {
      problem = "value " + std::to_string(first_index + i) + ": " +
                NumberProblem(status, tokens[i]);
      break;
    }
    parsed.push_back(v);
  }
  if (!problem.empty()) {
    // Fixed columns: the layout's widths, repeated, up to the end of the line.
    parsed.clear();
    size_t position = 0;
    const std::string_view content = TrimRight(line);
    for (size_t k = 0; position < content.size(); ++k) {
      const auto width = static_cast<size_t>(widths[k % widths.size()]);
      const std::string_view slice = Trim(content.substr(position, width));
      position += width;
      double v = 0.0;
      if (slice.empty() || ParseReal(slice, &v) != NumberStatus::kOk) {
        FailIn(line_, record, problem);
      }
      parsed.push_back(v);
    }
  }
  if (parsed.size() > wanted) {
    FailIn(line_, record,
           "more values than the dataset declares: " + std::to_string(wanted) +
               " still expected, this line has " + std::to_string(parsed.size()));
  }
  out->insert(out->end(), parsed.begin(), parsed.end());
}

// Reads `count` values spread over lines of the given layout.
std::vector<double> Reader::ValueBlock(size_t count, const std::vector<int>& widths,
                                       const std::string& record,
                                       const std::string& what) {
  std::vector<double> values;
  // Not more than the rest of the file can hold (a value takes 2 bytes at
  // least), whatever the record declares.
  values.reserve(std::min(count, (text_.size() - std::min(position_, text_.size())) / 2));
  std::string_view line;
  while (values.size() < count) {
    if (!NextLine(&line)) {
      FailIn(line_ + 1, record,
             "the file ends after " + std::to_string(values.size()) + " of " +
                 std::to_string(count) + " " + what + "; the dataset is truncated");
    }
    if (Trim(line) == "-1") {
      FailIn(line_, record,
             "found the end marker '-1' after " + std::to_string(values.size()) + " of " +
                 std::to_string(count) + " " + what + "; the dataset is truncated");
    }
    if (Trim(line).empty()) continue;
    ValueLine(line, widths, count - values.size(), values.size() + 1, record, &values);
  }
  return values;
}

std::array<std::string, 5> Reader::IdLines() {
  std::array<std::string, 5> ids;
  for (int i = 0; i < 5; ++i) {
    const std::string record =
        "record " + std::to_string(i + 1) + " (ID line " + std::to_string(i + 1) + ")";
    ids[static_cast<size_t>(i)] = std::string(TrimRight(RecordLine(record)));
  }
  return ids;
}

// An integer in character columns [first, first + width) of a text record.
int Reader::IntColumn(std::string_view line, size_t first, int width, const char* name,
                      int index, const std::string& record) {
  const std::string_view slice = Trim(CharSlice(line, first, width));
  int value = 0;
  if (!ParseInt(slice, &value)) {
    FailIn(line_, record,
           "field " + std::to_string(index) + " (" + name + ", columns " +
               std::to_string(first + 1) + "-" + std::to_string(first + width) +
               "): expected an integer, found " +
               (slice.empty() ? std::string("blanks") : Quote(slice)));
  }
  return value;
}

}  // namespace femup::uff_internal
