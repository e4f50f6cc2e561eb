// The outputs of femup diagnose: diagnosis.json (verdict, noise, classes, the
// gap mode by mode before and after the top class, the localisation), the
// plots (where, which, how far the gap shrinks) and the terminal report.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/reporting/outputs.h"
#include "femup/reporting/plot.h"
#include "femup/studies/diagnose_study.h"
#include "json_util.h"
#include "render_staged.h"
#include "stated_priors_text.h"

namespace femup {

namespace {

std::string Fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

struct GapSummary {
  double rms_fitted = 0, rms_held_out = NAN, mean_mac_fitted = NAN,
         mean_mac_held_out = NAN;
};

void Accumulate(const EffectFitData& data, const std::vector<PredictedState>& pred,
                double* sum_sq, int* count, double* mac_sum, int* mac_count) {
  for (std::size_t s = 0; s < data.states.size() && s < pred.size(); ++s) {
    for (std::size_t j = 0; j < data.states[s].modes.size(); ++j) {
      const double e =
          pred[s].modes[j].frequency_hz / data.states[s].modes[j].frequency_hz - 1;
      *sum_sq += e * e;
      ++*count;
      if (data.states[s].modes[j].shape.size() > 0) {
        *mac_sum += pred[s].modes[j].mac;
        ++*mac_count;
      }
    }
  }
}

GapSummary Summarise(const DiagnosisResult& r, const std::vector<PredictedState>& fitted,
                     const std::vector<PredictedState>& held) {
  GapSummary g;
  double ss = 0, ms = 0;
  int n = 0, mn = 0;
  Accumulate(r.fitted_data, fitted, &ss, &n, &ms, &mn);
  g.rms_fitted = n > 0 ? std::sqrt(ss / n) : NAN;
  g.mean_mac_fitted = mn > 0 ? ms / mn : NAN;
  ss = ms = 0;
  n = mn = 0;
  Accumulate(r.held_out_data, held, &ss, &n, &ms, &mn);
  if (n > 0) g.rms_held_out = std::sqrt(ss / n);
  if (mn > 0) g.mean_mac_held_out = ms / mn;
  return g;
}

nlohmann::json GapJson(const GapSummary& g) {
  using json_util::Number;
  return {{"rms_frequency_error", Number(g.rms_fitted)},
          {"rms_frequency_error_held_out", Number(g.rms_held_out)},
          {"mean_mac", Number(g.mean_mac_fitted)},
          {"mean_mac_held_out", Number(g.mean_mac_held_out)}};
}

nlohmann::json LocationJson(const EffectLocation& l) {
  nlohmann::json j = nlohmann::json::object();
  if (std::isfinite(l.depth)) j["depth"] = l.depth;
  if (std::isfinite(l.x)) j["x"] = l.x;
  if (std::isfinite(l.x0)) j["x0"] = l.x0;
  if (std::isfinite(l.x1)) j["x1"] = l.x1;
  return j;
}

}  // namespace

void WriteDiagnosisOutputs(const DiagnosisResult& r, bool plots, OutputDir* out,
                           std::vector<std::string>* warnings) {
  using json_util::Number;
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "diagnose";
  j["study"] = r.study_name;
  j["length"] = r.length;
  j["verdict"] = {{"text", r.verdict},
                  {"kind", r.candidates.front().label},
                  {"kinds", r.candidates.front().kinds},
                  {"probability", r.verdict_probability},
                  {"separated", r.separated},
                  {"confidence", r.confidence},
                  {"indistinguishable", r.indistinguishable}};
  j["noise"] = {{"frequency", r.frequency_noise},
                {"shape", r.shape_noise},
                {"mesh_error", r.mesh_error},
                {"form_error", r.form_error},
                {"form_error_fraction", r.form_error_fraction},
                {"temperature", r.temperature},
                {"best_chi2_p_value", r.best_chi2_p_value},
                {"degrees_of_freedom", r.degrees_of_freedom}};
  nlohmann::json kp = nlohmann::json::object();
  for (const auto& [k, p] : r.kind_probabilities) kp[k] = p;
  j["kind_probabilities"] = kp;
  const GapSummary before = Summarise(r, r.nominal_fitted, r.nominal_held_out);
  j["effects"] = nlohmann::json::array();
  for (std::size_t i = 0; i < r.candidates.size(); ++i) {
    const DiagnosisCandidate& c = r.candidates[i];
    nlohmann::json cj = {{"rank", i + 1},
                         {"kind", c.label},
                         {"kinds", c.kinds},
                         {"probability", c.probability},
                         {"score", c.score},
                         {"log_evidence", c.evidence.log_evidence},
                         {"log_occam", c.evidence.log_occam},
                         {"basins", c.basins},
                         {"chi2", c.chi2},
                         {"held_out_chi2", c.held_out_chi2},
                         {"held_out_log_predictive", c.held_out_log_predictive},
                         {"evidence_method", c.evidence_method},
                         {"laplace_score", c.laplace_score},
                         {"evidence_draws", c.evidence_draws},
                         {"evidence_effective_draws", c.evidence_effective_draws},
                         {"evidence_standard_error", c.evidence_standard_error},
                         {"converged", c.converged},
                         {"fits", c.starts}};
    nlohmann::json params = nlohmann::json::object();
    for (std::size_t p = 0; p < c.names.size(); ++p) {
      const auto k = static_cast<Eigen::Index>(p);
      params[c.names[p]] = {
          {"value", Number(c.theta[k])},
          {"sigma", c.evidence.sigma.size() > k ? Number(c.evidence.sigma[k])
                                                : nlohmann::json(nullptr)}};
    }
    cj["parameters"] = params;
    cj["components"] = nlohmann::json::array();
    for (std::size_t e = 0; e < c.kinds.size(); ++e) {
      nlohmann::json mag = nlohmann::json::object();
      for (const auto& m : c.magnitudes[e])
        mag[m.name] = {{"value", Number(m.value)}, {"unit", m.unit}};
      cj["components"].push_back({{"kind", c.kinds[e]},
                                  {"location", LocationJson(c.locations[e])},
                                  {"magnitude", mag}});
    }
    if (c.kinds.size() == 1) {
      cj["location"] = cj["components"][0]["location"];
      cj["magnitude"] = cj["components"][0]["magnitude"];
    }
    cj["gap_before"] = GapJson(before);
    cj["gap_after"] = GapJson(Summarise(r, c.fitted, c.held_out));
    j["effects"].push_back(cj);
  }
  // Mode by mode, before and after the top class.
  const DiagnosisCandidate& top = r.candidates.front();
  nlohmann::json modes = nlohmann::json::array();
  auto add_modes = [&](const EffectFitData& data, const std::vector<PredictedState>& nom,
                       const std::vector<PredictedState>& upd, bool held_out) {
    for (std::size_t s = 0; s < data.states.size(); ++s) {
      for (std::size_t k = 0; k < data.states[s].modes.size(); ++k) {
        const ObservedMode& m = data.states[s].modes[k];
        const PredictedMode& a = nom[s].modes[k];
        const PredictedMode& b = upd[s].modes[k];
        const bool shape = m.shape.size() > 0;
        modes.push_back(
            {{"state", data.states[s].state},
             {"mode", m.number},
             {"held_out", held_out},
             {"measured_hz", m.frequency_hz},
             {"nominal_hz", a.frequency_hz},
             {"updated_hz", b.frequency_hz},
             {"nominal_error", a.frequency_hz / m.frequency_hz - 1},
             {"updated_error", b.frequency_hz / m.frequency_hz - 1},
             {"nominal_mac", shape ? Number(a.mac) : nlohmann::json(nullptr)},
             {"updated_mac", shape ? Number(b.mac) : nlohmann::json(nullptr)}});
      }
    }
  };
  add_modes(r.fitted_data, r.nominal_fitted, top.fitted, false);
  if (!r.held_out_data.states.empty())
    add_modes(r.held_out_data, r.nominal_held_out, top.held_out, true);
  j["gap"] = {{"class", top.label}, {"modes", modes}};
  j["localisation"] = nlohmann::json::array();
  for (const auto& e : r.localisation) {
    j["localisation"].push_back({{"element", e.element},
                                 {"x0", e.x0},
                                 {"x1", e.x1},
                                 {"stiffness_factor", Number(e.stiffness_factor)},
                                 {"stiffness_chi2_drop", e.stiffness_chi2_drop},
                                 {"mass_factor", Number(e.mass_factor)},
                                 {"mass_chi2_drop", e.mass_chi2_drop}});
  }
  j["warnings"] = r.warnings;
  j["stated_priors"] = StatedPriorsJson(r.priors);
  out->WriteText("diagnosis.json", j.dump(2) + "\n");
  if (!plots) return;

  // Where: chi2 drop per element along the structure.
  if (!r.localisation.empty()) {
    Plot p;
    p.title = "Where: chi2 removed by changing one element (verdict: " +
              r.candidates.front().label + ")";
    p.x_label = "height above the support (m)";
    p.y_label = "chi2 drop";
    PlotSeries ks{"bending stiffness of the element",
                  PlotSeries::Style::kLinesPoints,
                  {},
                  {},
                  {},
                  {}};
    PlotSeries ms{
        "mass added to the element", PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    double top_drop = 0;
    for (const auto& e : r.localisation) {
      const double mid = 0.5 * (e.x0 + e.x1);
      ks.x.push_back(mid);
      ks.y.push_back(e.stiffness_chi2_drop);
      ms.x.push_back(mid);
      ms.y.push_back(e.mass_chi2_drop);
      top_drop = std::max({top_drop, e.stiffness_chi2_drop, e.mass_chi2_drop});
    }
    p.series = {ks, ms};
    PlotSeries where{
        "located by the top class", PlotSeries::Style::kPoints, {}, {}, {}, {}};
    for (const auto& l : top.locations) {
      for (double x : {l.depth, l.x, l.x0, l.x1}) {
        if (std::isfinite(x)) {
          where.x.push_back(x);
          where.y.push_back(top_drop);
        }
      }
    }
    if (!where.x.empty()) p.series.push_back(where);
    Figure f;
    f.panels = {p};
    RenderStaged(f, "localisation", out, warnings);
  }
  // Which: probabilities of the leading classes.
  {
    Plot p;
    p.title = "Which effect: posterior probability of each class";
    p.y_label = "probability";
    PlotSeries bars{"posterior", PlotSeries::Style::kBars, {}, {}, {}, {}};
    const std::size_t shown = std::min<std::size_t>(10, r.candidates.size());
    for (std::size_t i = 0; i < shown; ++i) {
      bars.x.push_back(static_cast<double>(i + 1));
      bars.y.push_back(r.candidates[i].probability);
      p.x_tick_labels.push_back(r.candidates[i].label);
    }
    p.series = {bars};
    Figure f;
    f.panels = {p};
    f.width_px = 1100;
    RenderStaged(f, "effects", out, warnings);
  }
  // How far it shrinks: frequency error per mode before and after.
  {
    Plot p;
    p.title = "Frequency error before and after " + top.label + " (* held out)";
    p.y_label = "|f_model / f_measured - 1| (%)";
    p.log_y = true;
    PlotSeries b{"nominal model", PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    PlotSeries a{"with " + top.label, PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    int x = 0;
    for (const auto& m : modes) {
      ++x;
      b.x.push_back(x);
      a.x.push_back(x);
      b.y.push_back(std::max(1e-4, 100 * std::abs(m["nominal_error"].get<double>())));
      a.y.push_back(std::max(1e-4, 100 * std::abs(m["updated_error"].get<double>())));
      p.x_tick_labels.push_back(m["state"].get<std::string>() + " " +
                                std::to_string(m["mode"].get<int>()) +
                                (m["held_out"].get<bool>() ? "*" : ""));
    }
    p.series = {b, a};
    Figure f;
    f.panels = {p};
    RenderStaged(f, "gap", out, warnings);
  }
}

std::string DiagnosisReport(const DiagnosisResult& r) {
  std::ostringstream o;
  o << "femup diagnose: " << r.study_name << "\n";
  o << "  data: " << r.fitted_data.states.size() << " state(s), " << r.degrees_of_freedom
    << " informative residuals fitted";
  int held = 0;
  for (const auto& s : r.held_out_data.states) held += static_cast<int>(s.modes.size());
  o << ", " << held << " mode(s) held out\n";
  o << "  noise: frequency " << 100 * r.frequency_noise << " %, shape "
    << 100 * r.shape_noise << " %";
  if (r.form_error_fraction > 0)
    o << ", form error " << 100 * r.form_error_fraction << " % of the nominal misfit";
  if (r.temperature > 1) o << " (scaled by sqrt(" << Fixed(r.temperature, 2) << "))";
  o << "\n";
  if (!r.priors.empty()) o << "  stated priors: " << StatedPriorsLine(r.priors) << "\n";
  o << "\n  verdict: " << r.verdict << "\n\n";
  o << "  rank  class                                    P       chi2   held-out  "
       "where\n";
  const std::size_t shown = std::min<std::size_t>(8, r.candidates.size());
  for (std::size_t i = 0; i < shown; ++i) {
    const auto& c = r.candidates[i];
    std::ostringstream where;
    for (std::size_t e = 0; e < c.locations.size(); ++e) {
      const auto& l = c.locations[e];
      if (e) where << "; ";
      if (std::isfinite(l.depth)) {
        where << "depth " << Fixed(l.depth, 2) << " m";
      } else if (std::isfinite(l.x) && std::isfinite(l.x0)) {
        where << "x " << Fixed(l.x0, 2) << "-" << Fixed(l.x1, 2) << " m";
      } else if (std::isfinite(l.x)) {
        where << "x " << Fixed(l.x, 2) << " m";
      } else {
        where << "everywhere";
      }
    }
    o << "  " << std::setw(4) << i + 1 << "  " << std::left << std::setw(40) << c.label
      << std::right << std::setw(6) << Fixed(c.probability, 3) << std::setw(11)
      << Fixed(c.chi2, 1) << std::setw(10) << Fixed(c.held_out_chi2, 1) << "  "
      << where.str() << "\n";
  }
  const auto& top = r.candidates.front();
  o << "\n  gap (" << top.label
    << "): mode, measured Hz, nominal error %, updated error %\n";
  auto list = [&](const EffectFitData& d, const std::vector<PredictedState>& nom,
                  const std::vector<PredictedState>& upd, const char* tag) {
    for (std::size_t s = 0; s < d.states.size(); ++s) {
      for (std::size_t k = 0; k < d.states[s].modes.size(); ++k) {
        const auto& m = d.states[s].modes[k];
        o << "    " << d.states[s].state << " " << m.number << tag << "  "
          << Fixed(m.frequency_hz, 3) << "  "
          << Fixed(100 * (nom[s].modes[k].frequency_hz / m.frequency_hz - 1), 3) << "  "
          << Fixed(100 * (upd[s].modes[k].frequency_hz / m.frequency_hz - 1), 3) << "\n";
      }
    }
  };
  list(r.fitted_data, r.nominal_fitted, top.fitted, "");
  if (!r.held_out_data.states.empty())
    list(r.held_out_data, r.nominal_held_out, top.held_out, " (held out)");
  for (const auto& w : r.warnings) o << "  warning: " << w << "\n";
  return o.str();
}

}  // namespace femup
