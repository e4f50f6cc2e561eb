// Time series in CSV files, as data loggers and scripts export them: a header
// line with the column names (time first, then one name per channel) and one
// row of numbers per sample.
//
//   # optional comment lines start with '#', anywhere
//   time,acc1,acc2
//   0.000,0.12,-0.5
//   0.001,0.15,-0.4
//
// The delimiter (comma, semicolon or tab) is detected from the header and the
// first data row. Fields may be enclosed in double quotes ("" for a quote
// inside). Blank lines, CRLF line endings, a UTF-8 byte order mark and blanks
// around fields are accepted. Everything else is checked: every row has as
// many fields as the header, every field is a whole finite number (no silent
// NaN: "nan", "1.5x" or an empty field are errors, and so is a decimal comma),
// time increases with a uniform step. Errors throw InputError naming the file,
// the line and the column.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace femup {

struct CsvSeries {
  std::string time_name;                   // header of the first column
  std::vector<std::string> channel_names;  // headers of the other columns
  Eigen::VectorXd time;                    // one entry per sample
  Eigen::MatrixXd values;                  // samples x channels
  // Set by the reader: the mean step (last - first time) / (samples - 1) and
  // its inverse. The writer does not use them.
  double time_step = 0.0;
  double sample_rate_hz = 0.0;
  // Detected by the reader; used by the writer (',', ';' or '\t').
  char delimiter = ',';
};

struct CsvReadOptions {
  // A step may differ from the median step by this fraction of it, plus the
  // rounding of the printed time values (half a unit in the last printed
  // digit of each of the two times, at most half a step). So times printed
  // with few digits, such as 0.000333 for 3 kHz, pass; a missing or repeated
  // sample does not, and the message names the row after the odd step.
  double relative_step_tolerance = 1e-6;
};

// Reads the file at `path`. Throws InputError (file, line, column) for a
// missing file, no header, fewer than two columns, no data rows (at least two
// samples are needed for a step), a row of another width, a field that is not a
// finite number, or a time step that is not uniform.
CsvSeries ReadCsvSeries(const std::string& path, const CsvReadOptions& options = {});
// The same for text already in memory; `name` stands for the file in messages.
CsvSeries ParseCsvSeries(std::string_view text, const std::string& name,
                         const CsvReadOptions& options = {});

// Writes the header and one row per sample with series.delimiter, numbers with
// 17 significant digits (they read back to the same doubles). Names that hold
// the delimiter, a quote or a leading '#' are quoted. Throws InputError naming
// the path for sizes that disagree, non-finite values, names with line breaks,
// or a delimiter other than ',', ';' or tab. Written through a temporary file
// and a rename.
void WriteCsvSeries(const std::string& path, const CsvSeries& series);
// The same, to a string; `name` stands for the file in messages.
std::string FormatCsvSeries(const CsvSeries& series, const std::string& name);

}  // namespace femup
