// femup_validate ill-posed: the parameter-choice rules (L-curve, GCV,
// discrepancy, quasi-optimality; TSVD's GCV and discrepancy) on Hansen's test
// problems with noise, against the best lambda and truncation.
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "femup/evaluation/ill_posed.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/regularisation.h"
#include "validate.h"

namespace femup_validate {
namespace {

double RelativeError(const Eigen::VectorXd& x, const Eigen::VectorXd& exact) {
  return (x - exact).norm() / exact.norm();
}

// Whether `lambda` is (to 1e-9 relative) an end of the grid the rules searched.
bool AtGridEnd(double lambda, const std::vector<double>& grid) {
  if (grid.empty() || !std::isfinite(lambda)) return false;
  const auto near = [lambda](double end) { return std::abs(lambda - end) <= 1e-9 * end; };
  return near(grid.front()) || near(grid.back());
}

}  // namespace

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

}  // namespace femup_validate
