// femup_validate: scores femup's solvers against references nobody here wrote
// (NIST's certified values for the StRD datasets, Hansen's ill-posed test
// problems with their exact solutions, the paper's preset correction factors)
// and prints each result as a Markdown table. With --out DIR it also writes the
// table and a JSON file of the numbers into DIR, all at once: files are staged
// and renamed into place only when every table has been computed.
#include <CLI/CLI.hpp>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

// Boost 1.74's cpp_int trips GCC's -Wmaybe-uninitialized inside its own code once
// inlined; not ours to fix.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/multiprecision/cpp_int.hpp>
#pragma GCC diagnostic pop

#include "femup/errors.h"
#include "femup/measurement.h"
#include "femup/modal.h"
#include "femup/output_dir.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/ill_posed.h"
#include "femup/problems/nist_strd.h"
#include "femup/problems/paper_chain.h"
#include "femup/solvers/extended_precision.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/solvers/regularisation.h"

namespace {

namespace fs = std::filesystem;
using femup::InputError;
using Json = nlohmann::ordered_json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------
// Output: one Markdown table (with its heading and notes) and its numbers.

struct Report {
  std::string name;      // file stem: "nist_linear"
  std::string markdown;  // heading, table, notes
  Json json;
};

std::string Format(const char* format, double value) {
  if (std::isnan(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}
std::string Digits(double lre) { return Format("%.1f", lre); }
std::string Sci(double value) { return Format("%.2e", value); }

// A Markdown cell: no pipes or line breaks inside.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n' || c == '\r') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

class MarkdownTable {
 public:
  explicit MarkdownTable(std::vector<std::string> header) : header_(std::move(header)) {}
  void Add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  std::string str() const {
    std::ostringstream out;
    const auto line = [&out](const std::vector<std::string>& cells) {
      out << "|";
      for (const auto& c : cells) out << " " << Cell(c) << " |";
      out << "\n";
    };
    line(header_);
    out << "|";
    for (std::size_t i = 0; i < header_.size(); ++i) out << " --- |";
    out << "\n";
    for (const auto& r : rows_) line(r);
    return out.str();
  }

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Correct significant digits of an answer: the least, over the parameters, of
// NIST's log relative error against the certified values.
double MinLre(const femup::VectorLD& x, const femup::VectorLD& certified) {
  if (x.size() != certified.size()) return 0;
  double lre = 15;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    lre = std::min(lre, femup::LogRelativeError(x[j], certified[j]));
  }
  return lre;
}
double MinLre(const Eigen::VectorXd& x, const femup::VectorLD& certified) {
  return MinLre(femup::VectorLD(x.cast<long double>()), certified);
}

std::string Join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

// The NIST folder (with linear/ and nonlinear/ inside), checked before any work.
std::string NistFolder(const std::string& data, const std::string& kind) {
  const fs::path folder = fs::path(data) / kind;
  std::error_code ec;
  if (!fs::is_directory(data, ec)) {
    throw InputError("--data " + data,
                     "folder not found (expected NIST StRD data with "
                     "linear/ and nonlinear/ inside)");
  }
  if (!fs::is_directory(folder, ec)) {
    throw InputError(folder.string(),
                     "folder not found (the NIST " + kind + " .dat files belong there)");
  }
  return folder.string();
}

// ---------------------------------------------------------------------------
// nist-linear

const char* const kLinearSets[] = {"Norris",   "Pontius",  "NoInt1",   "NoInt2",
                                   "Filip",    "Longley",  "Wampler1", "Wampler2",
                                   "Wampler3", "Wampler4", "Wampler5"};

// One solver's answer on one dataset: the estimate and whether it said anything
// (a status other than solved, a warning, a rank below full).
struct LinearOutcome {
  femup::VectorLD x;
  std::string status;
  int rank = -1;  // -1: not analysed
  bool flagged = false;
  std::string detail;  // the status and every warning, when flagged
};

LinearOutcome FromSolution(const femup::LinearSolution& s, int n) {
  LinearOutcome o;
  o.x = s.x.cast<long double>();
  o.status = femup::ToString(s.summary.status);
  if (s.identifiability.rank > 0) o.rank = s.identifiability.rank;
  std::vector<std::string> said = s.summary.warnings;
  said.insert(said.end(), s.identifiability.warnings.begin(),
              s.identifiability.warnings.end());
  o.flagged = s.summary.status != femup::SolverStatus::kSolved || !said.empty() ||
              (o.rank > 0 && o.rank < n);
  if (o.flagged) {
    o.detail = o.status + ": " + s.summary.message;
    if (!said.empty()) o.detail += "; warnings: " + Join(said, "; ");
  }
  return o;
}

struct LinearMethod {
  std::string label;
  std::string description;
  std::function<LinearOutcome(const femup::NistLinearDataset&)> run;
};

LinearMethod FactoryMethod(const std::string& label, const std::string& solver,
                           const femup::LinearSolverOptions& options,
                           const std::string& description) {
  return {label, description, [solver, options](const femup::NistLinearDataset& d) {
            femup::LinearSolverOptions o = options;
            if (solver == "tsvd") o.truncation = d.num_parameters();  // keep all
            return FromSolution(femup::CreateLinearSolver(solver, o)->Solve(d.Problem()),
                                d.num_parameters());
          }};
}

// The exact least-squares answer of the data as double precision holds them:
// the normal equations A'A x = A'b solved by Gaussian elimination in rational
// arithmetic (every double is an exact rational, so nothing is rounded until the
// answer is). The most a solver given the double problem can reach, but for luck.
// NaN when A'A is singular.
femup::VectorLD ExactOfDoubleData(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  using Rational = boost::multiprecision::cpp_rational;
  const Eigen::Index m = a.rows(), n = a.cols();
  // The augmented normal equations [A'A | A'b], row by row.
  std::vector<std::vector<Rational>> rows(n, std::vector<Rational>(n + 1));
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j <= n; ++j) {
      Rational sum = 0;
      for (Eigen::Index k = 0; k < m; ++k) {
        sum += Rational(a(k, i)) * Rational(j < n ? a(k, j) : b[k]);
      }
      rows[i][j] = sum;
    }
  }
  femup::VectorLD x = femup::VectorLD::Constant(n, kNaN);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index pivot = i;
    while (pivot < n && rows[pivot][i] == 0) ++pivot;
    if (pivot == n) return x;
    std::swap(rows[i], rows[pivot]);
    for (Eigen::Index r = i + 1; r < n; ++r) {
      const Rational factor = rows[r][i] / rows[i][i];
      for (Eigen::Index c = i; c <= n; ++c) rows[r][c] -= factor * rows[i][c];
    }
  }
  std::vector<Rational> exact(n);
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    Rational sum = rows[i][n];
    for (Eigen::Index c = i + 1; c < n; ++c) sum -= rows[i][c] * exact[c];
    exact[i] = sum / rows[i][i];
    x[i] = static_cast<long double>(exact[i]);
  }
  return x;
}

