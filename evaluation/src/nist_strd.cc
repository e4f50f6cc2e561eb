// NIST StRD datasets: reading the .dat files (ReadNistLinear,
// ReadNistNonlinear: header, certified values, data) and the log relative
// error used to score results against them. The nonlinear models themselves
// are in nist_strd_models.cc.
#include "femup/evaluation/nist_strd.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace {

// ---------------------------------------------------------------------------
// Reading the .dat files. NIST's files share one layout: a header whose "File
// Format:" section gives the line ranges of the starting values, certified values
// and data, a "Data:" description (counts of predictors and observations, level
// of difficulty), a "Model:" section (parameter count and formula), then the
// certified values and the data at the stated lines.

std::vector<std::string> Tokens(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  std::string token;
  while (in >> token) out.push_back(token);
  return out;
}

std::string Trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

bool StartsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

// Whole-token number parse with strtold; false unless the token is a finite
// number and nothing else.
bool ParseLongDouble(const std::string& token, LongDouble* value) {
  if (token.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const LongDouble v = std::strtold(token.c_str(), &end);
  if (end != token.c_str() + token.size() || errno == ERANGE || !std::isfinite(v)) {
    return false;
  }
  *value = v;
  return true;
}

bool ParseInt(const std::string& token, int* value) {
  if (token.empty() || token.size() > 9) return false;
  for (char c : token) {
    if (c < '0' || c > '9') return false;
  }
  *value = std::stoi(token);
  return true;
}

class DatFile {
 public:
  explicit DatFile(const std::string& path) : path_(path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      std::error_code ec;
      const bool exists = std::filesystem::exists(path, ec);
      throw InputError(path, exists ? "cannot open the NIST StRD file for reading"
                                    : "NIST StRD file not found");
    }
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines_.push_back(line);
    }
    if (in.bad()) throw InputError(path, "error while reading the NIST StRD file");
  }

  const std::string& path() const { return path_; }
  int num_lines() const { return static_cast<int>(lines_.size()); }
  // 1-based, as NIST numbers them.
  const std::string& Line(int number) const { return lines_[number - 1]; }

  [[noreturn]] void Fail(int line, const std::string& what) const {
    throw InputError(path_ + ":" + std::to_string(line), what);
  }

  // The first line in [from, to] (1-based, clipped to the file) whose trimmed
  // text starts with `prefix`, or 0.
  int Find(const std::string& prefix, int from = 1, int to = -1) const {
    if (to < 0 || to > num_lines()) to = num_lines();
    for (int k = std::max(from, 1); k <= to; ++k) {
      if (StartsWith(Trim(Line(k)), prefix)) return k;
    }
    return 0;
  }

  // The first line in [from, to] containing `text`, or 0.
  int FindContaining(const std::string& text, int from, int to) const {
    to = std::min(to, num_lines());
    for (int k = std::max(from, 1); k <= to; ++k) {
      if (Line(k).find(text) != std::string::npos) return k;
    }
    return 0;
  }

  // Line `number`, failing with "expected <what>, found end of file" past the end.
  const std::string& Need(int number, const std::string& what) const {
    if (number > num_lines()) Fail(number, "expected " + what + ", found end of file");
    return Line(number);
  }

  LongDouble Number(int line, const std::string& token, const std::string& what) const {
    LongDouble v = 0;
    if (!ParseLongDouble(token, &v)) {
      Fail(line, "expected " + what + " (a finite number), found '" + token + "'");
    }
    return v;
  }

 private:
  std::string path_;
  std::vector<std::string> lines_;
};

struct LineRange {
  int first = 0, last = 0;
};

// The common header, up to (not including) the certified values.
struct Header {
  std::string name;
  std::string difficulty;
  std::string model;
  int num_predictors = 0;
  int num_observations = 0;
  int num_parameters = 0;
  int model_line = 0;  // the "N Parameters" line
  LineRange starting, certified, data;
};

