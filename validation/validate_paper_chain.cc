// femup_validate paper-chain: the paper's 5-dof chain, modes simulated from its
// preset factors, on every linear solver unregularised, with and without the
// paper's constraint, and whether each names the common scaling of K and M.
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/paper_chain.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/linear_solver.h"
#include "validate.h"

namespace femup_validate {
namespace {

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

}  // namespace

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

}  // namespace femup_validate