std::vector<LinearMethod> LinearMethods() {
  const femup::LinearSolverOptions defaults;
  femup::LinearSolverOptions unscaled;
  unscaled.scale_columns = false;
  femup::LinearSolverOptions unregularised;
  unregularised.regularisation.parameter_choice = "fixed";
  unregularised.regularisation.lambda = 0;
  std::vector<LinearMethod> methods = {
      FactoryMethod("lstsq", "lstsq", defaults, "lstsq, default options"),
      FactoryMethod("lstsq unscaled", "lstsq", unscaled,
                    "lstsq with scale_columns = false (rank threshold 1e-10 on the "
                    "unscaled matrix)"),
      FactoryMethod(
          "tsvd", "tsvd", defaults,
          "tsvd with truncation = all parameters (capped at its numerical rank)"),
      FactoryMethod("tikhonov", "tikhonov", unregularised,
                    "tikhonov, parameter_choice fixed, lambda = 0"),
      FactoryMethod("bvls", "bvls", defaults, "bvls, default options (no bounds)"),
      FactoryMethod("ceres", "ceres", defaults, "ceres, default options"),
      FactoryMethod("ipopt", "ipopt", defaults, "ipopt, default options"),
  };
  methods.push_back(
      {"QR double", "baseline: Eigen ColPivHouseholderQR on column-scaled double data",
       [](const femup::NistLinearDataset& d) {
         const Eigen::MatrixXd a = d.Design<double>();
         const Eigen::VectorXd b = d.response.cast<double>();
         Eigen::VectorXd scale = a.colwise().norm().transpose();
         for (Eigen::Index j = 0; j < scale.size(); ++j) {
           if (scale[j] == 0) scale[j] = 1;
         }
         const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(
             a * scale.cwiseInverse().asDiagonal());
         LinearOutcome o;
         o.x = qr.solve(b).cwiseQuotient(scale).cast<long double>();
         o.rank = static_cast<int>(qr.rank());
         o.status = o.rank == d.num_parameters() ? "solved" : "rank deficient";
         o.flagged = o.rank < d.num_parameters();
         if (o.flagged) {
           o.detail = "rank " + std::to_string(o.rank) + " of " +
                      std::to_string(d.num_parameters());
         }
         return o;
       }});
  methods.push_back(
      {"QR long double",
       "femup::ExtendedPrecisionLeastSquares: column-scaled, column-pivoted Householder "
       "QR in long double on the long double data",
       [](const femup::NistLinearDataset& d) {
         const femup::ExtendedPrecisionSolution s =
             femup::ExtendedPrecisionLeastSquares(d.Design<long double>(), d.response);
         LinearOutcome o;
         o.x = s.x;
         o.rank = s.rank;
         o.status = s.rank_deficient() ? "rank deficient" : "solved";
         o.flagged = s.rank_deficient();
         if (o.flagged) o.detail = s.message;
         return o;
       }});
  methods.push_back(
      {"exact of double data",
       "reference: the exact least-squares answer of the double-precision data "
       "(normal equations in rational arithmetic), the most a solver given the "
       "double problem can reach but for luck",
       [](const femup::NistLinearDataset& d) {
         LinearOutcome o;
         o.x = ExactOfDoubleData(d.Design<double>(), d.response.cast<double>());
         o.status = o.x.allFinite() ? "solved" : "singular";
         o.flagged = !o.x.allFinite();
         if (o.flagged) o.detail = "A'A is singular";
         return o;
       }});
  return methods;
}

