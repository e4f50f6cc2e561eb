// The blind benchmark (blind_benchmark.h): its options, the generation of each
// case (a random cantilever, effects and noisy modes as a study file, and the
// truth apart) and the diagnosis of every case; blind_benchmark_scores.cc
// scores them and writes the outputs and the report.
#include "femup/evaluation/blind_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>

#include "benchmark_generator.h"
#include "blind_benchmark_common.h"
#include "femup/core/errors.h"
#include "femup/core/parallel.h"
#include "femup/evaluation/benchmark_oracle.h"
#include "femup/problems/effect_fit.h"
#include "femup/studies/diagnose_study.h"
#include "femup/studies/effect_ranking.h"
#include "femup/studies/structure_diagnosis.h"
#include "femup/studies/study.h"
#include "json_util.h"

namespace femup {

namespace fs = std::filesystem;
using benchmark_generator::Ranges;
using benchmark_generator::TrueEffect;
using blind_benchmark::AtNoiseLevel;
using blind_benchmark::kNan;
using blind_benchmark::Num;
using blind_benchmark::TruthLabel;

namespace blind_benchmark {

std::string Num(double v) {
  std::ostringstream o;
  o << std::setprecision(10) << v;
  return o.str();
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

// No effect, or every effect's largest frequency shift below the generator's
// lower bound for effects above the noise level (5 noise units): the cases
// the oracle's ceiling needs (RunBenchmark, oracle "weak").
bool AtNoiseLevel(const BenchmarkCase& c) {
  for (const auto& e : c.effects)
    if (e.shift_in_noise >= Ranges::kStrongMin) return false;
  return true;
}

}  // namespace blind_benchmark

namespace {

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
  if (!opt.rotary_inertia) y << "  rotary_inertia: false\n";
  if (opt.engine == "cantilever")
    y << "  engine: cantilever\n";
  else if (opt.suite == "mixed")
    y << "  max_effects: 2\n";  // the suite's truths include pairs
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

}  // namespace

Invalid BenchmarkOptions::Validate() const {
  if (suite != "single" && suite != "mixed") return {"suite", "expected single or mixed"};
  if (cases < 1) return {"cases", "expected at least 1"};
  if (threads < 1) return {"threads", "expected at least 1"};
  if (diagnosis_elements < 10) return {"diagnosis_elements", "expected at least 10"};
  if (refinement < 1) return {"refinement", "expected at least 1"};
  if (engine != "model_effects" && engine != "cantilever")
    return {"engine", "expected model_effects or cantilever, not '" + engine + "'"};
  if (sizes != "noise" && sizes != "absolute")
    return {"sizes", "expected noise or absolute, not '" + sizes + "'"};
  if (evidence != "sampled" && evidence != "laplace")
    return {"evidence", "expected sampled or laplace, not '" + evidence + "'"};
  if (!(form_error < 1))  // NaN too
    return {"form_error",
            "expected a fraction below 1 (or negative for diagnose's default)"};
  if (engine == "model_effects" && evidence != "laplace")
    return {"evidence",
            "the one engine (engine model_effects) has Laplace's evidence only; sampled "
            "evidence needs engine cantilever"};
  if (engine == "model_effects" && form_error >= 0)
    return {"form_error",
            "the one engine (engine model_effects) allows for the model's form error "
            "from its variants, not from a stated fraction; a stated form error needs "
            "engine cantilever"};
  if (oracle != "off" && oracle != "weak" && oracle != "all")
    return {"oracle", "expected off, weak or all, not '" + oracle + "'"};
  if (oracle != "off" && suite != "single")
    return {"oracle",
            "the Bayes oracle models the single suite only, not '" + suite + "'"};
  if (oracle_samples < 50) return {"oracle_samples", "expected at least 50"};
  return {};
}

std::vector<BenchmarkCase> GenerateBenchmark(const BenchmarkOptions& options,
                                             const std::string& out_dir) {
  ThrowIfInvalid(options.Validate(), "benchmark");
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

// The outcome of a case diagnosed by the cantilever's own pipeline.
void FillFromOwnPipeline(const DiagnosisResult& d, BenchmarkCase* c) {
  const DiagnosisCandidate& top = d.candidates.front();
  c->top = top.label;
  c->top_kinds = top.kinds;
  if (d.candidates.size() > 1) c->second_kinds = d.candidates[1].kinds;
  c->probability = top.probability;
  c->separated = d.separated;
  c->indistinguishable = d.indistinguishable;
  c->temperature = d.temperature;
  c->degrees_of_freedom = d.degrees_of_freedom;
  for (const DiagnosisCandidate& k : d.candidates) {
    c->classes.push_back({k.label, static_cast<int>(k.theta.size()), k.chi2,
                          k.held_out_chi2, k.score, k.probability});
  }
  // Location error of each true effect the top class names.
  for (const auto& e : c->effects) {
    for (std::size_t k = 0; k < top.kinds.size(); ++k) {
      if (top.kinds[k] != e.kind) continue;
      nlohmann::json loc = nlohmann::json::object();
      const EffectLocation& l = top.locations[k];
      if (std::isfinite(l.depth)) loc["depth"] = l.depth;
      if (std::isfinite(l.x)) loc["x"] = l.x;
      const double err = LocationError(e, loc);
      if (err >= 0) c->location_error = std::max(c->location_error, err);
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
  c->gap_before = rms(d.fitted_data, d.nominal_fitted);
  c->gap_after = rms(d.fitted_data, top.fitted);
  if (!d.held_out_data.states.empty()) {
    c->held_out_before = rms(d.held_out_data, d.nominal_held_out);
    c->held_out_after = rms(d.held_out_data, top.held_out);
  }
}

// The outcome of a case diagnosed by the one engine (RankModelEffects). Its
// classes are places of a family; the benchmark scores families (kinds), so a
// case's classes are here its kinds, each with its most probable place's fit
// and the kind's probability, as the own pipeline's candidates are.
void FillFromOneEngine(const StructureDiagnosisResult& d, BenchmarkCase* c) {
  const EffectRanking& k = d.ranking;
  const RankedClass& top = k.classes.front();
  auto kinds_of = [](const std::string& kind) {
    return kind == "none" ? std::vector<std::string>{} : FamiliesOf(kind);
  };
  c->top = top.kind;
  c->top_kinds = kinds_of(top.kind);
  for (const auto& [kind, p] : k.kind_probabilities) {
    if (kind == top.kind) continue;
    c->second_kinds = kinds_of(kind);
    break;
  }
  c->probability = KindProbability(k, top.kind);
  c->separated = c->probability >= d.confidence;
  c->indistinguishable = top.equivalent;
  c->temperature = k.temperature;
  c->degrees_of_freedom = k.num_residuals;
  // The verdict's kind first (where the effect explains too little of the
  // gap, "none" is the verdict whatever its share), then the others, most
  // probable first.
  std::vector<std::pair<std::string, double>> kinds = k.kind_probabilities;
  std::stable_partition(kinds.begin(), kinds.end(),
                        [&top](const auto& e) { return e.first == top.kind; });
  for (const auto& [kind, p] : kinds) {
    const auto best = std::find_if(k.classes.begin(), k.classes.end(),
                                   [&](const RankedClass& r) { return r.kind == kind; });
    if (best == k.classes.end()) continue;
    c->classes.push_back({kind, static_cast<int>(best->theta.size()), best->chi2, 0,
                          best->evidence.log_evidence + best->log_prior, p});
  }
  // Location error of the true effect where the top class names its kind
  // alone (a pair's place is not one location).
  if (c->top_kinds.size() == 1) {
    for (const auto& e : c->effects) {
      if (e.kind != c->top_kinds[0]) continue;
      nlohmann::json loc = nlohmann::json::object();
      if (std::isfinite(top.location.depth)) loc["depth"] = top.location.depth;
      if (std::isfinite(top.location.x)) loc["x"] = top.location.x;
      const double err = LocationError(e, loc);
      if (err >= 0) c->location_error = std::max(c->location_error, err);
    }
  }
  // -1: no modes (the own pipeline's convention).
  auto rms = [](const RankedClass& r) {
    const double e = RmsFrequencyError(r);
    return std::isnan(e) ? -1.0 : e;
  };
  const auto none = std::find_if(k.classes.begin(), k.classes.end(),
                                 [](const RankedClass& r) { return r.kind == "none"; });
  if (none != k.classes.end()) c->gap_before = rms(*none);
  c->gap_after = rms(top);
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
      if (study->diagnosis && study->diagnosis->Engine() == "cantilever")
        FillFromOwnPipeline(RunDiagnosis(*study), &c);
      else
        FillFromOneEngine(RunStructureDiagnosis(*study), &c);
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

}  // namespace femup
