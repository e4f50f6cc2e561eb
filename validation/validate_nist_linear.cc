// femup_validate nist-linear: the 11 NIST StRD linear least-squares datasets on
// every linear solver and three baselines (double and long double QR, the exact
// answer of the double data in rational arithmetic), in correct digits.
#include <Eigen/QR>
#include <algorithm>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

// Boost 1.74's cpp_int trips GCC's -Wmaybe-uninitialized inside its own code once
// inlined; not ours to fix.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/multiprecision/cpp_int.hpp>
#pragma GCC diagnostic pop

#include "femup/evaluation/nist_strd.h"
#include "femup/solvers/extended_precision.h"
#include "femup/solvers/linear_solver.h"
#include "validate.h"

namespace femup_validate {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

}  // namespace

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

}  // namespace femup_validate