// Fewer correct digits than this with nothing said is a silent failure.
constexpr double kSilentDigits = 4;

Report NistLinear(const std::string& data) {
  const auto start = std::chrono::steady_clock::now();
  const std::string folder = NistFolder(data, "linear");
  const std::vector<LinearMethod> methods = LinearMethods();

  std::vector<std::string> header = {"dataset", "difficulty"};
  for (const auto& m : methods) header.push_back(m.label);
  header.push_back("warned or rank deficient");
  MarkdownTable table(header);
  MarkdownTable flags({"dataset", "method", "status", "what it said"});
  Json rows = Json::array();
  for (const char* name : kLinearSets) {
    const femup::NistLinearDataset d =
        femup::ReadNistLinear((fs::path(folder) / (std::string(name) + ".dat")).string());
    std::vector<std::string> cells = {d.name, d.difficulty};
    std::vector<std::string> flagged;
    Json results = Json::object();
    for (const auto& m : methods) {
      const LinearOutcome o = m.run(d);
      const double lre = MinLre(o.x, d.certified);
      const bool silent = !o.flagged && lre < kSilentDigits;
      cells.push_back(Digits(lre) + (o.flagged ? " (!)" : silent ? " (silent)" : ""));
      if (o.flagged) {
        flagged.push_back(m.label);
        flags.Add({d.name, m.label, o.status, o.detail});
      }
      Json r = {{"digits", lre},
                {"status", o.status},
                {"flagged", o.flagged},
                {"silent_failure", silent}};
      if (o.rank >= 0) r["rank"] = o.rank;
      if (o.flagged) r["detail"] = o.detail;
      results[m.label] = r;
    }
    cells.push_back(flagged.empty() ? "none" : Join(flagged, ", "));
    table.Add(cells);
    rows.push_back({{"dataset", d.name},
                    {"difficulty", d.difficulty},
                    {"parameters", d.num_parameters()},
                    {"observations", d.num_observations()},
                    {"results", results}});
  }

  std::ostringstream md;
  md << "## NIST StRD linear least squares\n\n"
     << "Correct significant digits (the least, over the parameters, of NIST's log "
        "relative error against the certified values; 15 = every certified digit). "
        "(!) marks an answer whose solver warned, reported a status other than "
        "solved, or found the matrix rank deficient; the last column names them and "
        "the table below says what each said. (silent) marks fewer than "
     << kSilentDigits << " digits with nothing said.\n\n"
     << table.str() << "\nMethods:\n\n";
  Json method_list = Json::array();
  for (const auto& m : methods) {
    md << "- `" << m.label << "`: " << m.description << "\n";
    method_list.push_back({{"label", m.label}, {"description", m.description}});
  }
  md << "\nWhat the flagged solvers said:\n\n" << flags.str();
  Report report{"nist_linear", md.str(), Json::object()};
  report.json = {{"table", "nist-linear"},
                 {"data", folder},
                 {"methods", method_list},
                 {"datasets", rows},
                 {"seconds", Seconds(start)}};
  return report;
}

// ---------------------------------------------------------------------------
// nist-nonlinear