// "Certified Values  (lines 31 to 55)" in the File Format section.
LineRange ReadRange(const DatFile& file, int format_line, int section_end,
                    const std::string& label) {
  const int k = file.FindContaining(label, format_line, section_end);
  if (k == 0) {
    file.Fail(format_line, "expected a line '" + label +
                               " (lines A to B)' in the File Format section");
  }
  const std::string& text = file.Line(k);
  const auto open = text.find("(lines", text.find(label));
  std::vector<std::string> t;
  if (open != std::string::npos) {
    const auto close = text.find(')', open);
    if (close != std::string::npos) t = Tokens(text.substr(open + 1, close - open - 1));
  }
  LineRange range;
  if (t.size() != 4 || t[0] != "lines" || t[2] != "to" || !ParseInt(t[1], &range.first) ||
      !ParseInt(t[3], &range.last) || range.first < 1 || range.last < range.first) {
    file.Fail(k, "expected '" + label + " (lines A to B)' with 1 <= A <= B");
  }
  return range;
}

// The integer before `word` on a line of the Data: description ("82 Observations").
int CountBefore(const DatFile& file, int from, int to, const std::string& word,
                const std::string& what) {
  for (int k = from; k <= std::min(to, file.num_lines()); ++k) {
    const std::vector<std::string> t = Tokens(file.Line(k));
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (StartsWith(t[i], word)) {
        int n = 0;
        if (!ParseInt(t[i - 1], &n) || n < 1) {
          file.Fail(k, "expected a positive count before '" + t[i] + "'");
        }
        return n;
      }
    }
  }
  file.Fail(from, "expected the number of " + what + " ('N " + word + "...') in lines " +
                      std::to_string(from) + " to " + std::to_string(to));
}

Header ReadHeader(const DatFile& file, const std::string& procedure) {
  Header h;
  if (file.num_lines() == 0) {
    file.Fail(1, "expected 'NIST/ITL StRD', found an empty file");
  }
  if (Trim(file.Line(1)) != "NIST/ITL StRD") {
    file.Fail(1, "expected the first line 'NIST/ITL StRD'");
  }
  const int name_line = file.Find("Dataset Name:", 1, 5);
  if (name_line == 0) file.Fail(2, "expected a line 'Dataset Name:  <name> (<file>)'");
  const std::vector<std::string> name_tokens = Tokens(file.Line(name_line));
  if (name_tokens.size() < 3) file.Fail(name_line, "expected a dataset name");
  h.name = name_tokens[2];

  const int format_line = file.Find("File Format:");
  const int procedure_line = file.Find("Procedure:");
  if (format_line == 0) file.Fail(name_line + 1, "expected a 'File Format:' section");
  if (procedure_line == 0 || procedure_line < format_line) {
    file.Fail(format_line + 1,
              "expected a 'Procedure:' line after the File Format section");
  }
  const std::string proc = Trim(Trim(file.Line(procedure_line)).substr(10));
  if (proc != procedure) {
    file.Fail(procedure_line,
              "expected 'Procedure: " + procedure + "', found '" + proc + "'");
  }
  if (procedure != "Linear Least Squares Regression") {
    h.starting = ReadRange(file, format_line, procedure_line, "Starting Values");
  }
  h.certified = ReadRange(file, format_line, procedure_line, "Certified Values");
  h.data = ReadRange(file, format_line, procedure_line, "Data");

  // "Data:  1 Response ..." (the description; the data's own "Data:  y  x" line
  // comes later, just before the data).
  const int description = file.Find("Data:", procedure_line);
  const int model_line = file.Find("Model:", procedure_line);
  if (description == 0) file.Fail(procedure_line + 1, "expected a 'Data:' description");
  if (model_line == 0) {
    file.Fail(
        file.num_lines() + 1,
        "expected a 'Model:' section after the Data description, found end of file");
  }
  if (model_line < description) {
    file.Fail(model_line, "expected the 'Data:' description before the 'Model:' section");
  }
  h.num_predictors =
      CountBefore(file, description, model_line - 1, "Predictor", "predictor variables");
  h.num_observations =
      CountBefore(file, description, model_line - 1, "Observations", "observations");
  for (int k = description; k < model_line; ++k) {
    const std::vector<std::string> t = Tokens(file.Line(k));
    if (t.size() >= 4 && t[1] == "Level" && t[2] == "of" && t[3] == "Difficulty") {
      h.difficulty = t[0];
    }
  }
  if (h.difficulty != "Lower" && h.difficulty != "Average" && h.difficulty != "Higher") {
    file.Fail(description,
              "expected a line '<Lower|Average|Higher> Level of Difficulty' "
              "in the Data description");
  }
  const int section_end =
      std::min(h.certified.first,
               h.starting.first > 0 ? h.starting.first : h.certified.first) -
      1;
  h.num_parameters = CountBefore(file, model_line, std::min(model_line + 2, section_end),
                                 "Parameter", "parameters");
  for (int k = model_line; k <= std::min(model_line + 2, file.num_lines()); ++k) {
    if (file.Line(k).find("Parameter") != std::string::npos) h.model_line = k;
  }
  // The formula: the nonblank lines after the parameter count, up to the table.
  for (int k = h.model_line + 1; k <= std::min(section_end, file.num_lines()); ++k) {
    const std::string text = Trim(file.Line(k));
    if (text.find("Certified") != std::string::npos ||
        text.find("Starting") != std::string::npos ||
        text.find("Start 1") != std::string::npos) {
      break;
    }
    if (!text.empty()) h.model += (h.model.empty() ? "" : "\n") + text;
  }
  if (h.model.empty()) file.Fail(h.model_line + 1, "expected the model formula");
  return h;
}

