// The blind benchmark of `femup diagnose` (`femup benchmark`): a generator makes
// "measured" modes of random cantilevers from a model three times finer than
// the diagnosis model, with effects whose true form differs from the fitted
// families (water added mass fading towards the surface, damage of random
// width, springs in rotation and translation, an attached mass with rotary
// inertia between nodes, two effects at once), noise on frequencies and
// shapes, 2-4 modes, 5 or 10 sensors, some cases without shapes. Each case is
// written as a study file; its truth goes to a separate folder that the
// diagnosis never reads. Every case is then diagnosed from its study file and
// scored against the truth.
//
// Suites:
//   "single": one effect (or none) per case, noise 0.1 % on frequencies and 1 %
//             on shapes, 4 modes, 10 sensors.
//   "mixed":  everything mixed: none / one / two effects, noise 0.1-1 % and
//             1-5 %, 2-4 modes, 5 or 10 sensors, a third without shapes.
// Effect sizes are set by the largest relative frequency shift they cause on the
// measured modes (`sizes`):
//   "noise"    (default): in multiples of the case's frequency noise,
//              log-uniform in [5, 50] for four cases in five and [1, 5] (at the
//              noise level) for the rest, whatever the noise;
//   "absolute": a physical size independent of the measurement, log-uniform in
//              [0.5 %, 20 %], so that an effect is at the noise level only
//              where the noise is high (0.5-5 sigma at 1 % frequency noise,
//              5-200 sigma at 0.1 %).
#pragma once

#include <string>
#include <vector>

#include "femup/core/invalid.h"
#include "femup/core/progress.h"
#include "femup/reporting/output_dir.h"

namespace femup {

struct BenchmarkOptions {
  std::string suite = "mixed";  // "single" or "mixed"
  // The diagnosis engine, written into every case's study file:
  // "model_effects" (diagnose's default: the one engine, RankModelEffects;
  // the mixed suite's files also say `max_effects: 2`, since its truths
  // include pairs) or "cantilever" (the cantilever's own pipeline,
  // RunDiagnosis, which tries pairs by default).
  std::string engine = "model_effects";
  int cases = 100;
  unsigned long long seed = 20261121;
  int threads = 2;  // cases diagnosed in parallel
  int diagnosis_elements = 20;
  int refinement = 3;           // truth mesh = refinement x diagnosis mesh
  std::string sizes = "noise";  // "noise" or "absolute" (above)
  // The diagnosis's evidence, written into every case's study file: "laplace"
  // (the default of diagnose) or "sampled".
  std::string evidence = "laplace";
  // The diagnosis's form error (DiagnosisSpec::form_error), written into every
  // case's study file when >= 0; below 0, diagnose's default applies.
  double form_error = -1;
  // The diagnosis's attached masses carry a fitted rotary inertia (the
  // default of diagnose); false writes `rotary_inertia: false` into every
  // case's study file (translational point masses, as before session 40).
  bool rotary_inertia = true;
  // The "measured" modes exactly as the truth model gives them: the noise is
  // drawn (so that every case is the same as without this flag) but not added,
  // and the study files state the same noise. What the diagnosis still misses
  // then is due to the fitted families' form, the data's layout (modes,
  // sensors) and the evidence's priors, not to the noise draws.
  bool noise_free = false;
  // The Bayes oracle (benchmark_oracle.h), single suite only: "off"; "weak"
  // on the cases with no effect or whose effects all shift a frequency by less
  // than 5 noise units (enough for the ceiling on top-1 below, counting every
  // larger effect as right); "all" on every case.
  std::string oracle = "off";
  int oracle_samples = 500;  // importance-sampling draws per sub-class
  Invalid Validate() const;  // ok, or the field and what is wrong
};

// One generated case, as the truth file records it.
struct BenchmarkEffect {
  std::string kind;
  // Where, m from the support (NaN where not applicable).
  double depth = 0, x = 0, x0 = 0, x1 = 0;
  double shift_in_noise = 0;  // largest frequency shift / frequency noise
  std::string description;
};

// One model class of a case's diagnosis, as results.jsonl reports it.
struct BenchmarkClassOutcome {
  std::string label;  // "none", "added_mass", "added_mass+stiffness_loss"
  int parameters = 0;
  double chi2 = 0;           // fitted modes, at the best fit, stated noise
  double held_out_chi2 = 0;  // held-out modes, predicted from the best fit
  double score = 0;          // log evidence + held-out log predictive density
  double probability = 0;
};

// The Bayes oracle's answer for a case (benchmark_oracle.h).
struct BenchmarkOracleOutcome {
  bool run = false;
  std::string top;  // the most probable class
  double probability = 0;
  double truth_probability = 0;  // of the true class
  // Among the classes with probability >= 0.01: the largest standard error of
  // a log evidence, and the fewest effective draws (of the sub-class that
  // carries most of a class's evidence).
  double log_standard_error = 0;
  double effective_samples = 0;
  double affine_error = 0;
  int evaluations = 0;
  double seconds = 0;
  std::vector<std::pair<std::string, double>> probabilities;  // most probable first
  std::string error;                                          // when it failed
};

struct BenchmarkCase {
  std::string name;                      // "mixed_007"
  std::vector<BenchmarkEffect> effects;  // empty = none
  double length = 0;
  int modes = 0, sensors = 0;
  bool shapes = true;
  double frequency_noise = 0, shape_noise = 0;
  // Diagnosis outcome.
  std::string top;  // label of the top class
  std::vector<std::string> top_kinds, second_kinds;
  double probability = 0;
  bool separated = false;
  std::vector<std::string> indistinguishable;
  double location_error = -1;            // m, worst over located true effects; -1: none
  double gap_before = 0, gap_after = 0;  // rms relative frequency error, fitted modes
  double held_out_before = -1, held_out_after = -1;  // -1: nothing held out
  std::vector<BenchmarkClassOutcome> classes;        // every class, most probable first
  double temperature = 1;  // the noise scale the diagnosis applied
  int degrees_of_freedom = 0;
  bool failed = false;
  std::string error;
  double seconds = 0;
  BenchmarkOracleOutcome oracle;
};

struct BenchmarkResult {
  BenchmarkOptions options;
  std::vector<BenchmarkCase> cases;
};

// Generates the cases into <out>/cases/<name>.yaml and <out>/truth/<name>.json.
// Returns the cases (truth only).
std::vector<BenchmarkCase> GenerateBenchmark(const BenchmarkOptions& options,
                                             const std::string& out_dir);

// Diagnoses each generated case from its study file (options.threads in
// parallel) and fills in the outcome. `progress`, when set, is called after each
// case as (cases done, cases), from the worker threads (femup/progress.h).
BenchmarkResult RunBenchmark(const BenchmarkOptions& options, const std::string& out_dir,
                             const ProgressCallback& progress = {});

// scores.json, scores.md, results.jsonl and, when `plots`, accuracy.png and
// calibration.png.
void WriteBenchmarkOutputs(const BenchmarkResult& result, bool plots, OutputDir* out,
                           std::vector<std::string>* warnings);

std::string BenchmarkReport(const BenchmarkResult& result);

}  // namespace femup
