#include "femup/problems/nist_strd.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <unsupported/Eigen/AutoDiff>
#include <utility>
#include <vector>

#include "femup/errors.h"

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

// ---------------------------------------------------------------------------
// The nonlinear models, each written once over the scalar type T (double, long
// double, or an automatic-differentiation scalar over double). `b` holds the
// parameters b1.. at b[0].., `x` one observation's predictors, in the real type
// R of T (double for the AD scalar).

using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;

template <typename T>
struct RealOf {
  using type = T;
};
template <>
struct RealOf<AD> {
  using type = double;
};
template <typename T>
using Real = typename RealOf<T>::type;

// a^e with both depending on the parameters.
template <typename T>
T Pow(const T& a, const T& e) {
  using std::exp;
  using std::log;
  return exp(e * log(a));
}
double Pow(double a, double e) { return std::pow(a, e); }
long double Pow(long double a, long double e) { return std::pow(a, e); }

// a^e with e a constant.
template <typename T>
T PowConst(const T& a, Real<T> e) {
  using std::pow;
  return pow(a, e);
}

// arctan: the AD scalar has atan2 only (atan(v) = atan2(v, 1)).
double Atan(double v) { return std::atan(v); }
long double Atan(long double v) { return std::atan(v); }
AD Atan(const AD& v) {
  return atan2(v, AD(1.0, Eigen::VectorXd::Zero(v.derivatives().size())));
}

template <typename T>
Real<T> Pi() {
  return static_cast<Real<T>>(3.141592653589793238462643383279L);
}

// y = b1 * (b2+x)**(-1/b3)
struct Bennett5 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] * Pow(T(b[1] + x[0]), T(-1.0 / b[2]));
  }
};
// y = b1*(1-exp[-b2*x])  (BoxBOD and Misra1a)
struct BoxBOD {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] * (1.0 - exp(-b[1] * x[0]));
  }
};
// y = exp[-b1*x]/(b2+b3*x)  (Chwirut1, Chwirut2)
struct Chwirut {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return exp(-b[0] * x[0]) / (b[1] + b[2] * x[0]);
  }
};
// y = b1*x**b2
struct DanWood {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    using std::log;
    return b[0] * exp(b[1] * log(x[0]));
  }
};
// y = b1 + b2*cos(2*pi*x/12) + b3*sin(2*pi*x/12) + b5*cos(2*pi*x/b4)
//        + b6*sin(2*pi*x/b4) + b8*cos(2*pi*x/b7) + b9*sin(2*pi*x/b7)
struct ENSO {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::cos;
    using std::sin;
    const Real<T> w = 2 * Pi<T>() * x[0];
    const T a4 = w / b[3];
    const T a7 = w / b[6];
    return b[0] + b[1] * cos(w / 12) + b[2] * sin(w / 12) + b[4] * cos(a4) +
           b[5] * sin(a4) + b[7] * cos(a7) + b[8] * sin(a7);
  }
};
// y = (b1/b2) * exp[-0.5*((x-b3)/b2)**2]
struct Eckerle4 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    const T u = (x[0] - b[2]) / b[1];
    return b[0] / b[1] * exp(-0.5 * u * u);
  }
};
// y = b1*exp(-b2*x) + b3*exp(-(x-b4)**2/b5**2) + b6*exp(-(x-b7)**2/b8**2)
struct Gauss {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    const T u = (x[0] - b[3]) / b[4];
    const T v = (x[0] - b[6]) / b[7];
    return b[0] * exp(-b[1] * x[0]) + b[2] * exp(-(u * u)) + b[5] * exp(-(v * v));
  }
};
// y = (b1+b2*x+b3*x**2+b4*x**3) / (1+b5*x+b6*x**2+b7*x**3)  (Hahn1, Thurber)
struct CubicOverCubic {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    const Real<T> t = x[0];
    return (b[0] + t * (b[1] + t * (b[2] + t * b[3]))) /
           (1.0 + t * (b[4] + t * (b[5] + t * b[6])));
  }
};
// y = (b1 + b2*x + b3*x**2) / (1 + b4*x + b5*x**2)
struct Kirby2 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    const Real<T> t = x[0];
    return (b[0] + t * (b[1] + t * b[2])) / (1.0 + t * (b[3] + t * b[4]));
  }
};
// y = b1*exp(-b2*x) + b3*exp(-b4*x) + b5*exp(-b6*x)  (Lanczos1-3)
struct Lanczos {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] * exp(-b[1] * x[0]) + b[2] * exp(-b[3] * x[0]) + b[4] * exp(-b[5] * x[0]);
  }
};
// y = b1*(x**2+x*b2) / (x**2+x*b3+b4)
struct MGH09 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    const Real<T> t = x[0];
    return b[0] * (t * t + t * b[1]) / (t * t + t * b[2] + b[3]);
  }
};
// y = b1 * exp[b2/(x+b3)]
struct MGH10 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] * exp(b[1] / (x[0] + b[2]));
  }
};
// y = b1 + b2*exp[-x*b4] + b3*exp[-x*b5]
struct MGH17 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] + b[1] * exp(-x[0] * b[3]) + b[2] * exp(-x[0] * b[4]);
  }
};
// y = b1 * (1-(1+b2*x/2)**(-2))
struct Misra1b {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] * (1.0 - PowConst(T(1.0 + b[1] * x[0] / 2), Real<T>(-2)));
  }
};
// y = b1 * (1-(1+2*b2*x)**(-.5))
struct Misra1c {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] * (1.0 - PowConst(T(1.0 + 2 * b[1] * x[0]), Real<T>(-0.5)));
  }
};
// y = b1*b2*x*((1+b2*x)**(-1))
struct Misra1d {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] * b[1] * x[0] / (1.0 + b[1] * x[0]);
  }
};
// log[y] = b1 - b2*x1 * exp[-b3*x2]  (the response is log(y))
struct Nelson {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] - b[1] * x[0] * exp(-b[2] * x[1]);
  }
};
// y = b1 / (1+exp[b2-b3*x])
struct Rat42 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] / (1.0 + exp(b[1] - b[2] * x[0]));
  }
};
// y = b1 / ((1+exp[b2-b3*x])**(1/b4))
struct Rat43 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    using std::exp;
    return b[0] / Pow(T(1.0 + exp(b[1] - b[2] * x[0])), T(1.0 / b[3]));
  }
};
// y = b1 - b2*x - arctan[b3/(x-b4)]/pi
struct Roszman1 {
  template <typename T>
  static T f(const T* b, const Real<T>* x) {
    return b[0] - b[1] * x[0] - Atan(T(b[2] / (x[0] - b[3]))) / Pi<T>();
  }
};

