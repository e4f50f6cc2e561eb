#include "femup/studies/blind_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <set>
#include <sstream>

#include "benchmark_generator.h"
#include "femup/errors.h"
#include "femup/parallel.h"
#include "femup/plot.h"
#include "femup/problems/effect_fit.h"
#include "femup/studies/benchmark_oracle.h"
#include "femup/studies/diagnose_study.h"
#include "femup/studies/study.h"
#include "json_util.h"
#include "render_staged.h"

namespace femup {

namespace fs = std::filesystem;
using benchmark_generator::Ranges;
using benchmark_generator::TrueEffect;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();

struct Material {
  const char* name;
  double e, rho;
};
constexpr Material kMaterials[] = {{"steel", 210e9, 7850}, {"aluminium", 70e9, 2700}};

// Truth bending modes at the sensors: frequencies and shapes (largest entry 1).
bool TruthModes(const CantileverSpec& spec, const std::vector<std::string>& sensors,
                int count, Eigen::VectorXd* f, Eigen::MatrixXd* shapes) {
  std::string why;
  return BendingModesAtSensors(spec, sensors, count, f, shapes, &why);
}

std::string Num(double v) {
  std::ostringstream o;
  o << std::setprecision(10) << v;
  return o.str();
}

struct Generated {
  BenchmarkCase truth;
  std::string yaml;
  nlohmann::json truth_json;
};

Generated GenerateCase(const BenchmarkOptions& opt, int index) {
  std::mt19937_64 rng(opt.seed * 1000003ULL +
                      static_cast<unsigned long long>(index) * 7919ULL +
                      (opt.suite == "single" ? 17 : 0));
  std::uniform_real_distribution<double> u(0, 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  };
  std::normal_distribution<double> normal(0, 1);
  const bool single = opt.suite == "single";

  Generated g;
  BenchmarkCase& c = g.truth;
  std::ostringstream name;
  name << opt.suite << "_" << std::setw(3) << std::setfill('0') << index + 1;
  c.name = name.str();

  // Beam.
  const Material mat = kMaterials[u(rng) < 0.5 ? 0 : 1];
  c.length = uniform(1.0, 4.0);
  const double width = uniform(0.02, 0.1), thickness = uniform(0.005, 0.03);
  CantileverSpec nominal;
  nominal.section = {mat.e, width * thickness,
                     width * thickness * thickness * thickness / 12, mat.rho};
  nominal.node_heights = UniformHeights(c.length, opt.diagnosis_elements);
  CantileverSpec fine = nominal;
  fine.node_heights = UniformHeights(c.length, opt.diagnosis_elements * opt.refinement);

  // Data layout and noise.
  c.modes = single ? 4 : 2 + static_cast<int>(u(rng) * 3);
  c.sensors = single ? 10 : (u(rng) < 0.5 ? 5 : 10);
  c.shapes = single ? true : u(rng) >= 1.0 / 3;
  const double fn[] = {0.001, 0.003, 0.01};
  const double sn[] = {0.01, 0.02, 0.05};
  c.frequency_noise = single ? 0.001 : fn[static_cast<int>(u(rng) * 3) % 3];
  c.shape_noise = single ? 0.01 : sn[static_cast<int>(u(rng) * 3) % 3];
  std::vector<int> nodes;  // diagnosis node numbers
  if (c.sensors == 10 && u(rng) < 0.5) {
    for (int k = 1; k <= 10; ++k) nodes.push_back(k * opt.diagnosis_elements / 10);
  } else {
    std::vector<int> all;
    for (int k = 1; k <= opt.diagnosis_elements; ++k) all.push_back(k);
    std::shuffle(all.begin(), all.end(), rng);
    nodes.assign(all.begin(), all.begin() + c.sensors);
    std::sort(nodes.begin(), nodes.end());
  }
  std::vector<std::string> coarse_labels, fine_labels;
  for (int k : nodes) {
    coarse_labels.push_back("n" + std::to_string(k) + ":ux");
    fine_labels.push_back("n" + std::to_string(k * opt.refinement) + ":ux");
  }

  // Effects.
  const std::vector<std::string>& kinds = benchmark_generator::Kinds();
  int count = 1;
  const double draw = u(rng);
  if (single) {
    count = draw < Ranges::kSingleNoneShare ? 0 : 1;
  } else {
    count = draw < 0.15 ? 0 : (draw < 0.75 ? 1 : 2);
  }
  std::vector<std::string> chosen = kinds;
  std::shuffle(chosen.begin(), chosen.end(), rng);
  chosen.resize(count);
  std::vector<TrueEffect> effects;
  for (const std::string& kind : chosen) {
    TrueEffect e;
    e.kind = kind;
    BenchmarkEffect be;
    be.kind = kind;
    be.depth = be.x = be.x0 = be.x1 = kNan;
    std::ostringstream d;
    if (kind == "added_mass") {
      e.a = uniform(Ranges::kDepthMin, Ranges::kDepthMax) * c.length;
      e.b = u(rng) < Ranges::kFadeShare
                ? uniform(Ranges::kFadeMin, Ranges::kFadeMax) * e.a
                : 0.0;
      be.depth = e.a;
      be.x0 = 0;
      be.x1 = e.a;
      d << "transverse mass from the base to " << Num(e.a) << " m, fading over the top "
        << Num(e.b) << " m";
    } else if (kind == "support_flexibility") {
      // 0: rotation and translation, 1: rotation
      e.variant = u(rng) < Ranges::kBothShare ? 0 : 1;
      e.a = uniform(Ranges::kRatioMin, Ranges::kRatioMax);
      be.x = 0;
      d << (e.variant == 0 ? "rotational and translational" : "rotational")
        << " springs at the base";
    } else if (kind == "attached_mass") {
      // Between diagnosis nodes, with rotary inertia.
      const double h = c.length / opt.diagnosis_elements;
      const int k =
          Ranges::kFirstElement +
          static_cast<int>(u(rng) * (opt.diagnosis_elements - Ranges::kFirstElement));
      e.a = std::min(c.length,
                     (k + uniform(Ranges::kInElementMin, Ranges::kInElementMax)) * h);
      if (e.a > c.length) e.a = c.length - 0.3 * h;
      e.b = uniform(Ranges::kGyrationMin, Ranges::kGyrationMax);
      be.x = e.a;
      d << "point mass at " << Num(e.a) << " m with radius of gyration " << Num(e.b)
        << " m";
    } else if (kind == "stiffness_loss") {
      e.b = uniform(Ranges::kWidthMin, Ranges::kWidthMax) * c.length;    // width
      e.a = uniform(Ranges::kCentreMin, Ranges::kCentreMax) * c.length;  // centre
      be.x = e.a;
      be.x0 = std::max(0.0, e.a - 0.5 * e.b);
      be.x1 = std::min(c.length, e.a + 0.5 * e.b);
      d << "EI reduced over " << Num(be.x0) << "-" << Num(be.x1) << " m";
    } else {
      e.a = u(rng) < Ranges::kLowerShare ? -1.0 : 1.0;
      d << "Young's modulus " << (e.a > 0 ? "higher" : "lower") << " than modelled";
    }
    // Size: the largest frequency shift on the measured modes, in units of the
    // case's frequency noise or in absolute terms (`sizes`).
    const double target = opt.sizes == "absolute"
                              ? log_uniform(Ranges::kAbsoluteMin, Ranges::kAbsoluteMax)
                              : (u(rng) < Ranges::kStrongShare
                                     ? log_uniform(Ranges::kStrongMin, Ranges::kStrongMax)
                                     : log_uniform(Ranges::kWeakMin, Ranges::kWeakMax)) *
                                    c.frequency_noise;
    const Eigen::VectorXd f0 = benchmark_generator::BendingFrequencies(fine, c.modes);
    e.strength = benchmark_generator::CalibrateStrength(e, fine, f0, target);
    be.shift_in_noise =
        benchmark_generator::FrequencyShift(e, fine, f0, e.strength) / c.frequency_noise;
    if (kind == "added_mass") {
      d << "; " << Num(3 * e.strength * nominal.section.rho * nominal.section.A)
        << " kg/m";
    } else if (kind == "support_flexibility") {
      d << "; EI/(k_r L) = " << Num(5 * e.strength);
    } else if (kind == "attached_mass") {
      d << "; " << Num(e.strength * nominal.section.rho * nominal.section.A * c.length)
        << " kg";
    } else if (kind == "stiffness_loss") {
      d << "; " << Num(90 * e.strength) << " % of EI lost";
    } else {
      d << "; by " << Num(50 * e.strength) << " %";
    }
    be.description = d.str();
    effects.push_back(e);
    c.effects.push_back(be);
  }

  // The "measured" modes of the truth, with noise.
  CantileverSpec truth = fine;
  for (const TrueEffect& e : effects) e.Apply(e.strength, &truth);
  Eigen::VectorXd f;
  Eigen::MatrixXd shapes;
  if (!TruthModes(truth, fine_labels, c.modes, &f, &shapes))
    throw InputError(c.name, "the generated truth model cannot be solved");
  const double applied = opt.noise_free ? 0.0 : 1.0;
  for (int k = 0; k < c.modes; ++k) {
    f[k] *= 1 + applied * c.frequency_noise * normal(rng);
    for (Eigen::Index i = 0; i < shapes.rows(); ++i)
      shapes(i, k) += applied * c.shape_noise * normal(rng);
  }

  // Study file.
  std::ostringstream y;
  y << "# Blind benchmark case " << c.name << " (femup benchmark, seed " << opt.seed
    << "). The truth is not in this file.\n";
  y << "name: " << c.name << "\n";
  y << "model:\n  type: cantilever\n  length: " << Num(c.length)
    << "\n  elements: " << opt.diagnosis_elements << "\n  section: {E: " << Num(mat.e)
    << ", A: " << Num(nominal.section.A) << ", I: " << Num(nominal.section.I)
    << ", rho: " << Num(mat.rho) << "}\n";
  y << "measurements:\n  - state: test\n    frequencies_hz: [";
  for (int k = 0; k < c.modes; ++k) y << (k ? ", " : "") << Num(f[k]);
  y << "]\n";
  if (c.shapes) {
    y << "    sensors: [";
    for (std::size_t i = 0; i < coarse_labels.size(); ++i)
      y << (i ? ", " : "") << "\"" << coarse_labels[i] << "\"";
    y << "]\n    shapes:\n";
    for (int k = 0; k < c.modes; ++k) {
      y << "      - [";
      for (Eigen::Index i = 0; i < shapes.rows(); ++i)
        y << (i ? ", " : "") << Num(shapes(i, k));
      y << "]\n";
    }
  }
  y << "diagnosis:\n  noise: {frequency: " << Num(c.frequency_noise)
    << ", shape: " << Num(c.shape_noise)
    << "}\n  localise: false\n  evidence: " << opt.evidence << "\n";
  if (opt.form_error >= 0) y << "  form_error: " << Num(opt.form_error) << "\n";
  g.yaml = y.str();

  nlohmann::json tj;
  tj["case"] = c.name;
  tj["length"] = c.length;
  tj["material"] = mat.name;
  tj["truth_elements"] = opt.diagnosis_elements * opt.refinement;
  tj["effects"] = nlohmann::json::array();
  for (const auto& e : c.effects) {
    tj["effects"].push_back({{"kind", e.kind},
                             {"depth", json_util::Number(e.depth)},
                             {"x", json_util::Number(e.x)},
                             {"x0", json_util::Number(e.x0)},
                             {"x1", json_util::Number(e.x1)},
                             {"shift_in_noise", e.shift_in_noise},
                             {"description", e.description}});
  }
  tj["noise"] = {{"frequency", c.frequency_noise}, {"shape", c.shape_noise}};
  tj["modes"] = c.modes;
  tj["sensors"] = c.shapes ? c.sensors : 0;
  g.truth_json = tj;
  return g;
}

void WriteFile(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".part";
  {
    std::ofstream o(tmp);
    o << text;
    if (!o) throw InputError(path.string(), "cannot write");
  }
  fs::rename(tmp, path);
}

// Distance between a true and a fitted location of the same kind (m); -1 when
// the kind has no location to compare.
double LocationError(const BenchmarkEffect& t, const nlohmann::json& fitted) {
  auto get = [&](const char* k) {
    return fitted.contains(k) && fitted[k].is_number() ? fitted[k].get<double>() : kNan;
  };
  if (t.kind == "added_mass") return std::abs(get("depth") - t.depth);
  if (t.kind == "attached_mass" || t.kind == "stiffness_loss")
    return std::abs(get("x") - t.x);
  return -1;
}

std::set<std::string> KindSet(const std::vector<std::string>& v) {
  return std::set<std::string>(v.begin(), v.end());
}

std::string TruthLabel(const BenchmarkCase& c) {
  if (c.effects.empty()) return "none";
  std::vector<std::string> k;
  for (const auto& e : c.effects) k.push_back(e.kind);
  std::sort(k.begin(), k.end());
  std::string s;
  for (const auto& x : k) s += (s.empty() ? "" : "+") + x;
  return s;
}

bool Correct(const BenchmarkCase& c) {
  std::set<std::string> truth;
  for (const auto& e : c.effects) truth.insert(e.kind);
  return !c.failed && KindSet(c.top_kinds) == truth;
}

// No effect, or every effect's largest frequency shift below the generator's
// lower bound for effects above the noise level (5 noise units): the cases
// the oracle's ceiling needs (RunBenchmark, oracle "weak").
bool AtNoiseLevel(const BenchmarkCase& c) {
  for (const auto& e : c.effects)
    if (e.shift_in_noise >= Ranges::kStrongMin) return false;
  return true;
}

}  // namespace