// Data lines [range.first, range.last]: `columns` numbers each (the response,
// then the predictors). Also checks nothing but blank lines follows.
MatrixLD ReadData(const DatFile& file, const Header& h, int columns) {
  const int count = h.data.last - h.data.first + 1;
  if (count != h.num_observations) {
    file.Fail(h.data.first, "the File Format section puts the data on lines " +
                                std::to_string(h.data.first) + " to " +
                                std::to_string(h.data.last) + " (" +
                                std::to_string(count) + " lines), but the file states " +
                                std::to_string(h.num_observations) + " observations");
  }
  std::string layout = "y";
  for (int c = 1; c < columns; ++c) {
    layout += columns == 2 ? " x" : " x" + std::to_string(c);
  }
  MatrixLD data(count, columns);
  for (int i = 0; i < count; ++i) {
    const int k = h.data.first + i;
    const std::string what = "data line " + std::to_string(i + 1) + " of " +
                             std::to_string(count) + " ('" + layout + "')";
    const std::vector<std::string> t = Tokens(file.Need(k, what));
    if (static_cast<int>(t.size()) != columns) {
      file.Fail(k, "expected " + what + ": " + std::to_string(columns) +
                       " numbers, found " + std::to_string(t.size()) + " fields");
    }
    for (int c = 0; c < columns; ++c) {
      data(i, c) = file.Number(k, t[c], c == 0 ? "the response y" : "a predictor x");
    }
  }
  for (int k = h.data.last + 1; k <= file.num_lines(); ++k) {
    if (!Trim(file.Line(k)).empty()) {
      file.Fail(k, "expected the end of the file after the last data line (line " +
                       std::to_string(h.data.last) + ")");
    }
  }
  return data;
}

// The number after `label` on the first line in the range that starts with it
// and has something after it (column headings repeat some labels alone).
LongDouble LabelledValue(const DatFile& file, const LineRange& range,
                         const std::string& label) {
  for (int k = range.first; k <= std::min(range.last, file.num_lines()); ++k) {
    const std::string text = Trim(file.Line(k));
    if (!StartsWith(text, label)) continue;
    const std::vector<std::string> t = Tokens(text.substr(label.size()));
    if (t.empty()) continue;
    if (t.size() != 1) file.Fail(k, "expected one number after '" + label + "'");
    return file.Number(k, t[0], "the value of '" + label + "'");
  }
  if (range.last > file.num_lines()) {
    file.Fail(file.num_lines() + 1,
              "expected '" + label + " <value>' in lines " + std::to_string(range.first) +
                  " to " + std::to_string(range.last) + ", found end of file");
  }
  file.Fail(range.first, "expected a line '" + label + " <value>' in lines " +
                             std::to_string(range.first) + " to " +
                             std::to_string(range.last));
}

