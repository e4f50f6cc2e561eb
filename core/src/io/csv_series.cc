// CSV time series: reader with delimiter detection and strict checks, writer.
#include "femup/core/io/csv_series.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>
#include <utility>

#include "femup/core/errors.h"
#include "io/file_io.h"
#include "text_util.h"

namespace femup {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Blanks around a field; a tab is not trimmed when it is the delimiter (it
// cannot be inside a field then anyway).
std::string_view Trim(std::string_view s, char delimiter) {
  auto blank = [delimiter](char c) { return c != delimiter && IsBlank(c); };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::string Quote(std::string_view text) {
  constexpr size_t kMax = 60;
  if (text.size() > kMax) return "'" + std::string(text.substr(0, kMax)) + "...'";
  return "'" + std::string(text) + "'";
}

// One field of a row: its text, quotes removed.
struct Cell {
  std::string text;
  bool quoted = false;
};

// Splits a line at `delimiter` outside double quotes. Returns false (with the
// problem in *error) for an unterminated quote or text after a closing quote.
bool Split(std::string_view line, char delimiter, std::vector<Cell>* cells,
           std::string* error) {
  cells->clear();
  size_t i = 0;
  for (;;) {
    Cell cell;
    // Leading blanks.
    size_t start = i;
    while (start < line.size() && line[start] != delimiter && IsBlank(line[start]))
      ++start;
    if (start < line.size() && line[start] == '"') {
      cell.quoted = true;
      size_t j = start + 1;
      for (;;) {
        if (j >= line.size()) {
          *error = "column " + std::to_string(cells->size() + 1) + ": unterminated quote";
          return false;
        }
        if (line[j] == '"') {
          if (j + 1 < line.size() && line[j + 1] == '"') {
            cell.text += '"';
            j += 2;
            continue;
          }
          ++j;
          break;
        }
        cell.text += line[j++];
      }
      while (j < line.size() && line[j] != delimiter && IsBlank(line[j])) ++j;
      if (j < line.size() && line[j] != delimiter) {
        *error = "column " + std::to_string(cells->size() + 1) +
                 ": text after the closing quote";
        return false;
      }
      i = j;
    } else {
      size_t j = start;
      while (j < line.size() && line[j] != delimiter) ++j;
      cell.text = std::string(Trim(line.substr(start, j - start), delimiter));
      i = j;
    }
    cells->push_back(std::move(cell));
    if (i >= line.size()) break;
    ++i;  // the delimiter
  }
  return true;
}

// Count of `delimiter` outside quotes.
size_t CountOutsideQuotes(std::string_view line, char delimiter) {
  size_t n = 0;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (!quoted && c == delimiter) ++n;
  }
  return n;
}

enum class NumberStatus { kOk, kBad, kNotFinite, kDecimalComma };

// A whole field as a finite double, with its printed resolution: half a unit
// in the last printed digit (0.000333 -> 5e-7; 3.33e-4 -> 5e-7).
NumberStatus ParseNumber(std::string_view text, double* value, double* half_unit) {
  if (text.empty()) return NumberStatus::kBad;
  std::string lower;
  for (char c : text)
    lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string_view word =
      std::string_view(lower).substr(lower[0] == '+' || lower[0] == '-' ? 1 : 0);
  if (word == "nan" || word == "inf" || word == "infinity")
    return NumberStatus::kNotFinite;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (*first == '+') {
    ++first;
    if (first == last || *first == '+' || *first == '-') return NumberStatus::kBad;
  }
  for (const char* p = first; p != last; ++p) {
    const char c = *p;
    if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' ||
          c == '-')) {
      if (c == ',') return NumberStatus::kDecimalComma;
      return NumberStatus::kBad;
    }
  }
  double parsed = 0.0;
  const auto result = std::from_chars(first, last, parsed, std::chars_format::general);
  if (result.ptr != last || result.ec != std::errc()) return NumberStatus::kBad;
  if (!std::isfinite(parsed)) return NumberStatus::kNotFinite;
  *value = parsed;
  // Resolution: digits after the point and the exponent.
  const std::string_view body(first, static_cast<size_t>(last - first));
  const size_t e = body.find_first_of("eE");
  const std::string_view mantissa = body.substr(0, e);
  int exponent = 0;
  if (e != std::string_view::npos) {
    std::string_view exp_text = body.substr(e + 1);
    if (!exp_text.empty() && exp_text[0] == '+') exp_text.remove_prefix(1);
    std::from_chars(exp_text.data(), exp_text.data() + exp_text.size(), exponent);
  }
  const size_t point = mantissa.find('.');
  const int decimals =
      point == std::string_view::npos ? 0 : static_cast<int>(mantissa.size() - point - 1);
  *half_unit = 0.5 * std::pow(10.0, exponent - decimals);
  return NumberStatus::kOk;
}

class Parser {
 public:
  Parser(std::string_view text, std::string name, const CsvReadOptions& options)
      : text_(text), name_(std::move(name)), options_(options) {}

