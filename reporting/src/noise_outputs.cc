#include <algorithm>
#include <atomic>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/counter_rng.h"
#include "femup/core/errors.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/parallel.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/noise.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/factor_solve.h"
#include "json_util.h"
#include "render_staged.h"

namespace femup {

void WriteNoiseOutputs(const NoiseStudyResult& r, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings) {
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "noise";
  j["study"] = r.study_name;
  j["noise_model"] = {{"description",
                       "each measured eigenvalue and mode-shape entry multiplied by (1 + "
                       "level * r), r an "
                       "independent draw per entry"},
                      {"distribution", ToString(r.spec.distribution)},
                      {"draws_per_level", r.spec.draws},
                      {"seed", r.spec.seed},
                      {"generator",
                       "Philox4x64-10 (Random123), one stream per (seed, level, draw); "
                       "normal draws by the polar method"}};
  j["levels"] = r.spec.levels;
  j["usable_draws"] = r.usable_draws;
  j["rm_average_percent"] = nlohmann::json::array();
  for (double v : r.rm_average) j["rm_average_percent"].push_back(json_util::Number(v));
  j["rm_percent"] = nlohmann::json::array();
  for (std::size_t k = 0; k < r.added_mass_indices.size(); ++k) {
    nlohmann::json f = {{"parameter", r.parameter_names[r.added_mass_indices[k]]},
                        {"preset", r.preset[r.added_mass_indices[k]]}};
    for (const char* key : {"mean", "std", "median", "p90"})
      f[key] = nlohmann::json::array();
    for (std::size_t l = 0; l < r.rm.size(); ++l) {
      f["mean"].push_back(json_util::Number(r.rm[l][k].mean));
      f["std"].push_back(json_util::Number(r.rm[l][k].std_dev));
      f["median"].push_back(json_util::Number(r.rm[l][k].median));
      f["p90"].push_back(json_util::Number(r.rm[l][k].p90));
    }
    j["rm_percent"].push_back(f);
  }
  j["estimates_at_level"] = {{"level", r.figure_level},
                             {"parameters", nlohmann::json::array()}};
  for (std::size_t i = 0; i < r.parameter_names.size(); ++i) {
    j["estimates_at_level"]["parameters"].push_back(
        {{"name", r.parameter_names[i]},
         {"preset", r.preset[i]},
         {"mean", json_util::Number(r.figure_mean[i])},
         {"std", json_util::Number(r.figure_std[i])},
         {"first_draw", json_util::Number(r.figure_first_draw[i])}});
  }
  j["noise_model"]["shape_level_ratio"] = r.spec.shape_level_ratio;
  j["noise_model"]["shape_noise"] = r.spec.shape_noise;
  j["comparison"] = nlohmann::json::array();
  for (const SolverScores& c : r.comparison) {
    nlohmann::json cj = {{"label", c.label}, {"seconds", c.seconds}};
    cj["usable_draws"] = c.usable_draws;
    cj["rm_average_percent"] = nlohmann::json::array();
    cj["rm_median_percent"] = nlohmann::json::array();
    for (double v : c.rm_average)
      cj["rm_average_percent"].push_back(json_util::Number(v));
    for (double v : c.rm_median) cj["rm_median_percent"].push_back(json_util::Number(v));
    j["comparison"].push_back(cj);
  }
  out->WriteText("noise.json", j.dump(2) + "\n");
  if (!plots) return;

  // Fig. 4: estimated (mean +- std over draws) vs preset at one level.
  Figure f4;
  f4.width_px = std::max(900, 40 * static_cast<int>(r.parameter_names.size()) + 200);
  Plot p4;
  std::ostringstream title;
  title << r.study_name << ": factors at " << r.figure_level * 100 << " % corruption ("
        << r.spec.draws << " draws, mean and 1 std)";
  p4.title = title.str();
  p4.x_label = "parameter";
  p4.y_label = "factor";
  PlotSeries preset{"preset", PlotSeries::Style::kBars, {}, {}, {}, {}};
  PlotSeries est{"estimated", PlotSeries::Style::kErrorBars, {}, {}, {}, {}};
  for (std::size_t i = 0; i < r.parameter_names.size(); ++i) {
    p4.x_tick_labels.push_back(r.parameter_names[i]);
    preset.x.push_back(i + 1.0);
    preset.y.push_back(r.preset[i]);
    est.x.push_back(i + 1.0);
    est.y.push_back(r.figure_mean[i]);
    est.y_low.push_back(r.figure_mean[i] - r.figure_std[i]);
    est.y_high.push_back(r.figure_mean[i] + r.figure_std[i]);
  }
  p4.series = {preset, est};
  f4.panels.push_back(p4);
  RenderStaged(f4, "factors_at_level", out, warnings);

  // Fig. 5: Rm against corruption level, per added-mass factor and the average.
  Figure f5;
  Plot p5;
  p5.title = r.study_name + ": added-mass error Rm against corruption level";
  p5.x_label = "corruption level (%)";
  p5.y_label = "mean Rm (%)";
  std::vector<double> x;
  for (double l : r.spec.levels) x.push_back(l * 100);
  for (std::size_t k = 0; k < r.added_mass_indices.size(); ++k) {
    PlotSeries s{r.parameter_names[r.added_mass_indices[k]],
                 PlotSeries::Style::kLinesPoints,
                 x,
                 {},
                 {},
                 {}};
    for (std::size_t l = 0; l < r.rm.size(); ++l) s.y.push_back(r.rm[l][k].mean);
    p5.series.push_back(s);
  }
  p5.series.push_back({"average", PlotSeries::Style::kLines, x, r.rm_average, {}, {}});
  f5.panels.push_back(p5);
  RenderStaged(f5, "rm_vs_level", out, warnings);

  // Every compared solver: average Rm against level.
  if (r.comparison.size() > 1) {
    Figure fc;
    Plot pc;
    pc.title = r.study_name + ": added-mass error by solver (same draws)";
    pc.x_label = "corruption level of eigenvalues (%)";
    pc.y_label = "mean Rm over factors and draws (%)";
    for (const SolverScores& c : r.comparison)
      pc.series.push_back(
          {c.label, PlotSeries::Style::kLinesPoints, x, c.rm_average, {}, {}});
    fc.panels.push_back(pc);
    RenderStaged(fc, "rm_by_solver", out, warnings);
  }
}

std::string NoiseReport(const NoiseStudyResult& r) {
  std::ostringstream o;
  o << "noise study: " << r.study_name << " (" << r.spec.draws << " draws per level, "
    << ToString(r.spec.distribution) << " r, seed " << r.spec.seed << ")\n";
  o << "mean Rm (%) per added-mass factor\n  level_%";
  for (int k : r.added_mass_indices) o << std::setw(16) << r.parameter_names[k];
  o << std::setw(12) << "average" << std::setw(8) << "usable"
    << "\n";
  o << std::fixed;
  for (std::size_t l = 0; l < r.rm.size(); ++l) {
    o << std::setw(9) << std::setprecision(1) << r.spec.levels[l] * 100;
    for (const auto& s : r.rm[l]) o << std::setw(16) << std::setprecision(3) << s.mean;
    o << std::setw(12) << std::setprecision(3) << r.rm_average[l] << std::setw(8)
      << r.usable_draws[l] << "\n";
  }
  if (r.comparison.size() > 1) {
    o << "\nmean Rm (%) by solver, same draws (shape level = " << r.spec.shape_level_ratio
      << " x eigenvalue level)\n  level_%";
    // Each column as wide as its label or a 12-character number, whichever is wider.
    auto width = [](const SolverScores& c) {
      return static_cast<int>(std::max<std::size_t>(c.label.size(), 12)) + 2;
    };
    for (const SolverScores& c : r.comparison) o << std::setw(width(c)) << c.label;
    o << "\n";
    for (std::size_t l = 0; l < r.spec.levels.size(); ++l) {
      o << std::setw(9) << std::setprecision(2) << r.spec.levels[l] * 100;
      for (const SolverScores& c : r.comparison) {
        o << std::setw(width(c)) << std::setprecision(2) << c.rm_average[l];
      }
      o << "\n";
    }
    o << "  solve time (s):";
    for (const SolverScores& c : r.comparison)
      o << " " << c.label << " " << c.seconds << ";";
    o << "\n";
  }
  return o.str();
}

}  // namespace femup