struct Model {
  int num_parameters = 0;
  int num_predictors = 1;
  bool log_response = false;  // Nelson: the model is for log(y)
  double (*f_double)(const double*, const double*) = nullptr;
  long double (*f_long)(const long double*, const long double*) = nullptr;
  AD (*f_ad)(const AD*, const double*) = nullptr;
};

template <typename M>
Model Make(int num_parameters, int num_predictors = 1, bool log_response = false) {
  Model m;
  m.num_parameters = num_parameters;
  m.num_predictors = num_predictors;
  m.log_response = log_response;
  m.f_double = &M::template f<double>;
  m.f_long = &M::template f<long double>;
  m.f_ad = &M::template f<AD>;
  return m;
}

const std::map<std::string, Model>& Models() {
  static const std::map<std::string, Model> models = {
      {"Bennett5", Make<Bennett5>(3)},
      {"BoxBOD", Make<BoxBOD>(2)},
      {"Chwirut1", Make<Chwirut>(3)},
      {"Chwirut2", Make<Chwirut>(3)},
      {"DanWood", Make<DanWood>(2)},
      {"ENSO", Make<ENSO>(9)},
      {"Eckerle4", Make<Eckerle4>(3)},
      {"Gauss1", Make<Gauss>(8)},
      {"Gauss2", Make<Gauss>(8)},
      {"Gauss3", Make<Gauss>(8)},
      {"Hahn1", Make<CubicOverCubic>(7)},
      {"Kirby2", Make<Kirby2>(5)},
      {"Lanczos1", Make<Lanczos>(6)},
      {"Lanczos2", Make<Lanczos>(6)},
      {"Lanczos3", Make<Lanczos>(6)},
      {"MGH09", Make<MGH09>(4)},
      {"MGH10", Make<MGH10>(3)},
      {"MGH17", Make<MGH17>(5)},
      {"Misra1a", Make<BoxBOD>(2)},
      {"Misra1b", Make<Misra1b>(2)},
      {"Misra1c", Make<Misra1c>(2)},
      {"Misra1d", Make<Misra1d>(2)},
      {"Nelson", Make<Nelson>(3, 2, true)},
      {"Rat42", Make<Rat42>(3)},
      {"Rat43", Make<Rat43>(4)},
      {"Roszman1", Make<Roszman1>(4)},
      {"Thurber", Make<CubicOverCubic>(7)},
  };
  return models;
}

// The model for `data`, checked against its sizes.
const Model& ModelFor(const NistNonlinearDataset& data, const std::string& where) {
  const auto& models = Models();
  const auto it = models.find(data.name);
  if (it == models.end()) {
    std::string known;
    for (const auto& m : models) known += (known.empty() ? "" : ", ") + m.first;
    throw InputError(where, "no NIST model for dataset '" + data.name +
                                "' (known datasets: " + known + ")");
  }
  const Model& m = it->second;
  const Eigen::Index n = data.y.size();
  if (data.certified.size() != m.num_parameters ||
      data.starts.rows() != m.num_parameters || data.starts.cols() != 2 ||
      data.x.cols() != m.num_predictors || data.x.rows() != n || n == 0) {
    std::ostringstream msg;
    msg << "dataset '" << data.name << "' has " << data.certified.size()
        << " certified parameters, a " << data.starts.rows() << " x "
        << data.starts.cols() << " start table, " << data.x.rows() << " x "
        << data.x.cols() << " predictors and " << n << " responses; the model needs "
        << m.num_parameters << " parameters (starts: " << m.num_parameters << " x 2) and "
        << m.num_predictors << " predictor column(s) with one row per response";
    throw InputError(where, msg.str());
  }
  return m;
}

}  // namespace