  CsvSeries Parse() {
    position_ = internal::AfterByteOrderMark(text_);
    std::string_view header;
    if (!NextContentLine(&header)) {
      throw InputError(name_, "no header line: the file is empty or holds only comments");
    }
    const long long header_line = line_;
    std::string_view first_row;
    const bool has_row = NextContentLine(&first_row);
    const long long first_row_line = line_;
    series_.delimiter = DetectDelimiter(header, has_row ? first_row : std::string_view());

    std::vector<Cell> cells;
    std::string error;
    if (!Split(header, series_.delimiter, &cells, &error)) {
      Fail(header_line, "header: " + error);
    }
    if (cells.size() < 2) {
      Fail(header_line,
           std::string("header: expected a time column and at least one "
                       "channel separated by commas, semicolons or tabs, got ") +
               std::to_string(cells.size()) + " column");
    }
    for (size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].text.empty()) {
        Fail(header_line,
             "column " + std::to_string(c + 1) + ": empty name in the header");
      }
    }
    names_.clear();
    for (const Cell& cell : cells) names_.push_back(cell.text);
    series_.time_name = names_[0];
    series_.channel_names.assign(names_.begin() + 1, names_.end());

    if (!has_row) {
      Fail(header_line + 1,
           "no data rows after the header; at least two samples are needed");
    }
    std::vector<double> data;
    std::vector<double> half_units;  // printed resolution of each time value
    std::vector<long long> lines;
    std::string_view row = first_row;
    long long row_line = first_row_line;
    const size_t width = names_.size();
    for (;;) {
      if (!Split(row, series_.delimiter, &cells, &error)) Fail(row_line, error);
      if (cells.size() != width) {
        Fail(row_line,
             "expected " + std::to_string(width) + " fields (as the header on line " +
                 std::to_string(header_line) + "), got " + std::to_string(cells.size()));
      }
      for (size_t c = 0; c < width; ++c) {
        double value = 0.0;
        double half_unit = 0.0;
        const std::string& text = cells[c].text;
        const NumberStatus status = ParseNumber(text, &value, &half_unit);
        if (status != NumberStatus::kOk) {
          std::string what = text.empty() ? std::string("empty field, expected a number")
                             : status == NumberStatus::kNotFinite
                                 ? "expected a finite number, found " + Quote(text)
                                 : "expected a number, found " + Quote(text);
          if (status == NumberStatus::kDecimalComma) {
            what += " (the decimal separator must be '.')";
          }
          Fail(row_line, Column(c) + ": " + what);
        }
        data.push_back(value);
        if (c == 0) half_units.push_back(half_unit);
      }
      lines.push_back(row_line);
      if (!NextContentLine(&row)) break;
      row_line = line_;
    }

    const size_t samples = lines.size();
    if (samples < 2) {
      Fail(lines[0], "only one sample; at least two are needed for a time step");
    }
    series_.time.resize(static_cast<Eigen::Index>(samples));
    series_.values.resize(static_cast<Eigen::Index>(samples),
                          static_cast<Eigen::Index>(width - 1));
    for (size_t r = 0; r < samples; ++r) {
      const auto i = static_cast<Eigen::Index>(r);
      series_.time(i) = data[r * width];
      for (size_t c = 1; c < width; ++c) {
        series_.values(i, static_cast<Eigen::Index>(c - 1)) = data[r * width + c];
      }
    }
    CheckTime(half_units, lines);
    return std::move(series_);
  }

 private:
  [[noreturn]] void Fail(long long line, const std::string& what) const {
    throw InputError(name_ + ": line " + std::to_string(line), what);
  }

  std::string Column(size_t c) const {
    return "column " + std::to_string(c + 1) + " (" + names_[c] + ")";
  }

  bool NextLine(std::string_view* line) {
    if (!internal::NextTextLine(text_, &position_, line)) return false;
    ++line_;
    return true;
  }

  // Next line that is neither blank nor a '#' comment.
  bool NextContentLine(std::string_view* line) {
    while (NextLine(line)) {
      size_t i = 0;
      while (i < line->size() && IsBlank((*line)[i])) ++i;
      if (i == line->size() || (*line)[i] == '#') continue;
      return true;
    }
    return false;
  }

  // The candidate that splits header and first row into the same number (at
  // least 2) of fields; tab before semicolon before comma, since a comma may
  // also be a decimal separator or part of a name.
  char DetectDelimiter(std::string_view header, std::string_view row) const {
    const char candidates[] = {'\t', ';', ','};
    for (char d : candidates) {
      const size_t in_header = CountOutsideQuotes(header, d);
      if (in_header == 0) continue;
      if (row.empty() || CountOutsideQuotes(row, d) == in_header) return d;
    }
    // No agreement: the header's most frequent candidate, so that the row
    // check reports the mismatch.
    char best = ',';
    size_t most = 0;
    for (char d : candidates) {
      const size_t n = CountOutsideQuotes(header, d);
      if (n > most) {
        most = n;
        best = d;
      }
    }
    return best;
  }

  // Each step is compared with the median step, so that the message points at
  // the odd one out; the reported step is the mean over the whole record.
  void CheckTime(const std::vector<double>& half_units,
                 const std::vector<long long>& lines) {
    const Eigen::VectorXd& t = series_.time;
    const Eigen::Index n = t.size();
    for (Eigen::Index k = 1; k < n; ++k) {
      const auto r = static_cast<size_t>(k);
      if (!(t(k) > t(k - 1))) {
        Fail(lines[r], Column(0) + ": time " + FormatNumber(t(k)) +
                           " does not increase (previous " + FormatNumber(t(k - 1)) +
                           " on line " + std::to_string(lines[r - 1]) + ")");
      }
    }
    std::vector<double> steps(static_cast<size_t>(n - 1));
    for (Eigen::Index k = 1; k < n; ++k)
      steps[static_cast<size_t>(k - 1)] = t(k) - t(k - 1);
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(),
                     sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                     sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (size_t r = 1; r < static_cast<size_t>(n); ++r) {
      const double dt = steps[r - 1];
      // Rounding of the two printed times, but never half a step or more: a
      // time printed to the step's own resolution (0.001 at 1 kHz) is exact.
      const double rounding = std::min(half_units[r] + half_units[r - 1], 0.5 * median);
      const double allowed = options_.relative_step_tolerance * median + rounding;
      if (std::abs(dt - median) > allowed) {
        Fail(lines[r], Column(0) + ": time step " + FormatNumber(dt) + " (from line " +
                           std::to_string(lines[r - 1]) +
                           ") differs from the median step " + FormatNumber(median) +
                           " by more than the tolerance " + FormatNumber(allowed) +
                           "; the sampling is not uniform");
      }
    }
    series_.time_step = (t(n - 1) - t(0)) / static_cast<double>(n - 1);
    series_.sample_rate_hz = 1.0 / series_.time_step;
  }

  static std::string FormatNumber(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", v);
    return buffer;
  }

  std::string_view text_;
  std::string name_;
  CsvReadOptions options_;
  size_t position_ = 0;
  long long line_ = 0;
  std::vector<std::string> names_;
  CsvSeries series_;
};

