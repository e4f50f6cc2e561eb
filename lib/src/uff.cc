// Universal File Format datasets 15, 55, 58/58b and 2411: reader and writer.
//
// Reading works on the whole file in memory (binary 58b values may contain any
// byte, so lines are cut from a byte position rather than by a line stream).
// Numeric records are read blank-separated first; when blanks do not separate
// the values (a Fortran field filled to its width, e.g. "-1.234567890123E-100"
// after another value) they are read again by the columns of the record's
// layout. Text records (58 record 6 and records 8-11) are read by columns,
// counted in characters so that UTF-8 units such as "m/s²" keep their place.
#include "femup/uff.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <system_error>
#include <utility>

#include "femup/errors.h"
#include "file_io.h"
#include "text_util.h"

namespace femup {
namespace {

using internal::IsBlank;
using internal::Tokens;

// ---------------------------------------------------------------------------
// Text helpers.

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

std::string_view TrimRight(std::string_view s) {
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

// Quoted for messages, shortened when long.
std::string Quote(std::string_view text) {
  constexpr size_t kMax = 60;
  if (text.size() > kMax) return "'" + std::string(text.substr(0, kMax)) + "...'";
  return "'" + std::string(text) + "'";
}

bool IsUtf8Continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// Number of characters (UTF-8 code points) in `text`.
size_t CharCount(std::string_view text) {
  size_t n = 0;
  for (char c : text) n += IsUtf8Continuation(c) ? 0 : 1;
  return n;
}

// Byte offset of character `column` (0-based) in `line`, or line.size().
size_t ByteOffsetOfChar(std::string_view line, size_t column) {
  size_t chars = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    if (IsUtf8Continuation(line[i])) continue;
    if (chars == column) return i;
    ++chars;
  }
  return line.size();
}

// Characters [first, first + width) of `line` (0-based character columns);
// width < 0: to the end of the line.
std::string_view CharSlice(std::string_view line, size_t first, int width) {
  const size_t begin = ByteOffsetOfChar(line, first);
  if (width < 0) return line.substr(begin);
  const size_t end = ByteOffsetOfChar(line, first + static_cast<size_t>(width));
  return line.substr(begin, end - begin);
}

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
// Record layouts.

struct Field {
  const char* name;
  int width;  // columns of the Fortran layout
  bool integer;
};

// Numeric record layouts: a node of dataset 15, record 7 of dataset 58,
// record 6 of dataset 55.
const std::vector<Field> kNodeFields = {{"node label", 10, true},
                                        {"definition coordinate system", 10, true},
                                        {"displacement coordinate system", 10, true},
                                        {"color", 10, true},
                                        {"X coordinate", 13, false},
                                        {"Y coordinate", 13, false},
                                        {"Z coordinate", 13, false}};

// Dataset 2411: record 1 of a node (record 2 is three coordinates, 3D25.16).
const std::vector<Field> k2411Record1 = {{"node label", 10, true},
                                         {"export coordinate system", 10, true},
                                         {"displacement coordinate system", 10, true},
                                         {"color", 10, true}};
const std::vector<Field> k2411Record2 = {{"X coordinate", 25, false},
                                         {"Y coordinate", 25, false},
                                         {"Z coordinate", 25, false}};

const std::vector<Field> k58Record7 = {
    {"ordinate data type", 10, true},  {"number of points", 10, true},
    {"abscissa spacing", 10, true},    {"abscissa minimum", 13, false},
    {"abscissa increment", 13, false}, {"z-axis value", 13, false}};

const std::vector<Field> k55Record6 = {
    {"model type", 10, true},          {"analysis type", 10, true},
    {"data characteristic", 10, true}, {"specific data type", 10, true},
    {"data type", 10, true},           {"number of values per node", 10, true}};

// Record 8 of dataset 55 by analysis type.
const std::vector<Field> k55NormalMode = {{"frequency", 13, false},
                                          {"modal mass", 13, false},
                                          {"modal viscous damping ratio", 13, false},
                                          {"modal hysteretic damping ratio", 13, false}};
const std::vector<Field> k55ComplexMode = {
    {"real part of the eigenvalue", 13, false},
    {"imaginary part of the eigenvalue", 13, false},
    {"real part of modal A", 13, false},
    {"imaginary part of modal A", 13, false},
    {"real part of modal B", 13, false},
    {"imaginary part of modal B", 13, false}};
const std::vector<Field> k55FrequencyResponse = {{"frequency", 13, false}};

const char* const kAxisNames[4] = {"abscissa", "ordinate (numerator)",
                                   "ordinate denominator", "z-axis"};

std::string FieldList(const std::vector<Field>& fields) {
  std::string out;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) out += ", ";
    out += fields[i].name;
  }
  return out;
}

// One parsed numeric value of a record.
struct Value {
  double real = 0.0;
  int integer = 0;
};

// ---------------------------------------------------------------------------
// Reader.

