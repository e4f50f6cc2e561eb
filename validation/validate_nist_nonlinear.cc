// femup_validate nist-nonlinear: the 27 NIST StRD nonlinear datasets from both
// of NIST's starts on every nonlinear backend, with the table's options and
// with the defaults, in correct digits.
#include <sstream>
#include <string>
#include <vector>

#include "femup/evaluation/nist_strd.h"
#include "femup/solvers/nonlinear_solver.h"
#include "validate.h"

namespace femup_validate {
namespace {

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

}  // namespace

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

}  // namespace femup_validate