// NIST's order: lower, average, higher difficulty.
const char* const kNonlinearSets[] = {
    "Misra1a", "Chwirut2", "Chwirut1", "Lanczos3", "Gauss1", "Gauss2",   "DanWood",
    "Misra1b", "Kirby2",   "Hahn1",    "Nelson",   "MGH17",  "Lanczos1", "Lanczos2",
    "Gauss3",  "Misra1c",  "Misra1d",  "Roszman1", "ENSO",   "MGH09",    "Thurber",
    "BoxBOD",  "Rat42",    "MGH10",    "Eckerle4", "Rat43",  "Bennett5"};

constexpr double kSolvedDigits = 4;

// The options of the table: the same for both backends and every start. The
// defaults stop on a gradient relative to the start's (too loose where the start
// is steep: MGH10 start 1), allow 500 iterations (MGH17 start 1 needs more) and
// begin Ceres with an undamped Gauss-Newton step (meant for linear problems);
// these undo that.
femup::NonlinearSolverOptions NistOptions() {
  femup::NonlinearSolverOptions o;
  o.max_iterations = 10000;
  o.gradient_tolerance = 0;
  o.initial_trust_region = 1e4;
  return o;
}

Report NistNonlinear(const std::string& data) {
  const auto start = std::chrono::steady_clock::now();
  const std::string folder = NistFolder(data, "nonlinear");
  const std::vector<std::string> backends = femup::AvailableNonlinearSolvers();
  const femup::NonlinearSolverOptions options = NistOptions();
  const femup::NonlinearSolverOptions defaults;

  std::vector<std::string> header = {"dataset", "difficulty", "start"};
  for (const auto& b : backends) {
    header.push_back(b + " digits");
    header.push_back(b + " status");
    header.push_back(b + " iterations");
  }
  MarkdownTable table(header);
  std::vector<int> solved(backends.size(), 0), solved_defaults(backends.size(), 0);
  std::vector<std::vector<std::string>> failures(backends.size()),
      failures_defaults(backends.size());
  Json rows = Json::array();
  int starts = 0;
  for (const char* name : kNonlinearSets) {
    const femup::NistNonlinearDataset d = femup::ReadNistNonlinear(
        (fs::path(folder) / (std::string(name) + ".dat")).string());
    for (int s = 1; s <= 2; ++s) {
      ++starts;
      const femup::NonlinearProblem problem = femup::NistNonlinearProblem(d, s);
      std::vector<std::string> cells = {d.name, d.difficulty, std::to_string(s)};
      Json results = Json::object();
      for (std::size_t k = 0; k < backends.size(); ++k) {
        const femup::NonlinearSolution sol =
            femup::CreateNonlinearSolver(backends[k], options)->Solve(problem);
        const double lre = MinLre(sol.x, d.certified_long);
        const bool ok = lre >= kSolvedDigits;
        if (ok) {
          ++solved[k];
        } else {
          failures[k].push_back(d.name + "/" + std::to_string(s));
        }
        // The same start with the default options, for the summary.
        const femup::NonlinearSolution plain =
            femup::CreateNonlinearSolver(backends[k], defaults)->Solve(problem);
        const double plain_lre = MinLre(plain.x, d.certified_long);
        if (plain_lre >= kSolvedDigits) {
          ++solved_defaults[k];
        } else {
          failures_defaults[k].push_back(d.name + "/" + std::to_string(s));
        }
        cells.push_back(Digits(lre) + (ok ? "" : " (x)"));
        cells.push_back(femup::ToString(sol.summary.status));
        cells.push_back(std::to_string(sol.summary.iterations));
        results[backends[k]] = {{"digits", lre},
                                {"solved", ok},
                                {"status", femup::ToString(sol.summary.status)},
                                {"iterations", sol.summary.iterations},
                                {"cost", sol.summary.cost},
                                {"certified_cost", 0.5 * d.certified_rss},
                                {"seconds", sol.summary.time_seconds},
                                {"message", sol.summary.message},
                                {"default_options_digits", plain_lre}};
      }
      table.Add(cells);
      rows.push_back({{"dataset", d.name},
                      {"difficulty", d.difficulty},
                      {"start", s},
                      {"results", results}});
    }
  }

  std::ostringstream md;
  md << "## NIST StRD nonlinear least squares\n\n"
     << "All 27 datasets from both of NIST's starting points, through "
        "CreateNonlinearSolver with the same options for both backends and every "
        "start: max_iterations "
     << options.max_iterations << ", gradient_tolerance " << options.gradient_tolerance
     << ", initial_trust_region " << Format("%.0e", options.initial_trust_region)
     << " (Ceres only), the rest default. Digits: the least, over the parameters, of "
        "the log relative error against the certified values; (x) marks a start not "
        "solved to "
     << kSolvedDigits << " digits.\n\n"
     << table.str() << "\n";
  Json counts = Json::object();
  for (std::size_t k = 0; k < backends.size(); ++k) {
    md << "- " << backends[k] << ": " << solved[k] << " of " << starts
       << " starts solved to >= " << kSolvedDigits << " digits"
       << (failures[k].empty() ? "" : "; not solved: " + Join(failures[k], ", "))
       << ". With the default options: " << solved_defaults[k] << " of " << starts
       << (failures_defaults[k].empty()
               ? ""
               : "; not solved: " + Join(failures_defaults[k], ", "))
       << ".\n";
    counts[backends[k]] = {{"solved", solved[k]},
                           {"failed", failures[k]},
                           {"solved_with_default_options", solved_defaults[k]},
                           {"failed_with_default_options", failures_defaults[k]}};
  }
  Report report{"nist_nonlinear", md.str(), Json::object()};
  report.json = {{"table", "nist-nonlinear"},
                 {"data", folder},
                 {"solved_digits", kSolvedDigits},
                 {"options",
                  {{"max_iterations", options.max_iterations},
                   {"gradient_tolerance", options.gradient_tolerance},
                   {"initial_trust_region", options.initial_trust_region}}},
                 {"starts", starts},
                 {"solved", counts},
                 {"rows", rows},
                 {"seconds", Seconds(start)}};
  return report;
}

