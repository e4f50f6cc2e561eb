// The blind benchmark's scores (blind_benchmark.h): top-1 accuracy overall and
// per stratum, calibration, confusion, gaps and the Bayes oracle's ceiling, as
// scores.json, results.jsonl, plots and the Markdown report.
#include <algorithm>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "benchmark_generator.h"
#include "blind_benchmark_common.h"
#include "femup/evaluation/blind_benchmark.h"
#include "femup/reporting/plot.h"
#include "json_util.h"
#include "render_staged.h"

namespace femup {

using benchmark_generator::Ranges;
using blind_benchmark::AtNoiseLevel;
using blind_benchmark::kNan;
using blind_benchmark::Num;
using blind_benchmark::TruthLabel;

namespace {

std::set<std::string> KindSet(const std::vector<std::string>& v) {
  return std::set<std::string>(v.begin(), v.end());
}

bool Correct(const BenchmarkCase& c) {
  std::set<std::string> truth;
  for (const auto& e : c.effects) truth.insert(e.kind);
  return !c.failed && KindSet(c.top_kinds) == truth;
}

struct Tally {
  int n = 0, right = 0;
  void Add(bool ok) {
    ++n;
    right += ok ? 1 : 0;
  }
  double Rate() const { return n ? static_cast<double>(right) / n : kNan; }
  nlohmann::json Json() const {
    return {{"cases", n}, {"right", right}, {"rate", json_util::Number(Rate())}};
  }
};

struct Scores {
  Tally overall, single_effect, two_effects, none_cases, with_shapes, without_shapes;
  Tally both_named, located, confident;
  std::map<std::string, Tally> per_kind, per_noise, per_size;
  std::map<std::string, std::map<std::string, int>> confusion;
  std::map<std::string, Tally> calibration;  // probability bins
  int failed = 0;
  double median_gap_before = kNan, median_gap_after = kNan;
  double median_held_before = kNan, median_held_after = kNan;
  double seconds = 0;
  // The Bayes oracle, where it ran: its top-1 and the diagnosis's on the same
  // cases, per stratum ("none", "at the noise level" (< 5 sigma), "above");
  // the misses of the oracle and the sum of its top probabilities (its own
  // expected number right) on the cases with no effect or effects at the
  // noise level; the worst sampling quality among the cases.
  std::map<std::string, Tally> oracle, oracle_diagnosis;
  int oracle_failed = 0, oracle_low_misses = 0, oracle_low_run = 0;
  double oracle_low_expected = 0, oracle_seconds = 0;
  double oracle_worst_se = 0, oracle_fewest_draws = kNan, oracle_affine_error = 0;
};

double Median(std::vector<double> v) {
  if (v.empty()) return kNan;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string PredictedLabel(const BenchmarkCase& c) {
  if (c.failed) return "failed";
  if (c.top_kinds.empty()) return "none";
  if (c.top_kinds.size() > 1) return "pair";
  return c.top_kinds[0];
}

Scores Score(const BenchmarkResult& r) {
  Scores s;
  std::vector<double> gb, ga, hb, ha;
  for (const BenchmarkCase& c : r.cases) {
    s.seconds += c.seconds;
    if (c.failed) ++s.failed;
    const bool ok = Correct(c);
    s.overall.Add(ok);
    const std::string truth = c.effects.empty()       ? "none"
                              : c.effects.size() == 1 ? c.effects[0].kind
                                                      : "pair";
    s.per_kind[truth].Add(ok);
    s.confusion[truth][PredictedLabel(c)]++;
    std::ostringstream noise;
    noise << 100 * c.frequency_noise << " % / " << 100 * c.shape_noise << " %";
    s.per_noise[noise.str()].Add(ok);
    (c.shapes ? s.with_shapes : s.without_shapes).Add(ok);
    if (c.effects.empty()) s.none_cases.Add(ok);
    if (c.effects.size() == 1) s.single_effect.Add(ok);
    if (c.effects.size() == 2) {
      s.two_effects.Add(ok);
      std::set<std::string> named = KindSet(c.top_kinds);
      for (const auto& k : c.second_kinds) named.insert(k);
      bool both = true;
      for (const auto& e : c.effects) both = both && named.count(e.kind) > 0;
      s.both_named.Add(!c.failed && both);
    }
    double weakest = 1e9;
    for (const auto& e : c.effects) weakest = std::min(weakest, e.shift_in_noise);
    if (!c.effects.empty())
      s.per_size[weakest < 5 ? "shift < 5 sigma" : "shift >= 5 sigma"].Add(ok);
    // Localisation: every located true effect the top class names, within L/10.
    if (ok && c.location_error >= 0) s.located.Add(c.location_error <= 0.1 * c.length);
    if (c.oracle.run) {
      if (!c.oracle.error.empty()) {
        ++s.oracle_failed;
      } else {
        const bool right = c.oracle.top == TruthLabel(c);
        const std::string stratum = c.effects.empty() ? "none"
                                    : AtNoiseLevel(c) ? "shift < 5 sigma"
                                                      : "shift >= 5 sigma";
        s.oracle[stratum].Add(right);
        s.oracle["all run"].Add(right);
        s.oracle_diagnosis[stratum].Add(ok);
        s.oracle_diagnosis["all run"].Add(ok);
        if (AtNoiseLevel(c)) {
          ++s.oracle_low_run;
          s.oracle_low_misses += right ? 0 : 1;
          s.oracle_low_expected += c.oracle.probability;
        }
        s.oracle_seconds += c.oracle.seconds;
        s.oracle_worst_se = std::max(s.oracle_worst_se, c.oracle.log_standard_error);
        if (!(c.oracle.effective_samples >= s.oracle_fewest_draws))
          s.oracle_fewest_draws = c.oracle.effective_samples;
        s.oracle_affine_error = std::max(s.oracle_affine_error, c.oracle.affine_error);
      }
    }
    if (!c.failed) {
      const double p = c.probability;
      const char* bin = p >= 0.99  ? "0.99-1"
                        : p >= 0.9 ? "0.90-0.99"
                        : p >= 0.7 ? "0.70-0.90"
                                   : "below 0.70";
      s.calibration[bin].Add(ok);
      if (p >= 0.9) s.confident.Add(ok);
      gb.push_back(c.gap_before);
      ga.push_back(c.gap_after);
      if (c.held_out_before >= 0) {
        hb.push_back(c.held_out_before);
        ha.push_back(c.held_out_after);
      }
    }
  }
  s.median_gap_before = Median(gb);
  s.median_gap_after = Median(ga);
  s.median_held_before = Median(hb);
  s.median_held_after = Median(ha);
  return s;
}

int CountAtNoiseLevel(const BenchmarkResult& r) {
  int n = 0;
  for (const BenchmarkCase& c : r.cases) n += AtNoiseLevel(c) ? 1 : 0;
  return n;
}

std::string Pct(const Tally& t) {
  if (t.n == 0) return "-";
  std::ostringstream o;
  o << std::fixed << std::setprecision(1) << 100 * t.Rate() << " % (" << t.right << "/"
    << t.n << ")";
  return o.str();
}

}  // namespace

void WriteBenchmarkOutputs(const BenchmarkResult& r, bool plots, OutputDir* out,
                           std::vector<std::string>* warnings) {
  const Scores s = Score(r);
  nlohmann::json j;
  j["command"] = "benchmark";
  j["suite"] = r.options.suite;
  j["cases"] = r.options.cases;
  j["seed"] = r.options.seed;
  j["sizes"] = r.options.sizes;
  j["engine"] = r.options.engine;
  j["evidence"] = r.options.evidence;
  if (r.options.form_error >= 0) j["form_error"] = r.options.form_error;
  j["rotary_inertia"] = r.options.rotary_inertia;
  j["noise_free"] = r.options.noise_free;
  j["failed"] = s.failed;
  j["top1"] = s.overall.Json();
  j["top1_single_effect"] = s.single_effect.Json();
  j["top1_two_effects"] = s.two_effects.Json();
  j["both_effects_in_top_two"] = s.both_named.Json();
  j["none_right"] = s.none_cases.Json();
  j["false_alarm_rate_on_none"] = s.none_cases.n
                                      ? json_util::Number(1 - s.none_cases.Rate())
                                      : nlohmann::json(nullptr);
  j["top1_with_shapes"] = s.with_shapes.Json();
  j["top1_without_shapes"] = s.without_shapes.Json();
  j["located_within_tenth"] = s.located.Json();
  j["verdicts_at_90_percent"] = s.confident.Json();
  for (const auto& [k, t] : s.per_kind) j["top1_per_kind"][k] = t.Json();
  for (const auto& [k, t] : s.per_noise) j["top1_per_noise"][k] = t.Json();
  for (const auto& [k, t] : s.per_size) j["top1_per_size"][k] = t.Json();
  for (const auto& [k, t] : s.calibration) j["calibration"][k] = t.Json();
  j["confusion"] = s.confusion;
  j["median_gap_before"] = json_util::Number(s.median_gap_before);
  j["median_gap_after"] = json_util::Number(s.median_gap_after);
  j["median_held_out_gap_before"] = json_util::Number(s.median_held_before);
  j["median_held_out_gap_after"] = json_util::Number(s.median_held_after);
  j["diagnosis_seconds_total"] = s.seconds;
  if (r.options.oracle != "off") {
    nlohmann::json o;
    o["scope"] = r.options.oracle;
    o["samples_per_subclass"] = r.options.oracle_samples;
    for (const auto& [k, t] : s.oracle) o["top1"][k] = t.Json();
    for (const auto& [k, t] : s.oracle_diagnosis)
      o["diagnosis_top1_same_cases"][k] = t.Json();
    o["failed"] = s.oracle_failed;
    const int low = CountAtNoiseLevel(r);
    if (s.oracle_low_run == low && s.oracle_failed == 0) {
      const int n = static_cast<int>(r.cases.size());
      o["ceiling_top1"] =
          json_util::Number(static_cast<double>(n - s.oracle_low_misses) / n);
      o["ceiling_top1_expected"] =
          json_util::Number((n - low + s.oracle_low_expected) / n);
    }
    o["largest_log_standard_error"] = s.oracle_worst_se;
    o["fewest_effective_draws"] = json_util::Number(s.oracle_fewest_draws);
    o["affine_error"] = s.oracle_affine_error;
    o["seconds_total"] = s.oracle_seconds;
    j["oracle"] = o;
  }
  out->WriteText("scores.json", j.dump(2) + "\n");

  std::ostringstream lines;
  for (const BenchmarkCase& c : r.cases) {
    nlohmann::json cj = {{"case", c.name},
                         {"truth", TruthLabel(c)},
                         {"top", c.top},
                         {"probability", c.probability},
                         {"correct", Correct(c)},
                         {"separated", c.separated},
                         {"indistinguishable", c.indistinguishable},
                         {"location_error", c.location_error},
                         {"modes", c.modes},
                         {"sensors", c.shapes ? c.sensors : 0},
                         {"frequency_noise", c.frequency_noise},
                         {"shape_noise", c.shape_noise},
                         {"gap_before", c.gap_before},
                         {"gap_after", c.gap_after},
                         {"held_out_before", c.held_out_before},
                         {"held_out_after", c.held_out_after},
                         {"seconds", c.seconds}};
    nlohmann::json shifts = nlohmann::json::array();
    for (const auto& e : c.effects) shifts.push_back(e.shift_in_noise);
    cj["shift_in_noise"] = shifts;
    cj["temperature"] = c.temperature;
    cj["degrees_of_freedom"] = c.degrees_of_freedom;
    nlohmann::json classes = nlohmann::json::array();
    for (const BenchmarkClassOutcome& k : c.classes) {
      classes.push_back({{"label", k.label},
                         {"parameters", k.parameters},
                         {"chi2", json_util::Number(k.chi2)},
                         {"held_out_chi2", json_util::Number(k.held_out_chi2)},
                         {"score", json_util::Number(k.score)},
                         {"probability", k.probability}});
    }
    cj["classes"] = classes;
    if (c.failed) cj["error"] = c.error;
    if (c.oracle.run) {
      nlohmann::json oj = {
          {"top", c.oracle.top},
          {"probability", c.oracle.probability},
          {"truth_probability", c.oracle.truth_probability},
          {"correct", c.oracle.error.empty() && c.oracle.top == TruthLabel(c)},
          {"log_standard_error", c.oracle.log_standard_error},
          {"effective_samples", json_util::Number(c.oracle.effective_samples)},
          {"evaluations", c.oracle.evaluations},
          {"seconds", c.oracle.seconds}};
      for (const auto& [label, prob] : c.oracle.probabilities)
        oj["probabilities"][label] = prob;
      if (!c.oracle.error.empty()) oj["error"] = c.oracle.error;
      cj["oracle"] = oj;
    }
    lines << cj.dump() << "\n";
  }
  out->WriteText("results.jsonl", lines.str());
  out->WriteText("scores.md", BenchmarkReport(r));
  if (!plots) return;
  {
    Plot p;
    p.title = "Top-1 accuracy by true kind (" + r.options.suite + " suite)";
    p.y_label = "fraction right";
    PlotSeries bars{"top-1", PlotSeries::Style::kBars, {}, {}, {}, {}};
    int x = 0;
    for (const auto& [k, t] : s.per_kind) {
      bars.x.push_back(++x);
      bars.y.push_back(t.Rate());
      p.x_tick_labels.push_back(k);
    }
    p.series = {bars};
    Figure f;
    f.panels = {p};
    f.width_px = 1100;
    RenderStaged(f, "accuracy", out, warnings);
  }
  {
    Plot p;
    p.title = "Calibration: stated probability of the verdict vs fraction right";
    p.x_label = "stated probability";
    p.y_label = "fraction right";
    const double edges[] = {0.0, 0.5, 0.7, 0.9, 0.99, 1.0001};
    PlotSeries obs{"observed", PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    for (int b = 0; b < 5; ++b) {
      double sp = 0;
      Tally t;
      for (const auto& c : r.cases) {
        if (c.failed || c.probability < edges[b] || c.probability >= edges[b + 1])
          continue;
        sp += c.probability;
        t.Add(Correct(c));
      }
      if (t.n == 0) continue;
      obs.x.push_back(sp / t.n);
      obs.y.push_back(t.Rate());
    }
    PlotSeries ideal{"ideal", PlotSeries::Style::kLines, {0, 1}, {0, 1}, {}, {}};
    p.series = {obs, ideal};
    Figure f;
    f.panels = {p};
    RenderStaged(f, "calibration", out, warnings);
  }
}

std::string BenchmarkReport(const BenchmarkResult& r) {
  const Scores s = Score(r);
  std::ostringstream o;
  o << "# femup benchmark: " << r.options.suite << " suite, " << r.options.cases
    << " cases, seed " << r.options.seed << ", effect sizes "
    << (r.options.sizes == "absolute"
            ? "absolute (largest frequency shift " + Num(100 * Ranges::kAbsoluteMin) +
                  "-" + Num(100 * Ranges::kAbsoluteMax) + " %)"
            : std::string("in noise units (1-50 sigma)"))
    << ", engine " << r.options.engine << ", " << r.options.evidence << " evidence"
    << (r.options.form_error >= 0 ? ", form error " + Num(r.options.form_error)
                                  : std::string())
    << (r.options.rotary_inertia
            ? std::string()
            : std::string(", attached masses without rotary inertia"))
    << (r.options.noise_free ? ", noise-free data (the noise stated, not added)"
                             : std::string())
    << "\n\n";
  o << "| score | value |\n|---|---|\n";
  o << "| top-1 kind, all cases | " << Pct(s.overall) << " |\n";
  o << "| top-1, one effect | " << Pct(s.single_effect) << " |\n";
  o << "| top-1, two effects (both named by the top class) | " << Pct(s.two_effects)
    << " |\n";
  o << "| two effects: both among the top two classes | " << Pct(s.both_named) << " |\n";
  o << "| no effect: said 'no significant gap' | " << Pct(s.none_cases) << " |\n";
  o << "| top-1 with shapes | " << Pct(s.with_shapes) << " |\n";
  o << "| top-1 frequencies only | " << Pct(s.without_shapes) << " |\n";
  o << "| located within L/10 (right kind) | " << Pct(s.located) << " |\n";
  o << "| verdicts stated at >= 90 %: right | " << Pct(s.confident) << " |\n";
  o << "| failed cases | " << s.failed << " |\n";
  o << "| median rms frequency gap, fitted modes: before / after | "
    << 100 * s.median_gap_before << " % / " << 100 * s.median_gap_after << " % |\n";
  o << "| median rms frequency gap, held-out modes: before / after | "
    << 100 * s.median_held_before << " % / " << 100 * s.median_held_after << " % |\n";
  o << "| diagnosis time, all cases (CPU-seconds summed over threads) | " << s.seconds
    << " s |\n";
  o << "\n## Top-1 per true kind\n\n| kind | top-1 |\n|---|---|\n";
  for (const auto& [k, t] : s.per_kind) o << "| " << k << " | " << Pct(t) << " |\n";
  o << "\n## Top-1 per noise (frequency / shape)\n\n| noise | top-1 |\n|---|---|\n";
  for (const auto& [k, t] : s.per_noise) o << "| " << k << " | " << Pct(t) << " |\n";
  o << "\n## Top-1 per effect size (weakest effect's frequency shift)\n\n| size | top-1 "
       "|\n|---|---|\n";
  for (const auto& [k, t] : s.per_size) o << "| " << k << " | " << Pct(t) << " |\n";
  o << "\n## Calibration (stated probability of the verdict)\n\n| stated | right "
       "|\n|---|---|\n";
  for (const auto& [k, t] : s.calibration) o << "| " << k << " | " << Pct(t) << " |\n";
  if (r.options.oracle != "off") {
    o << "\n## Bayes oracle (the generator's own prior, forms and noise; "
         "benchmark_oracle.h)\n\n";
    o << "Cases: "
      << (r.options.oracle == "all"
              ? std::string("all")
              : std::string("no effect, or every effect below 5 sigma"))
      << "; " << r.options.oracle_samples << " draws per sub-class; " << s.oracle_failed
      << " failed.\n\n";
    o << "| cases | oracle top-1 | diagnosis top-1, same cases |\n|---|---|---|\n";
    for (const auto& [k, t] : s.oracle) {
      const auto it = s.oracle_diagnosis.find(k);
      o << "| " << k << " | " << Pct(t) << " | "
        << (it == s.oracle_diagnosis.end() ? "-" : Pct(it->second)) << " |\n";
    }
    const int low = CountAtNoiseLevel(r);
    const int n = static_cast<int>(r.cases.size());
    if (s.oracle_low_run == low && s.oracle_failed == 0 && n > 0) {
      o << "\nCeiling on top-1 for any method, counting every effect above 5 sigma as "
           "right: "
        << Pct(Tally{n, n - s.oracle_low_misses})
        << "; with the oracle's own probabilities "
        << "on the " << low << " cases at the noise level: " << std::fixed
        << std::setprecision(1) << 100.0 * (n - low + s.oracle_low_expected) / n
        << std::defaultfloat << " %.\n";
    }
    o << "\nSampling: largest standard error of a log evidence (classes with P >= "
         "0.01) "
      << Num(s.oracle_worst_se) << "; fewest effective draws (the same classes) "
      << Num(s.oracle_fewest_draws) << "; affine strength model against direct "
      << "assembly: " << Num(s.oracle_affine_error) << " (largest relative eigenvalue "
      << "difference); " << Num(s.oracle_seconds) << " CPU-seconds.\n";
  }
  std::set<std::string> predicted;
  for (const auto& [t, row] : s.confusion)
    for (const auto& [p, n] : row) predicted.insert(p);
  o << "\n## Confusion (rows: truth, columns: top class; pair = two effects)\n\n| truth "
       "|";
  for (const auto& p : predicted) o << " " << p << " |";
  o << "\n|---|";
  for (std::size_t i = 0; i < predicted.size(); ++i) o << "---|";
  o << "\n";
  for (const auto& [t, row] : s.confusion) {
    o << "| " << t << " |";
    for (const auto& p : predicted) {
      const auto it = row.find(p);
      o << " " << (it == row.end() ? 0 : it->second) << " |";
    }
    o << "\n";
  }
  return o.str();
}

}  // namespace femup
