#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/reporting/diagnosis_map_figure.h"
#include "femup/reporting/outputs.h"
#include "json_util.h"
#include "render_staged.h"
#include "stated_priors_text.h"

namespace femup {

namespace {

using json_util::Number;

std::string Label(const RankedClass& c) {
  return c.region.empty() ? c.kind : c.kind + " at " + c.region;
}

// The mean MAC over the modes whose shapes were compared (NaN: none were).
double MeanMac(const RankedClass& c) {
  double sum = 0;
  int n = 0;
  for (const PairedModeMisfit& m : c.modes) {
    if (std::isnan(m.mac)) continue;
    sum += m.mac;
    ++n;
  }
  return n > 0 ? sum / n : std::numeric_limits<double>::quiet_NaN();
}

std::string ModeName(const StructureDiagnosisResult& r, const PairedModeMisfit& m) {
  const std::size_t s = static_cast<std::size_t>(m.state);
  const std::string state = s < r.measured.size() && !r.measured[s].state.empty()
                                ? r.measured[s].state
                                : "state " + std::to_string(m.state + 1);
  return state + " " + std::to_string(m.mode + 1);
}

// Both classes' predictions of the same measured modes, or false.
bool SameModes(const RankedClass* a, const RankedClass* b) {
  return a != nullptr && b != nullptr && !a->modes.empty() &&
         a->modes.size() == b->modes.size();
}

// One measured mode and two models' predictions of it: the nominal model's and
// "<other>"'s (updated: the class the gap is shown with; refit: the held-out
// check's fit).
nlohmann::json PairedModesJson(const StructureDiagnosisResult& r,
                               const PairedModeMisfit& a, const PairedModeMisfit& b,
                               const std::string& other) {
  return {{"state", r.measured.at(static_cast<std::size_t>(a.state)).state},
          {"mode", a.mode + 1},
          {"measured_hz", a.measured_hz},
          {"nominal_hz", a.model_hz},
          {other + "_hz", b.model_hz},
          {"nominal_error", a.model_hz / a.measured_hz - 1},
          {other + "_error", b.model_hz / b.measured_hz - 1},
          {"nominal_mac", Number(a.mac)},
          {other + "_mac", Number(b.mac)}};
}

}  // namespace

void WriteStructureDiagnosisOutputs(const StructureDiagnosisResult& r, bool plots,
                                    OutputDir* out, std::vector<std::string>* warnings) {
  nlohmann::json j;
  j["study"] = r.study_name;
  j["model_type"] = r.model_type;
  const EffectRanking& k = r.ranking;
  const RankedClass& top = k.classes.front();
  j["verdict"] = {{"kind", top.kind},
                  {"region", top.region},
                  {"probability", top.probability},
                  {"kind_probability", KindProbability(k, top.kind)},
                  {"gap_probability", k.gap_probability},
                  {"gap_below_confidence", k.gap_below_confidence},
                  {"gap_unexplained", k.gap_unexplained},
                  {"gap_within_noise", k.gap_within_noise},
                  {"nominal_misfit", k.nominal_misfit},
                  {"noise_misfit", k.noise_misfit},
                  {"separated", top.probability >= r.confidence},
                  {"equivalent", top.equivalent},
                  {"group_probability", top.group_probability}};
  j["confidence"] = r.confidence;
  j["gap_confidence"] = r.gap_confidence;
  j["gap_explained"] = r.gap_explained;
  j["temperature"] = k.temperature;
  j["frequency_temperature"] = ToString(k.frequency_temperature);
  j["shape_temperature"] = k.shape_temperature;
  j["best_chi2_p_value"] = k.best_chi2_p_value;
  j["residuals"] = k.num_residuals;
  j["bagging_copies"] = k.bagging_copies;
  j["form_errors"] = nlohmann::json::array();
  for (const FormErrorAllowance& e : k.form_errors)
    j["form_errors"].push_back({{"variant", e.name},
                                {"max_frequency_change", e.max_frequency_change},
                                {"noise_units", e.noise_units}});
  j["kinds"] = nlohmann::json::array();
  for (const auto& [kind, p] : k.kind_probabilities)
    j["kinds"].push_back({{"kind", kind}, {"probability", p}});
  // Each family's probability alone or in a pair (= "kinds" where no pair
  // was tried).
  j["family_presence"] = nlohmann::json::array();
  for (const auto& [family, p] : FamilyPresence(k))
    j["family_presence"].push_back({{"family", family}, {"probability", p}});
  j["classes"] = nlohmann::json::array();
  for (const RankedClass& c : k.classes) {
    nlohmann::json cj = {{"kind", c.kind},
                         {"region", c.region},
                         {"probability", c.probability},
                         {"laplace_probability", c.laplace_probability},
                         {"chi2", c.chi2},
                         {"explained", c.explained},
                         {"log_evidence", c.evidence.log_evidence},
                         {"log_occam", c.evidence.log_occam},
                         {"log_prior", c.log_prior},
                         {"frequency_temperature", c.frequency_temperature},
                         {"converged", c.converged},
                         {"fitted", c.fitted},
                         {"equivalent", c.equivalent},
                         {"group_probability", c.group_probability},
                         {"rms_frequency_error", Number(RmsFrequencyError(c))}};
    cj["parameters"] = nlohmann::json::array();
    for (std::size_t i = 0; i < c.names.size(); ++i)
      cj["parameters"].push_back({{"name", c.names[i]}, {"value", c.theta[i]}});
    cj["magnitudes"] = nlohmann::json::array();
    for (const EffectMagnitude& m : c.magnitudes)
      cj["magnitudes"].push_back(
          {{"name", m.name}, {"unit", m.unit}, {"value", m.value}});
    j["classes"].push_back(cj);
  }
  // How far the gap shrinks, mode by mode: the nominal model, then with the
  // verdict (or the most probable effect where the verdict is none).
  const RankedClass* none = NoneClass(k);
  const RankedClass* with = GapClass(k);
  if (SameModes(none, with)) {
    nlohmann::json modes = nlohmann::json::array();
    for (std::size_t i = 0; i < none->modes.size(); ++i)
      modes.push_back(PairedModesJson(r, none->modes[i], with->modes[i], "updated"));
    j["gap"] = {{"class", Label(*with)},
                {"class_is_verdict", with == &top},
                {"rms_nominal_error", Number(RmsFrequencyError(*none))},
                {"rms_updated_error", Number(RmsFrequencyError(*with))},
                {"modes", modes}};
  }
  if (k.held_out) {
    const HeldOutCheck& h = *k.held_out;
    nlohmann::json hj = {
        {"class", h.region.empty() ? h.kind : h.kind + " at " + h.region},
        {"ok", h.ok},
        {"why", h.why}};
    hj["modes"] = nlohmann::json::array();
    for (std::size_t i = 0; i < h.nominal.size() && i < h.refit.size(); ++i)
      hj["modes"].push_back(PairedModesJson(r, h.nominal[i], h.refit[i], "refit"));
    j["held_out"] = hj;
  }
  j["not_applicable"] = k.skipped;
  j["notes"] = k.notes;
  j["stated_priors"] = StatedPriorsJson(r.priors);
  out->WriteText("diagnosis.json", j.dump(2) + "\n");
  if (!plots) return;
  Figure f;
  Plot p;
  p.title = "Which effect: posterior probability of each family";
  p.y_label = "probability";
  PlotSeries bars;
  bars.style = PlotSeries::Style::kBars;
  for (std::size_t i = 0; i < k.kind_probabilities.size(); ++i) {
    p.x_tick_labels.push_back(k.kind_probabilities[i].first);
    bars.x.push_back(static_cast<double>(i + 1));
    bars.y.push_back(k.kind_probabilities[i].second);
  }
  p.series.push_back(bars);
  f.panels.push_back(p);
  RenderStaged(f, "effects", out, warnings);
  if (SameModes(none, with)) {
    Plot g;
    g.title = "Frequency error before and after " + Label(*with);
    g.y_label = "|f_model / f_measured - 1| (%)";
    g.log_y = true;
    PlotSeries b{"nominal model", PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    PlotSeries a{"with " + Label(*with), PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    for (std::size_t i = 0; i < none->modes.size(); ++i) {
      const PairedModeMisfit& m = none->modes[i];
      b.x.push_back(static_cast<double>(i + 1));
      a.x.push_back(static_cast<double>(i + 1));
      // Floored at 1e-4 % so that an exact fit still has a place on the log axis.
      b.y.push_back(std::max(1e-4, 100 * std::abs(m.model_hz / m.measured_hz - 1)));
      a.y.push_back(
          std::max(1e-4, 100 * std::abs(with->modes[i].model_hz / m.measured_hz - 1)));
      g.x_tick_labels.push_back(ModeName(r, m));
    }
    g.series = {b, a};
    Figure gf;
    gf.panels = {g};
    RenderStaged(gf, "gap", out, warnings);
  }
  if (!r.map.empty()) {
    RenderStaged(DiagnosisMapFigure(r.map, k, "Where: " + r.study_name), "diagnosis_map",
                 out, warnings);
  }
}

std::string StructureDiagnosisReport(const StructureDiagnosisResult& r) {
  std::ostringstream o;
  const EffectRanking& k = r.ranking;
  const RankedClass& top = k.classes.front();
  o << "diagnosis of " << r.study_name << " (" << r.model_type << " model)\n";
  if (!r.priors.empty()) o << "stated priors: " << StatedPriorsLine(r.priors) << "\n";
  if (top.kind == "none" && k.gap_below_confidence) {
    const auto& [family, p] = k.kind_probabilities.front();
    o << "verdict: no significant gap: a gap of any kind has P " << std::fixed
      << std::setprecision(2) << k.gap_probability << ", below gap_confidence "
      << r.gap_confidence << " (none P " << top.probability;
    if (family != "none") o << "; the most probable family " << family << " P " << p;
    o << ")\n";
  } else if (top.kind == "none" && k.gap_unexplained && k.gap_within_noise &&
             GapClass(k) != nullptr) {
    const RankedClass& best = *GapClass(k);
    o << "verdict: no gap beyond the noise: the nominal model's misfit, chi2 "
      << std::fixed << std::setprecision(1) << k.nominal_misfit
      << ", is within the noise's " << k.noise_misfit
      << (k.form_errors.empty() ? "" : " (the model's form error allowed for)")
      << "; the most probable effect, " << Label(best) << " (P " << std::setprecision(2)
      << best.probability << "; a gap of any kind P " << k.gap_probability
      << "), would fit noise, and is not named\n";
  } else if (top.kind == "none" && k.gap_unexplained && GapClass(k) != nullptr) {
    const RankedClass& best = *GapClass(k);
    o << "verdict: no effect explains the gap: the most probable, " << Label(best)
      << " (P " << std::fixed << std::setprecision(2) << best.probability
      << "; a gap of any kind P " << k.gap_probability << "), removes "
      << std::setprecision(1) << 100 * best.explained
      << " % of the nominal model's misfit beyond the noise, less than gap_explained "
      << std::setprecision(2) << r.gap_explained
      << " (the rest is a form error of the model, or an effect of no family tried)\n";
  } else if (top.kind == "none") {
    o << "verdict: no significant gap (P " << std::fixed << std::setprecision(2)
      << top.probability << ")\n";
  } else {
    o << "verdict: " << Label(top) << " (P " << std::fixed << std::setprecision(2)
      << top.probability << "; family " << k.kind_probabilities.front().first << " P "
      << k.kind_probabilities.front().second << ")";
    if (top.probability < r.confidence) o << ", not separated at " << r.confidence;
    o << "\n";
    if (!top.equivalent.empty()) {
      o << "  these data cannot tell it from:";
      for (const std::string& e : top.equivalent) o << " " << e << ";";
      o << " together P " << std::fixed << std::setprecision(2) << top.group_probability
        << "\n";
    }
  }
  for (const FormErrorAllowance& e : k.form_errors) {
    o << "model form error allowed for: " << e.name << " changes the measured modes' "
      << "frequencies by up to " << std::fixed << std::setprecision(2)
      << 100 * e.max_frequency_change << " % (" << std::setprecision(1) << e.noise_units
      << " noise units)\n";
  }
  const bool marginal =
      k.frequency_temperature == EffectRankingOptions::FrequencyTemperature::kMarginal;
  if (marginal) {
    o << "frequencies' noise temperature: integrated over for each class (a "
         "discrepancy of each mode of unknown size); the verdict's at T "
      << std::fixed << std::setprecision(2) << k.temperature
      << " (standard deviations scaled by " << std::sqrt(k.temperature) << ")";
    if (k.shape_temperature > 1)
      o << "; the shapes' scaled by " << std::sqrt(k.shape_temperature);
    o << "\n";
  } else if (k.temperature > 1 || k.shape_temperature > 1) {
    o << "note: no class fits within the stated noise (best p " << std::scientific
      << std::setprecision(1) << k.best_chi2_p_value
      << "): the model's own form error, or noise understated; standard deviations "
         "scaled by "
      << std::fixed << std::setprecision(2) << std::sqrt(k.temperature)
      << " (frequencies) and " << std::sqrt(k.shape_temperature) << " (shapes)\n";
  }
  if (std::any_of(k.kind_probabilities.begin(), k.kind_probabilities.end(),
                  [](const auto& e) { return e.first.find('+') != std::string::npos; })) {
    o << "each family, alone or in a pair:";
    for (const auto& [family, p] : FamilyPresence(k)) {
      if (p >= 0.005)
        o << " " << family << " P " << std::fixed << std::setprecision(2) << p << ";";
    }
    o << "\n";
  }
  o << "classes (the most probable family first, then its most probable places):\n";
  const std::size_t shown = std::min<std::size_t>(k.classes.size(), 8);
  for (std::size_t i = 0; i < shown; ++i) {
    const RankedClass& c = k.classes[i];
    o << "  " << std::left << std::setw(40) << Label(c) << std::right << " P "
      << std::fixed << std::setprecision(3) << c.probability << "  chi2 "
      << std::setprecision(1) << c.chi2;
    if (c.kind != "none")
      o << "  explains " << std::setprecision(0) << 100 * c.explained << " %";
    if (marginal && c.frequency_temperature > 1.05)
      o << "  T " << std::setprecision(1) << c.frequency_temperature;
    if (!c.fitted) o << "  (screened, not fitted)";
    for (const EffectMagnitude& m : c.magnitudes) {
      o << "  " << m.name << " " << std::setprecision(4) << std::defaultfloat << m.value;
      if (!m.unit.empty() && m.unit.front() != '1') o << " " << m.unit;
    }
    if (!c.equivalent.empty()) {
      o << "  (the same change as:";
      for (const std::string& e : c.equivalent) o << " " << e << ";";
      o << " together P " << std::setprecision(3) << std::fixed << c.group_probability
        << ")";
    }
    o << "\n";
  }
  const RankedClass* none = NoneClass(k);
  const RankedClass* with = GapClass(k);
  if (SameModes(none, with)) {
    o << "the gap, mode by mode: the nominal model, then "
      << (with == &top ? "with " : "with the most probable effect, ") << Label(*with)
      << ":\n";
    o << "  mode            measured Hz  nominal Hz  error %    MAC  |  with: Hz  error %"
         "    MAC\n";
    auto mac = [](double v) {
      std::ostringstream m;
      if (std::isnan(v)) {
        m << "      -";
      } else {
        m << std::fixed << std::setprecision(3) << std::setw(7) << v;
      }
      return m.str();
    };
    for (std::size_t i = 0; i < none->modes.size(); ++i) {
      const PairedModeMisfit& a = none->modes[i];
      const PairedModeMisfit& b = with->modes[i];
      o << "  " << std::left << std::setw(14) << ModeName(r, a) << std::right
        << std::fixed << std::setprecision(4) << std::setw(13) << a.measured_hz
        << std::setw(12) << a.model_hz << std::setprecision(3) << std::setw(9)
        << 100 * (a.model_hz / a.measured_hz - 1) << mac(a.mac) << "  |"
        << std::setprecision(4) << std::setw(10) << b.model_hz << std::setprecision(3)
        << std::setw(9) << 100 * (b.model_hz / b.measured_hz - 1) << mac(b.mac) << "\n";
    }
    o << "  rms frequency error " << std::fixed << std::setprecision(3)
      << 100 * RmsFrequencyError(*none) << " % -> " << 100 * RmsFrequencyError(*with)
      << " %";
    if (!std::isnan(MeanMac(*none)))
      o << "; mean MAC " << MeanMac(*none) << " -> " << MeanMac(*with);
    o << "\n";
  }
  if (k.held_out && !k.held_out->ok) {
    o << "held-out check of " << k.held_out->kind << ": not made (" << k.held_out->why
      << ")\n";
  } else if (k.held_out) {
    const HeldOutCheck& h = *k.held_out;
    o << "held-out check: " << (h.region.empty() ? h.kind : h.kind + " at " + h.region)
      << " fitted again without these modes predicts them (the ranking used every "
         "mode):\n";
    for (std::size_t i = 0; i < h.nominal.size() && i < h.refit.size(); ++i) {
      const PairedModeMisfit& a = h.nominal[i];
      const PairedModeMisfit& b = h.refit[i];
      o << "  " << std::left << std::setw(14) << ModeName(r, a) << std::right
        << std::fixed << std::setprecision(4) << " measured " << a.measured_hz
        << " Hz; nominal " << a.model_hz << " Hz (" << std::setprecision(3)
        << 100 * (a.model_hz / a.measured_hz - 1) << " %); refitted "
        << std::setprecision(4) << b.model_hz << " Hz (" << std::setprecision(3)
        << 100 * (b.model_hz / b.measured_hz - 1) << " %)";
      if (!std::isnan(b.mac)) o << "; MAC " << a.mac << " -> " << b.mac;
      o << "\n";
    }
  }
  for (const std::string& s : k.skipped) o << "not applicable: " << s << "\n";
  for (const std::string& s : k.notes) o << "note: " << s << "\n";
  return o.str();
}

}  // namespace femup