// ---------------------------------------------------------------------------
// ill-posed

struct IllPosedSettings {
  int n = 64;
  double noise = 1e-3;
  std::uint64_t seed = 1;
};

double RelativeError(const Eigen::VectorXd& x, const Eigen::VectorXd& exact) {
  return (x - exact).norm() / exact.norm();
}

// Whether `lambda` is (to 1e-9 relative) an end of the grid the rules searched.
bool AtGridEnd(double lambda, const std::vector<double>& grid) {
  if (grid.empty() || !std::isfinite(lambda)) return false;
  const auto near = [lambda](double end) { return std::abs(lambda - end) <= 1e-9 * end; };
  return near(grid.front()) || near(grid.back());
}

// Throws InputError naming the option when the settings cannot be used.
void Check(const IllPosedSettings& settings) {
  if (settings.n < 4 || settings.n % 4 != 0) {
    throw InputError("--n", "must be a positive multiple of 4 (phillips needs it), got " +
                                std::to_string(settings.n));
  }
  if (!(settings.noise > 0 && std::isfinite(settings.noise))) {
    throw InputError("--noise", "must be a finite relative noise level > 0");
  }
}

Report IllPosed(const IllPosedSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  Check(settings);
  // The fine grid on which the best Tikhonov lambda is searched.
  constexpr int kFineGrid = 2000;
  const std::vector<std::pair<std::string, std::string>> rules = {
      {"lcurve", "L-curve corner"},
      {"gcv", "GCV"},
      {"discrepancy", "discrepancy"},
      {"quasi_optimality", "quasi-optimality"}};

  MarkdownTable table(
      {"problem", "method", "lambda or k", "relative error", "error / best", "flag"});
  Json problems = Json::array();
  int silent_ends = 0;
  for (const std::string& name : femup::IllPosedProblemNames()) {
    const femup::IllPosedProblem p = femup::MakeIllPosedProblem(name, settings.n);
    const Eigen::VectorXd b = femup::AddRelativeNoise(p.b, settings.noise, settings.seed);
    const double noise_norm = (b - p.b).norm();
    const femup::TikhonovPath path(p.A, b);
    Json entry = {{"problem", name}, {"noise_norm", noise_norm}};

    // The best lambda: least error on a fine log grid over the rules' range.
    const double lo = path.DefaultLambdaMin(), hi = path.DefaultLambdaMax();
    double best_lambda = lo, best_error = std::numeric_limits<double>::infinity();
    int best_index = 0;
    for (int i = 0; i < kFineGrid; ++i) {
      const double lambda = lo * std::pow(hi / lo, i / (kFineGrid - 1.0));
      const double error = RelativeError(path.Solve(lambda), p.x_exact);
      if (error < best_error) {
        best_error = error;
        best_lambda = lambda;
        best_index = i;
      }
    }
    const bool best_at_end = best_index == 0 || best_index == kFineGrid - 1;
    table.Add({name, "best Tikhonov (fine grid)", Sci(best_lambda), Sci(best_error), "1",
               best_at_end ? "at an end of the range" : ""});
    entry["best"] = {{"lambda", best_lambda},
                     {"error", best_error},
                     {"at_range_end", best_at_end},
                     {"lambda_min", lo},
                     {"lambda_max", hi}};

    Json rule_results = Json::object();
    for (const auto& [rule, label] : rules) {
      femup::RegularisationOptions o;
      o.parameter_choice = rule;
      o.noise_norm = noise_norm;
      femup::RegularisationReport rep;
      const double lambda = femup::ChooseLambda(path, o, &rep);
      const double error = RelativeError(path.Solve(lambda), p.x_exact);
      const bool at_end = AtGridEnd(lambda, rep.grid_lambda);
      const bool flagged = rep.at_range_end || !rep.note.empty();
      const bool silent = at_end && !flagged;
      if (silent) ++silent_ends;
      std::string flag = rep.at_range_end ? "at range end: " + rep.note : rep.note;
      if (silent) flag = "at an end of the range, NOT flagged";
      table.Add({name, "Tikhonov, " + label, Sci(lambda), Sci(error),
                 Format("%.2f", error / best_error), flag});
      rule_results[rule] = {{"lambda", lambda},
                            {"error", error},
                            {"error_ratio", error / best_error},
                            {"at_grid_end", at_end},
                            {"at_range_end", rep.at_range_end},
                            {"note", rep.note},
                            {"silent_end", silent}};
    }
    entry["tikhonov"] = rule_results;

    // TSVD: GCV and discrepancy, next to the best truncation.
    femup::LinearProblem lp;
    lp.A = p.A;
    lp.b = b;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(
        p.A, Eigen::ComputeThinU | Eigen::ComputeThinV);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(p.A.cols());
    int best_k = 0;
    double best_k_error = std::numeric_limits<double>::infinity();
    const Eigen::VectorXd beta = svd.matrixU().transpose() * b;
    for (int k = 1; k <= svd.nonzeroSingularValues(); ++k) {
      x += svd.matrixV().col(k - 1) * (beta[k - 1] / svd.singularValues()[k - 1]);
      const double error = RelativeError(x, p.x_exact);
      if (error < best_k_error) {
        best_k_error = error;
        best_k = k;
      }
    }
    table.Add({name, "best TSVD", "k = " + std::to_string(best_k), Sci(best_k_error),
               Format("%.2f", best_k_error / best_error), ""});
    Json tsvd = {{"best", {{"k", best_k}, {"error", best_k_error}}}};
    for (const std::string rule : {"gcv", "discrepancy"}) {
      femup::LinearSolverOptions o;
      o.regularisation.parameter_choice = rule;
      o.regularisation.noise_norm = noise_norm;
      const femup::LinearSolution s = femup::CreateLinearSolver("tsvd", o)->Solve(lp);
      const double error = RelativeError(s.x, p.x_exact);
      const std::string note = Join(s.summary.warnings, "; ");
      table.Add({name, "TSVD, " + std::string(rule == "gcv" ? "GCV" : "discrepancy"),
                 "k = " + std::to_string(s.regularisation.truncation), Sci(error),
                 Format("%.2f", error / best_error), note});
      tsvd[rule] = {{"k", s.regularisation.truncation},
                    {"error", error},
                    {"error_ratio", error / best_error},
                    {"note", note}};
    }
    entry["tsvd"] = tsvd;
    problems.push_back(entry);
  }

  std::ostringstream md;
  md << "## Hansen's discrete ill-posed problems\n\n"
     << "n = " << settings.n << ", b = b_exact + e with ||e|| = " << settings.noise
     << " ||b_exact|| (AddRelativeNoise, seed " << settings.seed
     << "), the noise norm known to the discrepancy principle. Tikhonov in Hansen's "
        "convention, min ||A x - b||^2 + lambda^2 ||x||^2; relative error "
        "||x - x_exact|| / ||x_exact||. The best lambda is the least error on a "
     << kFineGrid
     << "-point log grid over the range the rules search; error / best compares "
        "with it. Flag: what the rule reported (an optimum at an end of its range, "
        "or another note).\n\n"
     << table.str() << "\n"
     << (silent_ends == 0
             ? "No rule returned an end of its range without saying so.\n"
             : std::to_string(silent_ends) +
                   " rule(s) returned an end of the range without saying so.\n");
  Report report{"ill_posed", md.str(), Json::object()};
  report.json = {{"table", "ill-posed"},     {"n", settings.n},
                 {"noise", settings.noise},  {"seed", settings.seed},
                 {"problems", problems},     {"silent_range_ends", silent_ends},
                 {"seconds", Seconds(start)}};
  return report;
}