class Reader {
 public:
  Reader(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {}

  UffFile Read() {
    position_ = internal::AfterByteOrderMark(text_);
    std::string_view line;
    while (NextLine(&line)) {
      if (Trim(line).empty()) continue;
      if (Trim(line) != "-1") {
        Fail(line_,
             "expected '    -1' opening a dataset, found " + Quote(TrimRight(line)));
      }
      ReadDataset();
    }
    return std::move(file_);
  }

 private:
  // Header of a dataset: its number and, for binary datasets, the fields after
  // the 'b'.
  struct Header {
    int number = 0;
    bool binary = false;
    int byte_ordering = 0;
    int fp_format = 0;
    int ascii_lines = 0;
    long long bytes = 0;
    long long line = 0;
  };

  std::string Where(long long line) const {
    return name_ + ": line " + std::to_string(line);
  }
  [[noreturn]] void Fail(long long line, const std::string& what) const {
    throw InputError(Where(line), what);
  }
  // A failure inside the current dataset, e.g. "dataset 58 record 7: ...".
  [[noreturn]] void FailIn(long long line, const std::string& record,
                           const std::string& what) const {
    Fail(line, dataset_ + " " + record + ": " + what);
  }
  void Note(long long line, const std::string& what) {
    file_.notes.push_back(Where(line) + ": " + what);
  }

  // Next line without its terminator (LF or CRLF); false at the end of the text.
  bool NextLine(std::string_view* line) {
    if (!internal::NextTextLine(text_, &position_, line)) return false;
    ++line_;
    return true;
  }

  // Next line of record `record`; a missing line is a truncated dataset.
  std::string_view RecordLine(const std::string& record) {
    std::string_view line;
    if (!NextLine(&line)) {
      FailIn(line_ + 1, record, "the file ends here; the dataset is truncated");
    }
    if (Trim(line) == "-1") {
      FailIn(line_, record,
             "found the end marker '-1' instead; the dataset is truncated");
    }
    return line;
  }

  // Next non-blank line of a dataset of records, false at its closing "-1"; a
  // file that ends first is a truncated dataset.
  bool NextLineBeforeEnd(std::string_view* line) {
    while (NextLine(line)) {
      if (Trim(*line) == "-1") return false;
      if (!Trim(*line).empty()) return true;
    }
    FailIn(line_ + 1, "end", "the file ends before the '    -1' closing the dataset");
  }

  // Skips blank lines and expects the closing "-1".
  void ExpectEnd(const std::string& after) {
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

  Header ReadHeader() {
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

  void ReadDataset() {
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
  void Skip(const Header& header) {
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

  void SkipBytes(size_t count, const std::string& what) {
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
  std::vector<Value> NumericRecord(std::string_view line,
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
  static std::string ParseField(std::string_view token, const Field& field, size_t index,
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

  static bool ByColumns(std::string_view line, const std::vector<Field>& fields,
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
  void ValueLine(std::string_view line, const std::vector<int>& widths, size_t wanted,
                 size_t first_index, const std::string& record,
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
  std::vector<double> ValueBlock(size_t count, const std::vector<int>& widths,
                                 const std::string& record, const std::string& what) {
    std::vector<double> values;
    // Not more than the rest of the file can hold (a value takes 2 bytes at
    // least), whatever the record declares.
    values.reserve(
        std::min(count, (text_.size() - std::min(position_, text_.size())) / 2));
    std::string_view line;
    while (values.size() < count) {
      if (!NextLine(&line)) {
        FailIn(line_ + 1, record,
               "the file ends after " + std::to_string(values.size()) + " of " +
                   std::to_string(count) + " " + what + "; the dataset is truncated");
      }
      if (Trim(line) == "-1") {
        FailIn(line_, record,
               "found the end marker '-1' after " + std::to_string(values.size()) +
                   " of " + std::to_string(count) + " " + what +
                   "; the dataset is truncated");
      }
      if (Trim(line).empty()) continue;
      ValueLine(line, widths, count - values.size(), values.size() + 1, record, &values);
    }
    return values;
  }

  std::array<std::string, 5> IdLines() {
    std::array<std::string, 5> ids;
    for (int i = 0; i < 5; ++i) {
      const std::string record =
          "record " + std::to_string(i + 1) + " (ID line " + std::to_string(i + 1) + ")";
      ids[static_cast<size_t>(i)] = std::string(TrimRight(RecordLine(record)));
    }
    return ids;
  }

  // An integer in character columns [first, first + width) of a text record.
  int IntColumn(std::string_view line, size_t first, int width, const char* name,
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

  // --- Dataset 15 -------------------------------------------------------------

  UffNodes Read15() {
    UffNodes out;
    std::string_view line;
    while (NextLineBeforeEnd(&line)) {
      const auto v = NumericRecord(line, kNodeFields, "node record");
      UffNode node;
      node.label = v[0].integer;
      node.definition_cs = v[1].integer;
      node.displacement_cs = v[2].integer;
      node.color = v[3].integer;
      node.xyz = {v[4].real, v[5].real, v[6].real};
      node.line = line_;
      out.nodes.push_back(node);
    }
    return out;
  }

  // --- Dataset 2411 -----------------------------------------------------------

  UffNodes Read2411() {
    UffNodes out;
    out.dataset = 2411;
    std::string_view line;
    while (NextLineBeforeEnd(&line)) {
      const std::string r1 =
          "record 1 (node " + std::to_string(out.nodes.size() + 1) + ")";
      const auto v1 = NumericRecord(line, k2411Record1, r1);
      UffNode node;
      node.label = v1[0].integer;
      node.definition_cs = v1[1].integer;
      node.displacement_cs = v1[2].integer;
      node.color = v1[3].integer;
      node.line = line_;
      const std::string r2 =
          "record 2 (coordinates of node " + std::to_string(node.label) + ")";
      const auto v2 = NumericRecord(RecordLine(r2), k2411Record2, r2);
      node.xyz = {v2[0].real, v2[1].real, v2[2].real};
      out.nodes.push_back(node);
    }
    return out;
  }

  // --- Dataset 55 -------------------------------------------------------------

  // False when the analysis type is not supported (skipped with a note).
  bool Read55(UffModeShape* shape) {
    shape->id_lines = IdLines();
    const std::string r6 = "record 6";
    const auto v6 = NumericRecord(RecordLine(r6), k55Record6, r6);
    const long long line6 = line_;
    shape->model_type = v6[0].integer;
    const int analysis = v6[1].integer;
    shape->data_characteristic = v6[2].integer;
    shape->specific_data_type = v6[3].integer;
    const int data_type = v6[4].integer;
    const int per_node = v6[5].integer;
    if (analysis != 2 && analysis != 3 && analysis != 5 && analysis != 7) {
      Note(line6, dataset_ + " with analysis type " + std::to_string(analysis) +
                      " is not supported (only 2 normal mode, 3 and 7 complex mode, 5 "
                      "frequency response); skipped");
      Skip(Header());  // an ASCII dataset: up to the next "-1"
      return false;
    }
    shape->analysis_type = static_cast<UffAnalysisType>(analysis);
    if (data_type != 2 && data_type != 5) {
      FailIn(line6, r6,
             "field 5 (data type): expected 2 (real) or 5 (complex), found " +
                 std::to_string(data_type));
    }
    shape->complex_data = data_type == 5;
    if (per_node < 1 || per_node > 9) {
      FailIn(line6, r6,
             "field 6 (number of values per node): expected 1 to 9, found " +
                 std::to_string(per_node));
    }
    const bool complex_mode = analysis == 3 || analysis == 7;
    const int reals = analysis == 2 ? 4 : complex_mode ? 6 : 1;
    const char* number_name = analysis == 5 ? "frequency step number" : "mode number";

    const std::string r7 = "record 7";
    const std::vector<Field> f7 = {{"number of integer values", 10, true},
                                   {"number of real values", 10, true},
                                   {"load case", 10, true},
                                   {number_name, 10, true}};
    const auto v7 = NumericRecord(RecordLine(r7), f7, r7);
    if (v7[0].integer != 2) {
      FailIn(line_, r7,
             "field 1 (number of integer values): expected 2, found " +
                 std::to_string(v7[0].integer));
    }
    if (v7[1].integer != reals) {
      FailIn(line_, r7,
             "field 2 (number of real values): expected " + std::to_string(reals) +
                 " for analysis type " + std::to_string(analysis) + ", found " +
                 std::to_string(v7[1].integer));
    }
    shape->load_case = v7[2].integer;
    shape->mode_number = v7[3].integer;

    const std::string r8 = "record 8";
    const std::vector<Field>& f8 = analysis == 2  ? k55NormalMode
                                   : complex_mode ? k55ComplexMode
                                                  : k55FrequencyResponse;
    const auto v8 = NumericRecord(RecordLine(r8), f8, r8);
    if (analysis == 2) {
      shape->frequency_hz = v8[0].real;
      shape->modal_mass = v8[1].real;
      shape->viscous_damping_ratio = v8[2].real;
      shape->hysteretic_damping_ratio = v8[3].real;
    } else if (complex_mode) {
      shape->eigenvalue = {v8[0].real, v8[1].real};
      shape->modal_a = {v8[2].real, v8[3].real};
      shape->modal_b = {v8[4].real, v8[5].real};
    } else {
      shape->frequency_hz = v8[0].real;
    }

    // Records 9 and 10 until the end marker.
    const size_t count = static_cast<size_t>(per_node) * (shape->complex_data ? 2 : 1);
    std::vector<std::vector<double>> rows;
    std::string_view line;
    while (NextLineBeforeEnd(&line)) {
      const std::string r9 = "record 9 (node " + std::to_string(rows.size() + 1) + ")";
      const auto v9 = NumericRecord(line, {{"node number", 10, true}}, r9);
      shape->nodes.push_back(v9[0].integer);
      shape->node_lines.push_back(line_);
      const std::string r10 =
          "record 10 (values of node " + std::to_string(v9[0].integer) + ")";
      rows.push_back(ValueBlock(count, {13}, r10, "values"));
    }
    shape->values.resize(static_cast<Eigen::Index>(rows.size()), per_node);
    for (size_t i = 0; i < rows.size(); ++i) {
      for (int j = 0; j < per_node; ++j) {
        const auto k = static_cast<size_t>(j);
        shape->values(static_cast<Eigen::Index>(i), j) =
            shape->complex_data ? std::complex<double>(rows[i][2 * k], rows[i][2 * k + 1])
                                : std::complex<double>(rows[i][k], 0.0);
      }
    }
    return true;
  }

  // --- Dataset 58 -------------------------------------------------------------

  UffAxis AxisRecord(int axis) {
    const std::string record = "record " + std::to_string(8 + axis) + " (" +
                               kAxisNames[axis] + " data characteristics)";
    const std::string_view line = RecordLine(record);
    // I10,3I5,2(1X,20A1)
    UffAxis out;
    out.specific_data_type = IntColumn(line, 0, 10, "specific data type", 1, record);
    out.length_exponent = IntColumn(line, 10, 5, "length units exponent", 2, record);
    out.force_exponent = IntColumn(line, 15, 5, "force units exponent", 3, record);
    out.temperature_exponent =
        IntColumn(line, 20, 5, "temperature units exponent", 4, record);
    out.label = std::string(Trim(CharSlice(line, 26, 20)));
    out.units = std::string(Trim(CharSlice(line, 47, -1)));
    return out;
  }

  UffFunction Read58(const Header& header) {
    UffFunction f;
    f.binary = header.binary;
    if (header.binary) {
      const std::string where = "header";
      if (header.byte_ordering != 1 && header.byte_ordering != 2) {
        FailIn(header.line, where,
               "field 1 (byte ordering): expected 1 (little-endian) or 2 (big-endian), "
               "found " +
                   std::to_string(header.byte_ordering));
      }
      if (header.fp_format != 2) {
        const char* known = header.fp_format == 1   ? " (DEC VMS)"
                            : header.fp_format == 3 ? " (IBM 5/370)"
                                                    : "";
        FailIn(header.line, where,
               "field 2 (floating-point format): " + std::to_string(header.fp_format) +
                   std::string(known) + " is not supported; only 2 (IEEE 754) is read");
      }
      if (header.ascii_lines != 11) {
        FailIn(header.line, where,
               "field 3 (number of ASCII lines): expected 11 (records 1-11), found " +
                   std::to_string(header.ascii_lines));
      }
    }
    f.id_lines = IdLines();

    // Record 6: 2(I5,I10),2(1X,10A1,I10,I4)
    const std::string r6 = "record 6";
    const std::string_view line6 = RecordLine(r6);
    f.function_type = IntColumn(line6, 0, 5, "function type", 1, r6);
    f.function_id = IntColumn(line6, 5, 10, "function identification number", 2, r6);
    f.version = IntColumn(line6, 15, 5, "version number", 3, r6);
    f.load_case = IntColumn(line6, 20, 10, "load case", 4, r6);
    f.response_entity = std::string(Trim(CharSlice(line6, 31, 10)));
    f.response_node = IntColumn(line6, 41, 10, "response node", 6, r6);
    f.response_direction = IntColumn(line6, 51, 4, "response direction", 7, r6);
    f.reference_entity = std::string(Trim(CharSlice(line6, 56, 10)));
    f.reference_node = IntColumn(line6, 66, 10, "reference node", 9, r6);
    f.reference_direction = IntColumn(line6, 76, 4, "reference direction", 10, r6);

    // Record 7: 3I10,3E13.5
    const std::string r7 = "record 7";
    const auto v7 = NumericRecord(RecordLine(r7), k58Record7, r7);
    const long long line7 = line_;
    const int type = v7[0].integer;
    if (type != 2 && type != 4 && type != 5 && type != 6) {
      FailIn(line7, r7,
             "field 1 (ordinate data type): expected 2 (real single), 4 (real double), 5 "
             "(complex single) or 6 (complex double), found " +
                 std::to_string(type));
    }
    f.ordinate_type = static_cast<UffOrdinateType>(type);
    const int points = v7[1].integer;
    if (points < 1) {
      FailIn(line7, r7,
             "field 2 (number of points): expected at least 1, found " +
                 std::to_string(points));
    }
    if (v7[2].integer != 0 && v7[2].integer != 1) {
      FailIn(line7, r7,
             "field 3 (abscissa spacing): expected 0 (uneven) or 1 (even), found " +
                 std::to_string(v7[2].integer));
    }
    f.even_spacing = v7[2].integer == 1;
    f.abscissa_start = v7[3].real;
    f.abscissa_increment = v7[4].real;
    f.z_axis_value = v7[5].real;
    if (f.even_spacing && points > 1 && f.abscissa_increment == 0.0) {
      FailIn(line7, r7, "field 5 (abscissa increment): 0 with even spacing");
    }

    f.abscissa_axis = AxisRecord(0);
    f.ordinate_axis = AxisRecord(1);
    f.denominator_axis = AxisRecord(2);
    f.z_axis = AxisRecord(3);

    // Record 12.
    const bool complex = f.IsComplex();
    const bool single = !f.IsDoublePrecision();
    const size_t n = static_cast<size_t>(points);
    const size_t per_point = (complex ? 2 : 1) + (f.even_spacing ? 0 : 1);
    const size_t count = n * per_point;
    std::vector<double> values;
    const std::string r12 = "record 12 (data values)";
    if (header.binary) {
      values = BinaryValues(header, count, single ? 4 : 8, r12);
    } else {
      std::vector<int> widths;
      if (single) {
        widths = {13};
      } else if (f.even_spacing) {
        widths = {20};
      } else if (complex) {
        widths = {13, 20, 20};
      } else {
        widths = {13, 20};
      }
      values = ValueBlock(count, widths, r12,
                          "values (" + std::to_string(n) + " points of " +
                              std::to_string(per_point) + ")");
    }
    ExpectEnd(std::to_string(count) + " data values");

    f.x.resize(points);
    f.y.resize(points);
    for (size_t k = 0; k < n; ++k) {
      const double* p = values.data() + k * per_point;
      const auto i = static_cast<Eigen::Index>(k);
      if (f.even_spacing) {
        f.x(i) = f.abscissa_start + static_cast<double>(k) * f.abscissa_increment;
      } else {
        f.x(i) = *p++;
      }
      f.y(i) =
          complex ? std::complex<double>(p[0], p[1]) : std::complex<double>(p[0], 0.0);
    }
    return f;
  }

  std::vector<double> BinaryValues(const Header& header, size_t count, size_t size,
                                   const std::string& record) {
    const size_t expected = count * size;
    const long long start_line = line_ + 1;
    const size_t left = text_.size() - std::min(position_, text_.size());
    if (static_cast<size_t>(header.bytes) != expected) {
      // pyuff writes the byte count of a real even function also for complex
      // and uneven ones. Trust record 7 when the end marker follows its count.
      bool end_follows = false;
      if (left >= expected) {
        std::string_view after = text_.substr(position_ + expected, 16);
        while (!after.empty() && (IsBlank(after.front()) || after.front() == '\n')) {
          after.remove_prefix(1);
        }
        end_follows = after.substr(0, 2) == "-1" &&
                      (after.size() == 2 || after[2] == '\n' || IsBlank(after[2]));
      }
      if (!end_follows) {
        FailIn(header.line, "header",
               "field 4 (number of bytes): " + std::to_string(header.bytes) +
                   ", but record 7 declares " + std::to_string(count) + " values of " +
                   std::to_string(size) + " bytes (" + std::to_string(expected) + ")");
      }
      Note(header.line, dataset_ + ": the header declares " +
                            std::to_string(header.bytes) + " bytes, record 7 implies " +
                            std::to_string(expected) + "; read " +
                            std::to_string(expected) + " (the end marker follows them)");
    }
    if (left < expected) {
      FailIn(start_line, record,
             "expected " + std::to_string(expected) +
                 " bytes of binary values, the file has " + std::to_string(left) +
                 " left; the dataset is truncated");
    }
    const bool little = header.byte_ordering == 1;
    std::vector<double> values(count);
    const auto* bytes = reinterpret_cast<const unsigned char*>(text_.data() + position_);
    for (size_t k = 0; k < count; ++k) {
      const unsigned char* p = bytes + k * size;
      std::uint64_t bits = 0;
      for (size_t b = 0; b < size; ++b) {
        const size_t shift = 8 * (little ? b : size - 1 - b);
        bits |= static_cast<std::uint64_t>(p[b]) << shift;
      }
      double v = 0.0;
      if (size == 4) {
        const auto bits32 = static_cast<std::uint32_t>(bits);
        float f = 0.0f;
        std::memcpy(&f, &bits32, sizeof f);
        v = f;
      } else {
        std::memcpy(&v, &bits, sizeof v);
      }
      if (!std::isfinite(v)) {
        FailIn(start_line, record,
               "binary value " + std::to_string(k + 1) + " of " + std::to_string(count) +
                   " is not finite");
      }
      values[k] = v;
    }
    SkipBytes(expected, record);
    return values;
  }

  std::string_view text_;
  std::string name_;
  size_t position_ = 0;
  long long line_ = 0;
  std::string dataset_;
  UffFile file_;
};

// ---------------------------------------------------------------------------
// Writer.

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void AppendF(std::string* out, const char* format, ...) {
  char buffer[256];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  if (n > 0) out->append(buffer, std::min(static_cast<size_t>(n), sizeof buffer - 1));
}

class Writer {
 public:
  explicit Writer(std::string name) : name_(std::move(name)) {}

  std::string Format(const std::vector<UffDataset>& datasets) {
    for (size_t i = 0; i < datasets.size(); ++i) {
      index_ = i;
      std::visit([this](const auto& d) { Write(d); }, datasets[i]);
    }
    return std::move(out_);
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(name_, "dataset " + std::to_string(index_) + " (" +
                                std::to_string(number_) + "): " + what);
  }

  std::string Text(const std::string& text, size_t width,
                   const std::string& field) const {
    if (text.find_first_of("\r\n") != std::string::npos) {
      Fail(field + ": text contains a line break");
    }
    const std::string value = text.empty() ? std::string("NONE") : text;
    const size_t chars = CharCount(value);
    if (chars > width) {
      Fail(field + ": " + Quote(value) + " has " + std::to_string(chars) +
           " characters, the field holds " + std::to_string(width));
    }
    return value + std::string(width - chars, ' ');
  }

  // A text field right-trimmed when it ends the line.
  std::string LastText(const std::string& text, size_t width,
                       const std::string& field) const {
    return std::string(TrimRight(Text(text, width, field)));
  }

  int Int(long long value, int width, const std::string& field) const {
    const std::string text = std::to_string(value);
    if (static_cast<int>(text.size()) > width) {
      Fail(field + ": " + text + " does not fit " + std::to_string(width) + " columns");
    }
    return static_cast<int>(value);
  }

  double Real(double value, const std::string& field) const {
    if (!std::isfinite(value)) Fail(field + ": value is not finite");
    return value;
  }

  void Begin(int number, const char* suffix = "") {
    number_ = number;
    AppendF(&out_, "%6d\n%6d%s", -1, number, suffix);
  }
  void End() { out_ += "    -1\n"; }

  void IdLines(const std::array<std::string, 5>& ids) {
    for (size_t i = 0; i < 5; ++i) {
      out_ += Text(ids[i], 80, "ID line " + std::to_string(i + 1));
      out_ += '\n';
    }
  }

  // --- 15 and 2411 ---
  void Write(const UffNodes& d) {
    number_ = d.dataset;
    if (d.dataset != 15 && d.dataset != 2411) {
      Fail("dataset " + std::to_string(d.dataset) + ": nodes are written as 15 or 2411");
    }
    for (size_t k = 0; k < d.nodes.size(); ++k) {
      const UffNode& node = d.nodes[k];
      const std::string where = "node " + std::to_string(k + 1);
      Int(node.label, 10, where + " label");
      Int(node.definition_cs, 10, where + " definition coordinate system");
      Int(node.displacement_cs, 10, where + " displacement coordinate system");
      Int(node.color, 10, where + " color");
      for (int c = 0; c < 3; ++c)
        Real(node.xyz[static_cast<size_t>(c)], where + " coordinates");
    }
    Begin(d.dataset);
    out_ += std::string(74, ' ') + "\n";
    for (const UffNode& node : d.nodes) {
      if (d.dataset == 15) {
        AppendF(&out_, "%10d%10d%10d%10d%13.5E%13.5E%13.5E\n", node.label,
                node.definition_cs, node.displacement_cs, node.color, node.xyz[0],
                node.xyz[1], node.xyz[2]);
      } else {
        AppendF(&out_, "%10d%10d%10d%10d\n%25.16E%25.16E%25.16E\n", node.label,
                node.definition_cs, node.displacement_cs, node.color, node.xyz[0],
                node.xyz[1], node.xyz[2]);
      }
    }
    End();
  }

  // Values in lines of `per_line` fields of format `format`.
  void Lines(const std::vector<double>& values, size_t per_line, const char* format) {
    for (size_t k = 0; k < values.size(); ++k) {
      AppendF(&out_, format, values[k]);
      if ((k + 1) % per_line == 0 || k + 1 == values.size()) out_ += '\n';
    }
  }

  // --- 55 ---
  void Write(const UffModeShape& d) {
    number_ = 55;
    const auto analysis = static_cast<int>(d.analysis_type);
    if (analysis != 2 && analysis != 3 && analysis != 5 && analysis != 7) {
      Fail("analysis type " + std::to_string(analysis) + " is not supported");
    }
    const auto rows = static_cast<size_t>(d.values.rows());
    const auto per_node = static_cast<int>(d.values.cols());
    if (rows != d.nodes.size()) {
      Fail("values has " + std::to_string(rows) + " rows for " +
           std::to_string(d.nodes.size()) + " nodes");
    }
    if (per_node < 1 || per_node > 9) {
      Fail("values has " + std::to_string(per_node) +
           " columns; expected 1 to 9 per node");
    }
    if (!d.complex_data && rows > 0 && d.values.imag().cwiseAbs().maxCoeff() != 0.0) {
      Fail("values have imaginary parts but complex_data is false");
    }
    Int(d.model_type, 10, "model type");
    Int(d.data_characteristic, 10, "data characteristic");
    Int(d.specific_data_type, 10, "specific data type");
    Int(d.load_case, 10, "load case");
    Int(d.mode_number, 10, "mode number");

    std::vector<double> header;
    if (analysis == 2) {
      header = {d.frequency_hz, d.modal_mass, d.viscous_damping_ratio,
                d.hysteretic_damping_ratio};
    } else if (analysis == 5) {
      header = {d.frequency_hz};
    } else {
      header = {d.eigenvalue.real(), d.eigenvalue.imag(), d.modal_a.real(),
                d.modal_a.imag(),    d.modal_b.real(),    d.modal_b.imag()};
    }
    for (double v : header) Real(v, "record 8");

    Begin(55);
    out_ += std::string(74, ' ') + "\n";
    IdLines(d.id_lines);
    AppendF(&out_, "%10d%10d%10d%10d%10d%10d\n", d.model_type, analysis,
            d.data_characteristic, d.specific_data_type, d.complex_data ? 5 : 2,
            per_node);
    AppendF(&out_, "%10d%10d%10d%10d\n", 2, static_cast<int>(header.size()), d.load_case,
            d.mode_number);
    Lines(header, 6, "%13.5E");
    std::vector<double> row;
    for (size_t i = 0; i < rows; ++i) {
      Int(d.nodes[i], 10, "node " + std::to_string(i + 1));
      AppendF(&out_, "%10d\n", d.nodes[i]);
      row.clear();
      for (int j = 0; j < per_node; ++j) {
        const std::complex<double> v = d.values(static_cast<Eigen::Index>(i), j);
        row.push_back(Real(v.real(), "values of node " + std::to_string(d.nodes[i])));
        if (d.complex_data) {
          row.push_back(Real(v.imag(), "values of node " + std::to_string(d.nodes[i])));
        }
      }
      Lines(row, 6, "%13.5E");
    }
    End();
  }

  // --- 58 ---
  void AxisLine(const UffAxis& axis, int index) {
    const std::string field = std::string(kAxisNames[index]) + " axis";
    Int(axis.specific_data_type, 10, field + " specific data type");
    Int(axis.length_exponent, 5, field + " length units exponent");
    Int(axis.force_exponent, 5, field + " force units exponent");
    Int(axis.temperature_exponent, 5, field + " temperature units exponent");
    const std::string label = Text(axis.label, 20, field + " label");
    const std::string units = Text(axis.units, 20, field + " units");
    AppendF(&out_, "%10d%5d%5d%5d ", axis.specific_data_type, axis.length_exponent,
            axis.force_exponent, axis.temperature_exponent);
    out_ += label + " " + units + "\n";
  }

  void Write(const UffFunction& d) {
    number_ = 58;
    const auto type = static_cast<int>(d.ordinate_type);
    if (type != 2 && type != 4 && type != 5 && type != 6) {
      Fail("ordinate data type " + std::to_string(type) + " is not 2, 4, 5 or 6");
    }
    const auto n = static_cast<size_t>(d.y.size());
    if (n == 0) Fail("no data values");
    Int(static_cast<long long>(n), 10, "number of points");
    if (!d.even_spacing && static_cast<size_t>(d.x.size()) != n) {
      Fail("uneven spacing needs one abscissa value per point: x has " +
           std::to_string(d.x.size()) + ", y has " + std::to_string(n));
    }
    const bool complex = d.IsComplex();
    const bool single = !d.IsDoublePrecision();
    if (d.even_spacing && n > 1 && d.abscissa_increment == 0.0) {
      Fail("abscissa increment is 0 with even spacing");
    }

    // Record 12 values in file order.
    std::vector<double> values;
    values.reserve(n * 3);
    for (size_t k = 0; k < n; ++k) {
      const auto i = static_cast<Eigen::Index>(k);
      const std::string where = "point " + std::to_string(k + 1);
      if (!d.even_spacing) values.push_back(Real(d.x(i), where + " abscissa"));
      values.push_back(Real(d.y(i).real(), where + " ordinate"));
      if (complex) {
        values.push_back(Real(d.y(i).imag(), where + " ordinate"));
      } else if (d.y(i).imag() != 0.0) {
        Fail(where + ": ordinate has an imaginary part but the ordinate data type " +
             std::to_string(type) + " is real");
      }
    }
    if (single) {
      for (size_t k = 0; k < values.size(); ++k) {
        if (std::abs(values[k]) >
            static_cast<double>(std::numeric_limits<float>::max())) {
          Fail("value " + std::to_string(k + 1) + " does not fit single precision");
        }
      }
    }

    // Fields checked before the records are assembled.
    std::string ids;
    for (size_t i = 0; i < 5; ++i) {
      ids += Text(d.id_lines[i], 80, "ID line " + std::to_string(i + 1)) + "\n";
    }
    Int(d.function_type, 5, "function type");
    Int(d.function_id, 10, "function identification number");
    Int(d.version, 5, "version number");
    Int(d.load_case, 10, "load case");
    const std::string response = Text(d.response_entity, 10, "response entity name");
    Int(d.response_node, 10, "response node");
    Int(d.response_direction, 4, "response direction");
    const std::string reference = Text(d.reference_entity, 10, "reference entity name");
    Int(d.reference_node, 10, "reference node");
    Int(d.reference_direction, 4, "reference direction");
    const double start =
        d.even_spacing ? Real(d.abscissa_start, "abscissa minimum") : 0.0;
    const double step =
        d.even_spacing ? Real(d.abscissa_increment, "abscissa increment") : 0.0;
    Real(d.z_axis_value, "z-axis value");

    const size_t size = single ? 4 : 8;
    if (d.binary) {
      const size_t bytes = values.size() * size;
      if (bytes > static_cast<size_t>(std::numeric_limits<int>::max())) {
        Fail("too many values for one 58b dataset");
      }
      Begin(58, "");
      AppendF(&out_, "b%6d%6d%12d%12d%6d%6d%12d%12d\n", 1, 2, 11, static_cast<int>(bytes),
              0, 0, 0, 0);
    } else {
      Begin(58);
      out_ += std::string(74, ' ') + "\n";
    }
    out_ += ids;
    AppendF(&out_, "%5d%10d%5d%10d ", d.function_type, d.function_id, d.version,
            d.load_case);
    AppendF(&out_, "%s%10d%4d ", response.c_str(), d.response_node, d.response_direction);
    AppendF(&out_, "%s%10d%4d\n", reference.c_str(), d.reference_node,
            d.reference_direction);
    AppendF(&out_, "%10d%10d%10d%13.5E%13.5E%13.5E\n", type, static_cast<int>(n),
            d.even_spacing ? 1 : 0, start, step, d.z_axis_value);
    AxisLine(d.abscissa_axis, 0);
    AxisLine(d.ordinate_axis, 1);
    AxisLine(d.denominator_axis, 2);
    AxisLine(d.z_axis, 3);

    if (d.binary) {
      // Little-endian IEEE, whatever the host; the end marker follows at once
      // (as pyuff writes and reads it).
      for (double v : values) {
        std::uint64_t bits = 0;
        if (single) {
          const auto f = static_cast<float>(v);
          std::uint32_t bits32 = 0;
          std::memcpy(&bits32, &f, sizeof f);
          bits = bits32;
        } else {
          std::memcpy(&bits, &v, sizeof v);
        }
        for (size_t b = 0; b < size; ++b) {
          out_ += static_cast<char>((bits >> (8 * b)) & 0xFF);
        }
      }
    } else if (single) {
      Lines(values, 6, "%13.5E");
    } else if (d.even_spacing) {
      Lines(values, 4, "%20.11E");
    } else {
      // 2(E13.5,E20.12) for real, E13.5,2E20.12 for complex: the abscissa in
      // the narrow field.
      const size_t per_point = complex ? 3 : 2;
      const size_t per_line = complex ? 3 : 4;
      for (size_t k = 0; k < values.size(); ++k) {
        AppendF(&out_, k % per_point == 0 ? "%13.5E" : "%20.11E", values[k]);
        if ((k + 1) % per_line == 0 || k + 1 == values.size()) out_ += '\n';
      }
    }
    End();
  }

  std::string name_;
  std::string out_;
  size_t index_ = 0;
  int number_ = 0;
};

template <typename T>
std::vector<const T*> Select(const std::vector<UffDataset>& datasets) {
  std::vector<const T*> out;
  for (const auto& d : datasets) {
    if (const T* p = std::get_if<T>(&d)) out.push_back(p);
  }
  return out;
}

}  // namespace

std::vector<const UffNodes*> UffFile::Nodes() const { return Select<UffNodes>(datasets); }
std::vector<const UffModeShape*> UffFile::ModeShapes() const {
  return Select<UffModeShape>(datasets);
}
std::vector<const UffFunction*> UffFile::Functions() const {
  return Select<UffFunction>(datasets);
}

UffFile ParseUff(std::string_view contents, const std::string& name) {
  return Reader(contents, name).Read();
}

UffFile ReadUff(const std::string& path) {
  const std::string text = internal::ReadFileText(path, "UFF file");
  return ParseUff(text, path);
}

std::string FormatUff(const std::vector<UffDataset>& datasets, const std::string& name) {
  return Writer(name).Format(datasets);
}

void WriteUff(const std::string& path, const std::vector<UffDataset>& datasets) {
  internal::WriteFileAtomically(path, FormatUff(datasets, path));
}

}  // namespace femup