bool IsParameterName(const std::string& token, char letter, int* index) {
  return token.size() >= 2 && token[0] == letter && ParseInt(token.substr(1), index);
}

[[noreturn]] void FailParameterRows(const DatFile& file, const LineRange& range,
                                    const std::string& layout, int expected, int found) {
  const int at = range.last > file.num_lines() ? file.num_lines() + 1 : range.first;
  file.Fail(at, "expected " + std::to_string(expected) + " parameter lines '" + layout +
                    "' in lines " + std::to_string(range.first) + " to " +
                    std::to_string(range.last) +
                    " (as the Model section states), found " + std::to_string(found) +
                    (range.last > file.num_lines() ? " before the end of file" : ""));
}

// The fields every dataset takes from its header, and its file.
template <typename Dataset>
void SetHeaderFields(const Header& h, const std::string& path, Dataset* d) {
  d->name = h.name;
  d->path = path;
  d->difficulty = h.difficulty;
  d->model = h.model;
}

}  // namespace

// ---------------------------------------------------------------------------

NistLinearDataset ReadNistLinear(const std::string& path) {
  const DatFile file(path);
  const Header h = ReadHeader(file, "Linear Least Squares Regression");
  NistLinearDataset d;
  SetHeaderFields(h, path, &d);

  // "B0   estimate   sd" rows.
  std::vector<int> rows;
  for (int k = h.certified.first; k <= std::min(h.certified.last, file.num_lines());
       ++k) {
    const std::vector<std::string> t = Tokens(file.Line(k));
    int index = 0;
    if (!t.empty() && IsParameterName(t[0], 'B', &index)) {
      if (t.size() != 3) file.Fail(k, "expected '" + t[0] + " <estimate> <sd>'");
      rows.push_back(k);
    }
  }
  if (static_cast<int>(rows.size()) != h.num_parameters) {
    FailParameterRows(file, h.certified, "Bk <estimate> <standard deviation>",
                      h.num_parameters, static_cast<int>(rows.size()));
  }
  d.certified.resize(h.num_parameters);
  d.certified_sd.resize(h.num_parameters);
  int first = 0;  // B0, or B1 without an intercept
  for (int j = 0; j < h.num_parameters; ++j) {
    const int k = rows[j];
    const std::vector<std::string> t = Tokens(file.Line(k));
    int index = 0;
    IsParameterName(t[0], 'B', &index);
    if (j == 0 && (index == 0 || index == 1)) first = index;
    if (index != first + j) {
      file.Fail(k,
                "expected parameter " +
                    (j == 0 ? std::string("B0 or B1") : "B" + std::to_string(first + j)) +
                    ", found " + t[0]);
    }
    d.parameter_names.push_back(t[0]);
    d.certified(j) = file.Number(k, t[1], "the certified estimate of " + t[0]);
    d.certified_sd(j) =
        file.Number(k, t[2], "the certified standard deviation of " + t[0]);
  }
  d.residual_sd = LabelledValue(file, h.certified, "Standard Deviation");
  d.r_squared = LabelledValue(file, h.certified, "R-Squared");

  // The design: an intercept when the first parameter is B0; a polynomial in a
  // single predictor, or one column per predictor (Longley).
  d.intercept = d.parameter_names[0] == "B0";
  const int slopes = h.num_parameters - (d.intercept ? 1 : 0);
  if (h.num_predictors == 1) {
    d.degree = slopes;
    if (d.degree < 1) {
      file.Fail(h.model_line, "expected at least one parameter multiplying x");
    }
  } else {
    d.degree = 0;
    if (slopes != h.num_predictors) {
      file.Fail(h.model_line, "expected one parameter per predictor (" +
                                  std::to_string(h.num_predictors) + ") plus B0, found " +
                                  std::to_string(h.num_parameters) + " parameters");
    }
  }

  const MatrixLD data = ReadData(file, h, 1 + h.num_predictors);
  d.response = data.col(0);
  d.predictors = data.rightCols(h.num_predictors);
  return d;
}