std::string BenchmarkOptions::Validate() const {
  if (suite != "single" && suite != "mixed") return "suite: expected single or mixed";
  if (cases < 1) return "cases: expected at least 1";
  if (threads < 1) return "threads: expected at least 1";
  if (diagnosis_elements < 10) return "diagnosis_elements: expected at least 10";
  if (refinement < 1) return "refinement: expected at least 1";
  if (sizes != "noise" && sizes != "absolute")
    return "sizes: expected noise or absolute, not '" + sizes + "'";
  if (evidence != "sampled" && evidence != "laplace")
    return "evidence: expected sampled or laplace, not '" + evidence + "'";
  if (!(form_error < 1))  // NaN too
    return "form_error: expected a fraction below 1 (or negative for diagnose's default)";
  if (oracle != "off" && oracle != "weak" && oracle != "all")
    return "oracle: expected off, weak or all, not '" + oracle + "'";
  if (oracle != "off" && suite != "single")
    return "oracle: the Bayes oracle models the single suite only, not '" + suite + "'";
  if (oracle_samples < 50) return "oracle_samples: expected at least 50";
  return "";
}

std::vector<BenchmarkCase> GenerateBenchmark(const BenchmarkOptions& options,
                                             const std::string& out_dir) {
  const std::string invalid = options.Validate();
  if (!invalid.empty())
    throw InputError("benchmark." + invalid.substr(0, invalid.find(':')),
                     invalid.substr(invalid.find(':') + 2));
  const fs::path cases_dir = fs::path(out_dir) / "cases";
  const fs::path truth_dir = fs::path(out_dir) / "truth";
  std::error_code ec;
  fs::create_directories(cases_dir, ec);
  fs::create_directories(truth_dir, ec);
  if (ec) throw InputError(out_dir, "cannot create the case folders: " + ec.message());
  std::vector<BenchmarkCase> out;
  for (int i = 0; i < options.cases; ++i) {
    const Generated g = GenerateCase(options, i);
    WriteFile(cases_dir / (g.truth.name + ".yaml"), g.yaml);
    WriteFile(truth_dir / (g.truth.name + ".json"), g.truth_json.dump(2) + "\n");
    out.push_back(g.truth);
  }
  return out;
}