// ---------------------------------------------------------------------------
// paper-chain

// Every factory solver with the options that make it an unregularised solve.
femup::LinearSolverOptions Unregularised(const std::string& solver, int unknowns) {
  femup::LinearSolverOptions o;
  if (solver == "tsvd") o.truncation = unknowns;  // every singular value it can keep
  if (solver == "tikhonov") {
    o.regularisation.parameter_choice = "fixed";
    o.regularisation.lambda = 0;
  }
  return o;
}

// Where a solver's answer names the common scaling of K and M: in its message or
// warnings, only in its identifiability analysis, or nowhere.
std::string WhereCommonScalingIsNamed(const femup::LinearSolution& s) {
  const auto mentions = [](const std::string& text) {
    return text.find("common scaling") != std::string::npos;
  };
  bool said = mentions(s.summary.message);
  for (const auto& w : s.summary.warnings) said = said || mentions(w);
  if (said) return "message";
  for (const auto& d : s.identifiability.null_directions) {
    if (d.common_scaling) return "identifiability only";
  }
  return "no";
}

Report PaperChain() {
  const auto start = std::chrono::steady_clock::now();
  const femup::PaperChainScenario sc = femup::PaperChain(3);
  const femup::Modes fem = femup::SolveModes(sc.model.stiffness(), sc.model.mass());
  const std::vector<femup::ModalData> states = {
      femup::PredictModes(sc.model, sc.preset, femup::Immersion::kDry, 2, "air"),
      femup::PredictModes(sc.model, sc.preset, femup::Immersion::kWet, 2, "water")};
  const femup::LinearProblem open =
      femup::BuildCorrectionSystem(sc.model, fem, states, {});
  femup::LinearProblem fixed = open;
  fixed.Fix(sc.fixed_parameter, sc.preset[sc.model.FindParameter(sc.fixed_parameter)]);
  const int n = open.num_unknowns();

  // The independent analysis of the open system, for the heading.
  const femup::Identifiability id =
      femup::AnalyseIdentifiability(open.A, open.names, open.groups, 1e-10);
  std::string directions;
  for (const auto& d : id.null_directions) {
    directions += (directions.empty() ? "" : "; ") + d.description;
  }

  MarkdownTable table({"solver", "max error, " + sc.fixed_parameter + " fixed", "status",
                       "without the constraint: status", "common scaling named in",
                       "message"});
  Json rows = Json::array();
  double worst = 0;
  for (const std::string& solver : femup::AvailableLinearSolvers()) {
    const auto s = femup::CreateLinearSolver(solver, Unregularised(solver, n));
    const femup::LinearSolution a = s->Solve(fixed);
    const double error = (a.x - sc.preset).cwiseAbs().maxCoeff();
    worst = std::max(worst, error);
    const femup::LinearSolution b = s->Solve(open);
    const std::string names = WhereCommonScalingIsNamed(b);
    std::string said = b.summary.message;
    if (!b.summary.warnings.empty()) {
      said += "; warnings: " + Join(b.summary.warnings, "; ");
    }
    table.Add({solver, Sci(error), femup::ToString(a.summary.status),
               femup::ToString(b.summary.status), names, said});
    rows.push_back({{"solver", solver},
                    {"fixed",
                     {{"max_error", error},
                      {"status", femup::ToString(a.summary.status)},
                      {"message", a.summary.message}}},
                    {"open",
                     {{"status", femup::ToString(b.summary.status)},
                      {"names_common_scaling", names},
                      {"residual_norm", b.residual.norm()},
                      {"rank", b.identifiability.rank},
                      {"message", b.summary.message},
                      {"warnings", b.summary.warnings}}}});
  }

  std::ostringstream md;
  md << "## The paper's 5-dof chain\n\n"
     << "Masses 1-3 wet, two modes in air and two in water simulated from the "
        "paper's preset factors, stacked correction system ("
     << open.num_rows() << " x " << n << "). Each solver runs unregularised (tsvd "
     << "keeps every singular value, tikhonov has lambda = 0). Max error: the largest "
        "|x - preset| over the "
     << n << " factors with " << sc.fixed_parameter
     << " fixed at its preset value (the paper's constraint). Without it the system "
        "has rank "
     << id.rank << " of " << n << "; AnalyseIdentifiability names the missing "
     << "direction: " << directions << ".\n\n"
     << table.str();
  Report report{"paper_chain", md.str(), Json::object()};
  report.json = {{"table", "paper-chain"},
                 {"rows_of_system", open.num_rows()},
                 {"unknowns", n},
                 {"fixed_parameter", sc.fixed_parameter},
                 {"open_rank", id.rank},
                 {"null_directions", directions},
                 {"worst_error", worst},
                 {"solvers", rows},
                 {"seconds", Seconds(start)}};
  return report;
}

