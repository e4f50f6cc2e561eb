#include <cmath>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/reporting/outputs.h"
#include "femup/reporting/plot.h"
#include "femup/studies/study.h"
#include "json_util.h"
#include "render_staged.h"

namespace femup {

void WriteCompareOutputs(const CompareResult& r, bool plots, OutputDir* out,
                         std::vector<std::string>* warnings) {
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "compare";
  j["studies"] = nlohmann::json::array();
  for (std::size_t s = 0; s < r.updates.size(); ++s) {
    const UpdateResult& u = r.updates[s];
    const AddedMassSummary& a = u.added_mass_summary;
    nlohmann::json sj = {{"file", r.paths[s]},
                         {"study", u.study_name},
                         {"status", ToString(u.solution.summary.status)},
                         {"sa", a.sa},
                         {"added_mass_kg", a.total_kg},
                         {"added_mass_per_length", a.per_length},
                         {"wet_elements", a.wet_elements},
                         {"element_x0", r.element_x0[s]},
                         {"element_x1", r.element_x1[s]},
                         {"element_factor", r.element_factor[s]}};
    sj["states"] = nlohmann::json::array();
    for (const StateComparison& c : u.states) {
      sj["states"].push_back({{"state", c.state},
                              {"measured_hz", json_util::Vector(c.measured_hz)},
                              {"model_hz", json_util::Vector(c.model_hz)},
                              {"updated_hz", json_util::Vector(c.updated_hz)},
                              {"updated_mac", json_util::Vector(c.updated_mac)}});
    }
    j["studies"].push_back(sj);
  }
  out->WriteText("comparison.json", j.dump(2) + "\n");
  if (!plots) return;

  Figure ff;
  Plot p;
  p.title = "added-mass factor per wet element";
  p.x_label = "height above the base (m)";
  p.y_label = "added-mass factor";
  p.key_outside = true;
  for (std::size_t s = 0; s < r.updates.size(); ++s) {
    PlotSeries ser{r.updates[s].study_name, PlotSeries::Style::kLines, {}, {}, {}, {}};
    for (std::size_t e = 0; e < r.element_factor[s].size(); ++e) {
      ser.x.push_back(r.element_x0[s][e]);
      ser.y.push_back(r.element_factor[s][e]);
      ser.x.push_back(r.element_x1[s][e]);
      ser.y.push_back(r.element_factor[s][e]);
    }
    if (!ser.x.empty()) p.series.push_back(ser);
  }
  ff.panels.push_back(p);
  if (!p.series.empty()) RenderStaged(ff, "added_mass_factors", out, warnings);

  Figure sf;
  Plot q;
  q.title = "sensitivity indicator Sa (mean wet-element factor, Eq. 36)";
  q.x_label = "study";
  q.y_label = "Sa";
  PlotSeries bars{"Sa", PlotSeries::Style::kBars, {}, {}, {}, {}};
  for (std::size_t s = 0; s < r.updates.size(); ++s) {
    q.x_tick_labels.push_back(r.updates[s].study_name);
    bars.x.push_back(s + 1.0);
    bars.y.push_back(r.updates[s].added_mass_summary.sa);
  }
  q.series.push_back(bars);
  sf.panels.push_back(q);
  RenderStaged(sf, "sa", out, warnings);
}

std::string CompareReport(const CompareResult& r) {
  std::ostringstream o;
  o << std::fixed;
  o << std::left << std::setw(28) << "study" << std::right << std::setw(8) << "factors"
    << std::setw(9) << "Sa" << std::setw(10) << "kg/m"
    << "  updated Hz (error %) per state\n";
  for (std::size_t s = 0; s < r.updates.size(); ++s) {
    const UpdateResult& u = r.updates[s];
    const AddedMassSummary& a = u.added_mass_summary;
    o << std::left << std::setw(28) << u.study_name << std::right << std::setw(8)
      << u.parameters.size() << std::setw(9) << std::setprecision(4) << a.sa
      << std::setw(10) << a.per_length << " ";
    for (const StateComparison& c : u.states) {
      o << " " << c.state << ":";
      for (Eigen::Index k = 0; k < c.measured_hz.size(); ++k) {
        o << " " << std::setprecision(3) << c.updated_hz[k] << " (" << std::showpos
          << std::setprecision(2)
          << (c.updated_hz[k] - c.measured_hz[k]) / c.measured_hz[k] * 100
          << std::noshowpos << ")";
      }
    }
    if (!u.solution.summary.usable())
      o << "  [" << ToString(u.solution.summary.status) << "]";
    o << "\n";
  }
  if (!r.updates.empty()) {
    o << "measured:";
    for (const StateComparison& c : r.updates.front().states) {
      o << " " << c.state << ":";
      for (Eigen::Index k = 0; k < c.measured_hz.size(); ++k)
        o << " " << std::setprecision(3) << c.measured_hz[k];
    }
    o << "\n";
  }
  return o.str();
}

}  // namespace femup
