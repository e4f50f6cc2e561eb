#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/reporting/outputs.h"
#include "json_util.h"
#include "render_staged.h"

namespace femup {

void WriteModesOutputs(const ModesResult& r, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings) {
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "modes";
  j["study"] = r.study_name;
  j["model"] = {{"description", r.model_description}, {"dofs", r.dof_labels.size()}};
  j["frequencies_hz"] = json_util::Vector(r.nominal.FrequenciesHz());
  j["eigenvalues"] = json_util::Vector(r.nominal.eigenvalues);
  j["dof_labels"] = r.dof_labels;
  j["shapes_mass_normalised"] = nlohmann::json::array();
  for (int k = 0; k < r.nominal.size(); ++k) {
    j["shapes_mass_normalised"].push_back(json_util::Vector(r.nominal.shapes.col(k)));
  }
  j["checks"] = {{"max_relative_residual", r.max_residual},
                 {"max_orthogonality_error", r.max_orthogonality_error}};
  out->WriteText("modes.json", j.dump(2) + "\n");
  if (!plots) return;
  std::vector<int> all(r.dof_labels.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  const std::vector<int> rows = TransverseRows(r.dof_labels, all);
  Figure f;
  Plot p;
  p.title = r.study_name + ": mode shapes (mass-normalised)";
  p.x_label = rows.size() == r.dof_labels.size() ? "DOF position" : "height (m)";
  p.y_label = "transverse displacement";
  p.key_outside = true;
  const int shown = std::min(r.nominal.size(), 6);
  const Eigen::VectorXd hz = r.nominal.FrequenciesHz();
  for (int k = 0; k < shown; ++k) {
    std::ostringstream t;
    t << "mode " << k + 1 << " (" << std::fixed << std::setprecision(2) << hz[k]
      << " Hz)";
    PlotSeries s{t.str(), PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    if (rows.size() != r.dof_labels.size()) {
      s.x.push_back(0.0);  // the clamped base
      s.y.push_back(0.0);
    }
    for (int i : rows) {
      s.x.push_back(i < static_cast<int>(r.dof_positions.size()) ? r.dof_positions[i]
                                                                 : i + 1);
      s.y.push_back(r.nominal.shapes(i, k));
    }
    p.series.push_back(s);
  }
  f.panels.push_back(p);
  RenderStaged(f, "mode_shapes", out, warnings);
}

std::string ModesReport(const ModesResult& r) {
  std::ostringstream o;
  o << "study: " << r.study_name << "\nmodel: " << r.model_description << " ("
    << r.dof_labels.size() << " DOFs)\n  mode  frequency_Hz\n";
  const Eigen::VectorXd hz = r.nominal.FrequenciesHz();
  o << std::fixed;
  for (int k = 0; k < r.nominal.size(); ++k) {
    o << "  " << std::setw(4) << k + 1 << std::setw(14) << std::setprecision(4) << hz[k]
      << "\n";
  }
  o << std::scientific << std::setprecision(2) << "checks: max relative residual "
    << r.max_residual << ", max |Phi'M Phi - I| " << r.max_orthogonality_error << "\n";
  return o.str();
}

}  // namespace femup