// ---------------------------------------------------------------------------

// Prints every report and, with an output folder, writes <name>.md and
// <name>.json for each (and `combined` when not empty) in one commit.
void Emit(const std::vector<Report>& reports, const std::string& out,
          const std::string& combined) {
  std::string all;
  for (const auto& r : reports) all += (all.empty() ? "" : "\n") + r.markdown;
  std::cout << all;
  if (out.empty()) return;
  std::error_code ec;
  const fs::path parent = fs::path(out).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  femup::OutputDir dir(out);
  for (const auto& r : reports) {
    dir.WriteText(r.name + ".md", r.markdown);
    dir.WriteText(r.name + ".json", r.json.dump(2) + "\n");
  }
  if (!combined.empty()) dir.WriteText(combined, "# femup validation\n\n" + all);
  dir.Commit();
  std::cerr << "femup_validate: wrote " << Join(dir.files(), ", ") << " to " << out
            << "\n";
}

const std::vector<std::string> kSubcommands = {"nist-linear", "nist-nonlinear",
                                               "ill-posed", "paper-chain", "all"};

}  // namespace

int main(int argc, char** argv) {
  // CLI11 reports an unknown subcommand as an unexpected argument; name it.
  if (argc > 1 && argv[1][0] != '-' &&
      std::find(kSubcommands.begin(), kSubcommands.end(), argv[1]) ==
          kSubcommands.end()) {
    std::cerr << "femup_validate: error: unknown subcommand '" << argv[1] << "' (choose "
              << Join(kSubcommands, ", ") << ")\n";
    return 1;
  }
  CLI::App app{
      "femup_validate: femup's solvers on references nobody here wrote (NIST StRD, "
      "Hansen's ill-posed problems, the paper's preset factors), as Markdown tables"};
  app.require_subcommand(1);

  std::string data = FEMUP_NIST_DATA_DIR;
  std::string out;
  IllPosedSettings ill;
  const auto add_out = [&out](CLI::App* cmd) {
    cmd->add_option("--out", out,
                    "also write the table (.md) and its numbers (.json) to this folder");
  };
  const auto add_data = [&data](CLI::App* cmd) {
    cmd->add_option("--data", data,
                    "NIST StRD folder holding linear/ and nonlinear/ (default: the "
                    "copy in tests/data/nist)");
  };
  const auto add_ill = [&ill](CLI::App* cmd) {
    cmd->add_option("--n", ill.n, "problem size (a multiple of 4)");
    cmd->add_option("--noise", ill.noise, "relative noise level ||e|| / ||b||");
    cmd->add_option("--seed", ill.seed, "seed of the noise");
  };
  CLI::App* linear = app.add_subcommand(
      "nist-linear", "the 11 NIST linear datasets on every linear solver");
  add_data(linear);
  add_out(linear);
  CLI::App* nonlinear = app.add_subcommand(
      "nist-nonlinear", "the 27 NIST nonlinear datasets, 2 starts, on ceres and ipopt");
  add_data(nonlinear);
  add_out(nonlinear);
  CLI::App* ill_posed = app.add_subcommand(
      "ill-posed", "parameter-choice rules on Hansen's test problems with noise");
  add_ill(ill_posed);
  add_out(ill_posed);
  CLI::App* chain =
      app.add_subcommand("paper-chain", "the paper's 5-dof chain on every linear solver");
  add_out(chain);
  CLI::App* all = app.add_subcommand("all", "every table, plus a combined Markdown file");
  add_data(all);
  add_ill(all);
  add_out(all);

  CLI11_PARSE(app, argc, argv);

  try {
    const auto start = std::chrono::steady_clock::now();
    std::vector<Report> reports;
    std::string combined;
    if (*linear) reports.push_back(NistLinear(data));
    if (*nonlinear) reports.push_back(NistNonlinear(data));
    if (*ill_posed) reports.push_back(IllPosed(ill));
    if (*chain) reports.push_back(PaperChain());
    if (*all) {
      // Bad options fail before the long runs.
      Check(ill);
      NistFolder(data, "linear");
      NistFolder(data, "nonlinear");
      reports = {NistLinear(data), NistNonlinear(data), IllPosed(ill), PaperChain()};
      combined = "validation.md";
    }
    Emit(reports, out, combined);
    std::cerr << "femup_validate: " << app.get_subcommands().front()->get_name()
              << " took " << Format("%.1f", Seconds(start)) << " s\n";
  } catch (const InputError& e) {
    std::cerr << "femup_validate: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "femup_validate: internal error: " << e.what() << "\n";
    return 4;
  }
  return 0;
}