// ---------------------------------------------------------------------------

NistLinearDataset ReadNistLinear(const std::string& path) {
  const DatFile file(path);
  const Header h = ReadHeader(file, "Linear Least Squares Regression");
  NistLinearDataset d;
  d.name = h.name;
  d.path = path;
  d.difficulty = h.difficulty;
  d.model = h.model;

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
  d.name = h.name;
  d.path = path;
  d.difficulty = h.difficulty;
  d.model = h.model;

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

NonlinearProblem NistNonlinearProblem(const NistNonlinearDataset& data, int start) {
  const std::string where = "NistNonlinearProblem(" + data.name + ")";
  const Model& model = ModelFor(data, where);
  if (start != 1 && start != 2) {
    throw InputError(where, "start must be 1 or 2 (NIST's two starting points), not " +
                                std::to_string(start));
  }
  NonlinearProblem p;
  p.num_residuals = static_cast<int>(data.y.size());
  p.initial = data.starts.col(start - 1);
  p.names = data.parameter_names;
  // The residual is against log(y) for Nelson.
  Eigen::VectorXd target = data.y;
  if (model.log_response) target = data.y.array().log().matrix();
  // Predictors row-major, one observation after another.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x = data.x;
  const std::string name = data.name;
  const auto f_ad = model.f_ad;
  const auto f_plain = model.f_double;
  const int num_parameters = model.num_parameters;
  p.evaluate = [name, target, x, f_ad, f_plain, num_parameters](
                   const Eigen::VectorXd& b, Eigen::VectorXd* residuals,
                   Eigen::MatrixXd* jacobian, std::string* why) {
    const Eigen::Index n = target.size();
    const Eigen::Index k = b.size();
    residuals->resize(n);
    if (k != num_parameters) {
      if (jacobian) jacobian->resize(n, k);
      if (why) {
        *why = name + ": " + std::to_string(k) + " parameters given, the model has " +
               std::to_string(num_parameters);
      }
      return false;
    }
    if (jacobian) jacobian->resize(n, k);
    std::vector<AD> params(static_cast<std::size_t>(k));
    std::vector<double> plain(static_cast<std::size_t>(k));
    for (Eigen::Index j = 0; j < k; ++j) {
      plain[j] = b(j);
      if (jacobian) params[j] = AD(b(j), k, j);
    }
    // Without a Jacobian the plain double model is evaluated (the same
    // operations on the values as the AD scalar performs).
    for (Eigen::Index i = 0; i < n; ++i) {
      const double* xi = x.data() + i * x.cols();
      double value = 0;
      if (jacobian) {
        const AD fi = f_ad(params.data(), xi);
        value = fi.value();
        const Eigen::Index m = fi.derivatives().size();
        for (Eigen::Index j = 0; j < k; ++j) {
          (*jacobian)(i, j) = j < m ? fi.derivatives()(j) : 0.0;
        }
      } else {
        value = f_plain(plain.data(), xi);
      }
      (*residuals)(i) = value - target(i);
      if (!std::isfinite((*residuals)(i)) ||
          (jacobian && !jacobian->row(i).allFinite())) {
        if (why) {
          std::ostringstream msg;
          msg.precision(17);
          msg << name << ": the model "
              << (std::isfinite((*residuals)(i)) ? "derivative" : "value")
              << " is not finite at observation " << i + 1 << " (x = " << xi[0] << ")";
          *why = msg.str();
        }
        return false;
      }
    }
    return true;
  };
  return p;
}

VectorLD NistNonlinearResiduals(const NistNonlinearDataset& data, const VectorLD& b) {
  const std::string where = "NistNonlinearResiduals(" + data.name + ")";
  const Model& model = ModelFor(data, where);
  if (b.size() != model.num_parameters) {
    throw InputError(where, "expected " + std::to_string(model.num_parameters) +
                                " parameters, got " + std::to_string(b.size()));
  }
  const bool exact = data.x_long.rows() == data.x.rows() &&
                     data.x_long.cols() == data.x.cols() &&
                     data.y_long.size() == data.y.size();
  const MatrixLD x = exact ? data.x_long : data.x.cast<LongDouble>();
  const VectorLD y = exact ? data.y_long : data.y.cast<LongDouble>();
  VectorLD r(y.size());
  std::vector<LongDouble> xi(static_cast<std::size_t>(x.cols()));
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    for (Eigen::Index c = 0; c < x.cols(); ++c) xi[c] = x(i, c);
    const LongDouble target = model.log_response ? std::log(y(i)) : y(i);
    r(i) = model.f_long(b.data(), xi.data()) - target;
  }
  return r;
}

std::vector<std::string> NistNonlinearModelNames() {
  std::vector<std::string> names;
  for (const auto& m : Models()) names.push_back(m.first);
  return names;
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
