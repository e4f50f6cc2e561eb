#include <cmath>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/io/matrix_market.h"
#include "femup/reporting/outputs.h"
#include "femup/reporting/plot.h"
#include "json_util.h"
#include "regularisation_output.h"
#include "render_staged.h"

namespace femup {

void WriteSolveOutputs(const SolveResult& r, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings) {
  const LinearSolution& s = r.solution;
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "solve";
  j["solver"] = {{"name", r.solver},
                 {"status", ToString(s.summary.status)},
                 {"message", s.summary.message},
                 {"warnings", s.summary.warnings},
                 {"iterations", s.summary.iterations},
                 {"cost", s.summary.cost},
                 {"kkt_residual", json_util::Number(s.summary.kkt_residual)},
                 {"time_seconds", s.summary.time_seconds}};
  j["rows"] = r.problem.num_rows();
  j["unknowns"] = r.problem.num_unknowns();
  j["rank"] = s.identifiability.rank;
  j["condition_number"] = json_util::Number(s.identifiability.condition_number);
  j["x"] = json_util::Vector(s.x);
  j["names"] = r.problem.names;
  if (s.standard_error.size() > 0)
    j["standard_error"] = json_util::Vector(s.standard_error);
  j["residual_norm"] = s.residual.norm();
  if (r.truth.size() > 0)
    j["relative_error"] = (s.x - r.truth).norm() / std::max(r.truth.norm(), 1e-300);
  const RegularisationReport& reg = s.regularisation;
  if (!reg.parameter_choice.empty()) {
    j["regularisation"] = RegularisationJson(reg);
  }
  out->WriteText("solution.json", j.dump(2) + "\n");
  std::ostringstream csv;
  csv << std::setprecision(17) << "name,x"
      << (s.standard_error.size() ? ",standard_error" : "") << "\n";
  for (Eigen::Index i = 0; i < s.x.size(); ++i) {
    csv << r.problem.names[i] << "," << s.x[i];
    if (s.standard_error.size()) csv << "," << s.standard_error[i];
    csv << "\n";
  }
  out->WriteText("x.csv", csv.str());
  if (!plots) return;
  Figure f;
  Plot p;
  p.title = r.solver + ": solution";
  p.x_label = "unknown index";
  p.y_label = "value";
  PlotSeries xs{"estimate", PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
  PlotSeries ts{"reference", PlotSeries::Style::kLines, {}, {}, {}, {}};
  for (Eigen::Index i = 0; i < s.x.size(); ++i) {
    xs.x.push_back(i + 1.0);
    xs.y.push_back(s.x[i]);
    if (r.truth.size() > 0) {
      ts.x.push_back(i + 1.0);
      ts.y.push_back(r.truth[i]);
    }
  }
  p.series.push_back(xs);
  if (r.truth.size() > 0) p.series.push_back(ts);
  f.panels.push_back(p);
  if (!reg.grid_lambda.empty()) {
    f.columns = 3;
    f.width_px = 1500;
    for (const Plot& panel :
         RegularisationPlots(reg, "residual norm", "solution (semi)norm"))
      f.panels.push_back(panel);
  }
  RenderStaged(f, "solution", out, warnings);
}

std::string SolveReport(const SolveResult& r) {
  std::ostringstream o;
  const LinearSolution& s = r.solution;
  o << "problem: " << r.problem.num_rows() << " x " << r.problem.num_unknowns()
    << ", rank " << s.identifiability.rank << ", condition number "
    << s.identifiability.condition_number << "\nsolver " << r.solver << ": "
    << ToString(s.summary.status) << ": " << s.summary.message << "\n";
  for (const auto& w : s.summary.warnings) o << "  warning: " << w << "\n";
  if (r.truth.size() > 0)
    o << "relative error vs reference: " << (s.x - r.truth).norm() / r.truth.norm()
      << "\n";
  o << "residual norm: " << s.residual.norm() << "\n";
  return o.str();
}

}  // namespace femup