// A name as a CSV field, quoted when needed.
std::string Field(const std::string& name, char delimiter) {
  const bool quote = name.find(delimiter) != std::string::npos ||
                     name.find('"') != std::string::npos || name.empty() ||
                     name.front() == '#' || name.front() == ' ' || name.back() == ' ';
  if (!quote) return name;
  std::string out = "\"";
  for (char c : name) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

CsvSeries ParseCsvSeries(std::string_view text, const std::string& name,
                         const CsvReadOptions& options) {
  return Parser(text, name, options).Parse();
}

CsvSeries ReadCsvSeries(const std::string& path, const CsvReadOptions& options) {
  const std::string text = internal::ReadFileText(path, "CSV file");
  return ParseCsvSeries(text, path, options);
}

std::string FormatCsvSeries(const CsvSeries& series, const std::string& name) {
  const char d = series.delimiter;
  if (d != ',' && d != ';' && d != '\t') {
    throw InputError(name, "delimiter must be ',', ';' or tab");
  }
  const Eigen::Index samples = series.time.size();
  const auto channels = static_cast<Eigen::Index>(series.channel_names.size());
  if (series.values.rows() != samples || series.values.cols() != channels) {
    throw InputError(name, "values are " + std::to_string(series.values.rows()) + " x " +
                               std::to_string(series.values.cols()) + ", expected " +
                               std::to_string(samples) + " samples x " +
                               std::to_string(channels) + " channels");
  }
  std::vector<std::string> names = {series.time_name};
  names.insert(names.end(), series.channel_names.begin(), series.channel_names.end());
  std::string out;
  for (size_t c = 0; c < names.size(); ++c) {
    if (names[c].empty() || names[c].find_first_of("\r\n") != std::string::npos) {
      throw InputError(name, "column " + std::to_string(c + 1) +
                                 ": a name must be non-empty and on one line");
    }
    if (c > 0) out += d;
    out += Field(names[c], d);
  }
  out += '\n';
  char buffer[32];
  for (Eigen::Index i = 0; i < samples; ++i) {
    for (Eigen::Index c = 0; c <= channels; ++c) {
      const double v = c == 0 ? series.time(i) : series.values(i, c - 1);
      if (!std::isfinite(v)) {
        throw InputError(name, "sample " + std::to_string(i + 1) + ", column " +
                                   std::to_string(c + 1) + ": value is not finite");
      }
      if (c > 0) out += d;
      std::snprintf(buffer, sizeof buffer, "%.17g", v);
      out += buffer;
    }
    out += '\n';
  }
  return out;
}

void WriteCsvSeries(const std::string& path, const CsvSeries& series) {
  internal::WriteFileAtomically(path, FormatCsvSeries(series, path));
}

}  // namespace femup