LinearProblem NistLinearDataset::Problem() const {
  LinearProblem p;
  p.A = Design<double>();
  p.b = response.cast<double>();
  p.names = parameter_names;
  return p;
}

NistNonlinearDataset ReadNistNonlinear(const std::string& path) {
  const DatFile file(path);
  const Header h = ReadHeader(file, "Nonlinear Least Squares Regression");
  NistNonlinearDataset d;
  SetHeaderFields(h, path, &d);

  // "b1 =  start1  start2  certified  sd" rows.
  std::vector<int> rows;
  for (int k = h.starting.first; k <= std::min(h.starting.last, file.num_lines()); ++k) {
    const std::vector<std::string> t = Tokens(file.Line(k));
    int index = 0;
    if (!t.empty() && IsParameterName(t[0], 'b', &index)) {
      if (t.size() != 6 || t[1] != "=") {
        file.Fail(k,
                  "expected '" + t[0] +
                      " = <start 1> <start 2> <certified value> <standard deviation>'");
      }
      rows.push_back(k);
    }
  }
  const int np = h.num_parameters;
  if (static_cast<int>(rows.size()) != np) {
    FailParameterRows(file, h.starting, "bk = <start 1> <start 2> <certified> <sd>", np,
                      static_cast<int>(rows.size()));
  }
  d.starts.resize(np, 2);
  d.certified_long.resize(np);
  d.certified_sd.resize(np);
  for (int j = 0; j < np; ++j) {
    const int k = rows[j];
    const std::vector<std::string> t = Tokens(file.Line(k));
    if (t[0] != "b" + std::to_string(j + 1)) {
      file.Fail(k, "expected parameter b" + std::to_string(j + 1) + ", found " + t[0]);
    }
    d.parameter_names.push_back(t[0]);
    d.starts(j, 0) = static_cast<double>(file.Number(k, t[2], "start 1 of " + t[0]));
    d.starts(j, 1) = static_cast<double>(file.Number(k, t[3], "start 2 of " + t[0]));
    d.certified_long(j) = file.Number(k, t[4], "the certified value of " + t[0]);
    d.certified_sd(j) = static_cast<double>(
        file.Number(k, t[5], "the certified standard deviation of " + t[0]));
  }
  d.certified = d.certified_long.cast<double>();
  d.certified_rss_long = LabelledValue(file, h.certified, "Residual Sum of Squares:");
  d.certified_rss = static_cast<double>(d.certified_rss_long);
  d.residual_sd = static_cast<double>(
      LabelledValue(file, h.certified, "Residual Standard Deviation:"));
  const LongDouble n = LabelledValue(file, h.certified, "Number of Observations:");
  if (n != h.num_observations) {
    file.Fail(file.Find("Number of Observations:", h.certified.first, h.certified.last),
              "expected " + std::to_string(h.num_observations) +
                  " observations, as the Data description states");
  }
  // Read, so that a malformed line is reported, but not checked against
  // observations - parameters: NIST's Rat43.dat states 9 degrees of freedom for 15
  // observations and 4 parameters, while its certified residual standard
  // deviation is sqrt(RSS / 11).
  LabelledValue(file, h.certified, "Degrees of Freedom:");
  d.degrees_of_freedom = h.num_observations - np;

  const MatrixLD data = ReadData(file, h, 1 + h.num_predictors);
  d.y_long = data.col(0);
  d.x_long = data.rightCols(h.num_predictors);
  d.y = d.y_long.cast<double>();
  d.x = d.x_long.cast<double>();
  return d;
}

namespace {

template <typename T>
double Lre(T value, T certified) {
  constexpr double kMaxDigits = 15;
  if (!std::isfinite(value) || !std::isfinite(certified)) return 0;
  const T error = std::fabs(value - certified);
  if (error == 0) return kMaxDigits;
  const T relative = certified == 0 ? error : error / std::fabs(certified);
  const double lre = -static_cast<double>(std::log10(relative));
  return std::min(kMaxDigits, std::max(0.0, lre));
}

}  // namespace

double LogRelativeError(double value, double certified) { return Lre(value, certified); }
double LogRelativeError(long double value, long double certified) {
  return Lre(value, certified);
}

}  // namespace femup
