// femup benchmark: the blind benchmark of diagnose (generated cases with the
// truth kept apart, each diagnosed, then scored).
#include <algorithm>
#include <filesystem>

#include "commands.h"
#include "femup/core/errors.h"
#include "femup/evaluation/blind_benchmark.h"

namespace femup::cli {

namespace {

struct BenchmarkCommandOptions {
  femup::BenchmarkOptions benchmark;
  OutputOptions output;
};

void AddOptions(CLI::App* cmd, BenchmarkCommandOptions* o) {
  femup::BenchmarkOptions& b = o->benchmark;
  cmd->add_option("--suite", b.suite, "single or mixed (default mixed)");
  cmd->add_option("--cases", b.cases, "number of cases (default 100)");
  cmd->add_option("--seed", b.seed, "random seed (default 20261121)");
  cmd->add_option("--threads", b.threads, "cases in parallel (default 2)");
  cmd->add_option("--engine", b.engine,
                  "the diagnosis engine: model_effects (diagnose's default, the one "
                  "engine; the mixed suite's cases also try pairs) or cantilever (the "
                  "cantilever's own pipeline)");
  cmd->add_option("--sizes", b.sizes,
                  "effect sizes: noise (largest frequency shift 1-50 x the case's "
                  "frequency noise, the default) or absolute (0.5-20 %)");
  cmd->add_option("--evidence", b.evidence,
                  "each class's evidence in the diagnosis: laplace (the default) or "
                  "sampled (importance sampling; with --engine cantilever)");
  cmd->add_option("--form-error", b.form_error,
                  "the diagnosis's form error, a fraction of the nominal misfit "
                  "(with --engine cantilever; default: diagnose's, 0.05)");
  cmd->add_option("--rotary-inertia", b.rotary_inertia,
                  "the diagnosis's attached masses carry a fitted rotary inertia: true "
                  "(the default) or false (translational point masses)");
  cmd->add_flag("--noise-free", b.noise_free,
                "the same cases without the noise added to their data (the noise "
                "still stated): which misses the noise causes");
  cmd->add_option("--oracle", b.oracle,
                  "single suite: also the Bayes-optimal classification under the "
                  "generator's own prior and forms, the ceiling of top-1: off (the "
                  "default), weak (cases with no effect or effects below 5 sigma: "
                  "enough for the ceiling) or all");
  cmd->add_option("--oracle-samples", b.oracle_samples,
                  "the oracle's importance-sampling draws per sub-class (default 500)");
  AddOutputOptions(cmd, &o->output, "JSON and tables", "out/benchmark");
}

int Run(const Invocation& invocation, BenchmarkCommandOptions* o) {
  const femup::BenchmarkOptions& options = o->benchmark;
  const std::string& out = o->output.out;
  if (const femup::Invalid bad = options.Validate()) {
    std::string flag = bad.field;
    std::replace(flag.begin(), flag.end(), '_', '-');  // form_error: --form-error
    throw femup::InputError("--" + flag, bad.message);
  }
  std::filesystem::create_directories(out);
  femup::BenchmarkResult result;
  {
    const auto bar = MakeProgressBar("diagnosing cases", o->output.quiet);
    result = femup::RunBenchmark(options, out, bar->Callback());
  }
  Publish(invocation,
          RunInfo{"benchmark",
                  options.suite + " suite, " + std::to_string(options.cases) + " cases",
                  {}},
          out, !o->output.no_plots, o->output.quiet, result, femup::WriteBenchmarkOutputs,
          femup::BenchmarkReport);
  return 0;
}

}  // namespace

Command BenchmarkCommand() {
  auto o = std::make_shared<BenchmarkCommandOptions>();
  return {"benchmark",
          "the blind benchmark of diagnose: generate cases (study files; truth kept "
          "apart), diagnose each, score",
          [o](CLI::App* cmd) { AddOptions(cmd, o.get()); },
          [o](const Invocation& invocation) { return Run(invocation, o.get()); }};
}

}  // namespace femup::cli