BenchmarkResult RunBenchmark(const BenchmarkOptions& options, const std::string& out_dir,
                             const ProgressCallback& progress) {
  BenchmarkResult result;
  result.options = options;
  result.cases = GenerateBenchmark(options, out_dir);
  // Each case writes only its own slot; a failing case is recorded, not thrown.
  auto diagnose_case = [&](int i) {
    BenchmarkCase& c = result.cases[i];
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<Study> study;  // read once, for the diagnosis and the oracle
    try {
      study = LoadStudy((fs::path(out_dir) / "cases" / (c.name + ".yaml")).string());
      const DiagnosisResult d = RunDiagnosis(*study);
      const DiagnosisCandidate& top = d.candidates.front();
      c.top = top.label;
      c.top_kinds = top.kinds;
      if (d.candidates.size() > 1) c.second_kinds = d.candidates[1].kinds;
      c.probability = top.probability;
      c.separated = d.separated;
      c.indistinguishable = d.indistinguishable;
      c.temperature = d.temperature;
      c.degrees_of_freedom = d.degrees_of_freedom;
      for (const DiagnosisCandidate& k : d.candidates) {
        c.classes.push_back({k.label, static_cast<int>(k.theta.size()), k.chi2,
                             k.held_out_chi2, k.score, k.probability});
      }
      // Location error of each true effect the top class names.
      for (const auto& e : c.effects) {
        for (std::size_t k = 0; k < top.kinds.size(); ++k) {
          if (top.kinds[k] != e.kind) continue;
          nlohmann::json loc = nlohmann::json::object();
          const EffectLocation& l = top.locations[k];
          if (std::isfinite(l.depth)) loc["depth"] = l.depth;
          if (std::isfinite(l.x)) loc["x"] = l.x;
          const double err = LocationError(e, loc);
          if (err >= 0) c.location_error = std::max(c.location_error, err);
        }
      }
      auto rms = [](const EffectFitData& data, const std::vector<PredictedState>& p) {
        double ss = 0;
        int n = 0;
        for (std::size_t s = 0; s < data.states.size(); ++s)
          for (std::size_t k = 0; k < data.states[s].modes.size(); ++k) {
            const double e =
                p[s].modes[k].frequency_hz / data.states[s].modes[k].frequency_hz - 1;
            ss += e * e;
            ++n;
          }
        return n ? std::sqrt(ss / n) : -1.0;
      };
      c.gap_before = rms(d.fitted_data, d.nominal_fitted);
      c.gap_after = rms(d.fitted_data, top.fitted);
      if (!d.held_out_data.states.empty()) {
        c.held_out_before = rms(d.held_out_data, d.nominal_held_out);
        c.held_out_after = rms(d.held_out_data, top.held_out);
      }
    } catch (const std::exception& e) {
      c.failed = true;
      c.error = e.what();
    }
    c.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (options.oracle == "off" || (options.oracle == "weak" && !AtNoiseLevel(c))) return;
    BenchmarkOracleOutcome& o = c.oracle;
    o.run = true;
    if (!study) {
      o.error = c.error;  // the study file could not be read
      return;
    }
    try {
      OracleOptions oo;
      oo.samples = options.oracle_samples;
      const OracleResult r = BayesOracle(*study, options, oo);
      o.top = r.classes.front().label;
      o.probability = r.classes.front().probability;
      o.evaluations = r.evaluations;
      o.affine_error = r.affine_error;
      o.seconds = r.seconds;
      o.effective_samples = std::numeric_limits<double>::infinity();
      for (const OracleClass& oc : r.classes) {
        o.probabilities.emplace_back(oc.label, oc.probability);
        if (oc.label == TruthLabel(c)) o.truth_probability = oc.probability;
        if (oc.probability >= 0.01) {
          o.log_standard_error = std::max(o.log_standard_error, oc.log_standard_error);
          if (oc.label != "none")
            o.effective_samples = std::min(o.effective_samples, oc.effective_samples);
        }
      }
    } catch (const std::exception& e) {
      o.error = e.what();
    }
  };
  ParallelFor(static_cast<int>(result.cases.size()), options.threads, diagnose_case,
              progress);
  return result;
}

namespace {

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
  j["evidence"] = r.options.evidence;
  if (r.options.form_error >= 0) j["form_error"] = r.options.form_error;
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
    << ", " << r.options.evidence << " evidence"
    << (r.options.form_error >= 0 ? ", form error " + Num(r.options.form_error)
                                  : std::string())
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
