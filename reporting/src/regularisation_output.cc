#include "regularisation_output.h"

#include <algorithm>
#include <cmath>

#include "json_util.h"

namespace femup {

nlohmann::json RegularisationJson(const RegularisationReport& reg) {
  return {{"parameter_choice", reg.parameter_choice},
          {"lambda", json_util::Number(reg.lambda)},
          {"truncation", reg.truncation},
          {"at_range_end", reg.at_range_end},
          {"note", reg.note},
          {"lambda_lcurve", json_util::Number(reg.lambda_lcurve)},
          {"lambda_gcv", json_util::Number(reg.lambda_gcv)},
          {"lambda_discrepancy", json_util::Number(reg.lambda_discrepancy)},
          {"lambda_quasi_optimality", json_util::Number(reg.lambda_quasi)},
          {"grid_lambda", reg.grid_lambda},
          {"grid_residual_norm", reg.grid_residual_norm},
          {"grid_solution_norm", reg.grid_solution_norm},
          {"grid_gcv", reg.grid_gcv},
          {"grid_curvature", reg.grid_curvature}};
}

std::vector<Plot> RegularisationPlots(const RegularisationReport& reg,
                                      const std::string& residual_label,
                                      const std::string& norm_label) {
  if (reg.grid_lambda.empty()) return {};
  // The chosen point: the k-th (tsvd) or the grid point nearest the chosen lambda.
  std::size_t at = 0;
  if (reg.truncation > 0) {
    at = std::min<std::size_t>(reg.truncation - 1, reg.grid_lambda.size() - 1);
  } else {
    for (std::size_t i = 1; i < reg.grid_lambda.size(); ++i) {
      if (std::abs(std::log(reg.grid_lambda[i] / reg.lambda)) <
          std::abs(std::log(reg.grid_lambda[at] / reg.lambda)))
        at = i;
    }
  }
  Plot lc;
  lc.title = "L-curve (" + reg.parameter_choice + ")";
  lc.x_label = residual_label;
  lc.y_label = norm_label;
  lc.log_x = lc.log_y = true;
  lc.series.push_back({"path",
                       PlotSeries::Style::kLines,
                       reg.grid_residual_norm,
                       reg.grid_solution_norm,
                       {},
                       {}});
  lc.series.push_back({"chosen",
                       PlotSeries::Style::kPoints,
                       {reg.grid_residual_norm[at]},
                       {reg.grid_solution_norm[at]},
                       {},
                       {}});
  Plot gp;
  gp.title = "GCV function";
  gp.x_label = reg.truncation > 0 ? "singular value kept" : "lambda";
  gp.y_label = "GCV";
  gp.log_x = gp.log_y = true;
  gp.series.push_back(
      {"GCV", PlotSeries::Style::kLines, reg.grid_lambda, reg.grid_gcv, {}, {}});
  gp.series.push_back({"chosen",
                       PlotSeries::Style::kPoints,
                       {reg.grid_lambda[at]},
                       {reg.grid_gcv[at]},
                       {},
                       {}});
  return {lc, gp};
}

}  // namespace femup
