// femup: the command line. Each subcommand reads a study file, runs one
// pipeline from studies/, and writes its JSON, matrices and plots into an
// output folder all at once (nothing is left behind when a run fails).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include "femup/errors.h"
#include "femup/output_dir.h"
#include "femup/progress.h"
#include "femup/run_report.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/studies/blind_benchmark.h"
#include "femup/studies/compare_study.h"
#include "femup/studies/diagnose_study.h"
#include "femup/studies/file_info.h"
#include "femup/studies/identify_study.h"
#include "femup/studies/modes_study.h"
#include "femup/studies/noise_study.h"
#include "femup/studies/simulate_study.h"
#include "femup/studies/solve_study.h"
#include "femup/studies/structure_diagnosis.h"
#include "femup/studies/study.h"
#include "femup/studies/update_study.h"

namespace {

struct Common {
  std::string study;
  std::string out;
  bool no_plots = false;
  bool quiet = false;
  std::string solver;  // overrides the study file's solver.name
  std::string method;  // overrides solver.method
};

void AddCommon(CLI::App* cmd, Common* c) {
  cmd->add_option("study", c->study, "study file (YAML or JSON)")->required();
  cmd->add_option("-o,--out", c->out, "output folder (default: out/<study name>)");
  cmd->add_flag("--no-plots", c->no_plots, "write JSON and matrices only");
  cmd->add_flag("-q,--quiet", c->quiet, "print nothing but errors and warnings");
}

void AddSolverOverride(CLI::App* cmd, Common* c) {
  cmd->add_option(
      "--solver", c->solver,
      "solver name, overriding the study file (linear: lstsq, tsvd, tikhonov, "
      "bvls, ceres, ipopt; sensitivity: ceres, ipopt)");
  cmd->add_option(
      "--method", c->method,
      "linear (the paper's Z d = F) or sensitivity (iterative eigen-sensitivity)");
}

// Applies --solver / --method and checks the result before any work.
void ApplyOverride(const Common& c, femup::Study* study) {
  if (!c.method.empty()) {
    if (c.method != "linear" && c.method != "sensitivity")
      throw femup::InputError("--method",
                              "expected linear or sensitivity, got '" + c.method + "'");
    study->solver.method = c.method;
    if (c.solver.empty() && c.method == "sensitivity") study->solver.name = "ceres";
  }
  if (!c.solver.empty()) study->solver.name = c.solver;
  if (c.solver.empty() && c.method.empty()) return;
  study->solver.label = study->solver.method + " (" + study->solver.name + ")";
  try {
    if (study->solver.method == "linear") {
      femup::CreateLinearSolver(study->solver.name, study->solver.linear);
    } else {
      femup::CreateNonlinearSolver(study->solver.name, study->solver.nonlinear);
    }
  } catch (const femup::InputError& e) {
    throw femup::InputError("--solver", e.what());
  }
}

void RequireMeasurements(const femup::Study& study) {
  if (study.measurements.empty()) {
    throw femup::InputError(study.path,
                            "measurements: missing (this study only describes records "
                            "to simulate; run femup simulate on it)");
  }
}

std::string OutputFolder(const Common& c, const femup::Study& study) {
  if (!c.out.empty()) return c.out;
  std::filesystem::create_directories("out");
  return "out/" + study.name;
}

// Reports of long work as a bar on stderr, only when stderr is a terminal and
// the command is not --quiet.
std::unique_ptr<femup::ProgressBar> MakeProgressBar(const std::string& label,
                                                    bool quiet) {
  return std::make_unique<femup::ProgressBar>(label, &std::cerr,
                                              !quiet && femup::StderrIsTerminal());
}

constexpr const char* kVersion = "femup 0.1.0";

// The command line as typed, each argument quoted where the shell would need it.
std::string g_command_line;

std::string QuotedCommandLine(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    std::string arg = i == 0 ? std::string("femup") : std::string(argv[i]);
    const bool plain =
        !arg.empty() && arg.find_first_not_of(
                            "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUV"
                            "WXYZ0123456789-_./=:,+@%") == std::string::npos;
    if (!plain) {
      std::string quoted = "'";
      for (const char ch : arg)
        quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
      arg = quoted + "'";
    }
    line += (i ? " " : "") + arg;
  }
  return line;
}

// What report.html shows besides the output folder's files.
femup::RunReport Report(const std::string& command, const std::string& name,
                        std::vector<std::string> inputs, std::string summary) {
  femup::RunReport report;
  report.command = command;
  report.name = name;
  report.command_line = g_command_line;
  report.version = kVersion;
  report.inputs = std::move(inputs);
  report.summary = std::move(summary);
  return report;
}

// Stages report.html, moves every file into place, then prints the warnings
// and what was written.
void Finish(femup::OutputDir* dir, const std::vector<std::string>& warnings, bool quiet,
            femup::RunReport report) {
  report.warnings = warnings;
  femup::WriteRunReport(report, dir);
  dir->Commit();
  for (const auto& w : warnings) std::cerr << "femup: warning: " << w << "\n";
  if (!quiet) {
    std::cout << "\nwrote to " << dir->directory() << ":";
    for (const auto& f : dir->files()) {
      if (std::filesystem::exists(std::filesystem::path(dir->directory()) / f)) {
        std::cout << " " << f;
      }
    }
    std::cout << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "femup: find where a finite element model is wrong, and by how much, from "
      "vibration measurements"};
  app.require_subcommand(1);
  app.set_version_flag("--version", kVersion);
  g_command_line = QuotedCommandLine(argc, argv);

  Common run_opts, noise_opts, modes_opts, check_opts, sim_opts, diag_opts;
  int num_modes = 0;
  CLI::App* run = app.add_subcommand(
      "run", "identify correction factors (Z d = F), build the updated model, compare");
  AddCommon(run, &run_opts);
  AddSolverOverride(run, &run_opts);
  CLI::App* noise = app.add_subcommand(
      "noise", "the noise study: Rm of the added-mass factors vs corruption");
  AddCommon(noise, &noise_opts);
  AddSolverOverride(noise, &noise_opts);
  femup::NoiseRunOptions noise_run;
  noise_run.threads = 2;
  noise->add_option("--threads", noise_run.threads,
                    "draws solved in parallel (default 2); the results are identical "
                    "for any number");
  CLI::App* modes =
      app.add_subcommand("modes", "modal analysis of the study's nominal model");
  AddCommon(modes, &modes_opts);
  modes->add_option("-n,--modes", num_modes,
                    "number of lowest modes (default: all, or 10)");
  CLI::App* simulate = app.add_subcommand(
      "simulate",
      "test records of the study's structure (its truth factors, strip-theory water): "
      "impulse responses at the sensors as UFF 58 or CSV, with truth.json");
  AddCommon(simulate, &sim_opts);
  CLI::App* diagnose = app.add_subcommand(
      "diagnose",
      "the sim-to-real gap: where it lies, which unmodelled effect causes it (ranked, "
      "with probabilities), how far it shrinks on fitted and held-out modes");
  AddCommon(diagnose, &diag_opts);
  CLI::App* bench = app.add_subcommand(
      "benchmark",
      "the blind benchmark of diagnose: generate cases (study files; truth kept apart), "
      "diagnose each, score");
  femup::BenchmarkOptions bench_options;
  std::string bench_out = "out/benchmark";
  bool bench_no_plots = false, bench_quiet = false;
  bench->add_option("--suite", bench_options.suite, "single or mixed (default mixed)");
  bench->add_option("--cases", bench_options.cases, "number of cases (default 100)");
  bench->add_option("--seed", bench_options.seed, "random seed (default 20261121)");
  bench->add_option("--threads", bench_options.threads, "cases in parallel (default 2)");
  bench->add_option("--sizes", bench_options.sizes,
                    "effect sizes: noise (largest frequency shift 1-50 x the case's "
                    "frequency noise, the default) or absolute (0.5-20 %)");
  bench->add_option("--evidence", bench_options.evidence,
                    "each class's evidence in the diagnosis: laplace (the default) or "
                    "sampled (importance sampling)");
  bench->add_option("--form-error", bench_options.form_error,
                    "the diagnosis's form error, a fraction of the nominal misfit "
                    "(default: diagnose's, 0.05)");
  bench->add_flag("--noise-free", bench_options.noise_free,
                  "the same cases without the noise added to their data (the noise "
                  "still stated): which misses the noise causes");
  bench->add_option("--oracle", bench_options.oracle,
                    "single suite: also the Bayes-optimal classification under the "
                    "generator's own prior and forms, the ceiling of top-1: off (the "
                    "default), weak (cases with no effect or effects below 5 sigma: "
                    "enough for the ceiling) or all");
  bench->add_option("--oracle-samples", bench_options.oracle_samples,
                    "the oracle's importance-sampling draws per sub-class (default 500)");
  bench->add_option("-o,--out", bench_out, "output folder (default out/benchmark)");
  bench->add_flag("--no-plots", bench_no_plots, "write JSON and tables only");
  bench->add_flag("-q,--quiet", bench_quiet, "print nothing but errors and warnings");
  CLI::App* compare = app.add_subcommand(
      "compare",
      "run several studies of one structure and compare their added mass "
      "(factors along the structure, Sa) and updated frequencies");
  std::vector<std::string> compare_studies;
  std::string compare_out = "out/compare";
  bool compare_no_plots = false, compare_quiet = false;
  compare->add_option("studies", compare_studies, "study files (two or more)")
      ->required();
  compare->add_option("-o,--out", compare_out, "output folder (default out/compare)");
  compare->add_flag("--no-plots", compare_no_plots, "write JSON only");
  compare->add_flag("-q,--quiet", compare_quiet, "print nothing but errors and warnings");
  CLI::App* check =
      app.add_subcommand("check", "read and check a study file, do no work");
  check->add_option("study", check_opts.study, "study file (YAML or JSON)")->required();

  CLI::App* solve = app.add_subcommand(
      "solve",
      "solve a general linear inverse problem A x ~ b from files (.mtx or .csv)");
  femup::SolveFiles files;
  std::string solve_solver = "lstsq", solve_out = "out/solve";
  femup::LinearSolverOptions solve_options;
  bool solve_no_plots = false, solve_quiet = false;
  solve
      ->add_option("--A", files.a,
                   "matrix A (.mtx or .csv; a CSV header names the unknowns)")
      ->required();
  solve->add_option("--b", files.b, "right-hand side b (.mtx or .csv)")->required();
  solve->add_option("--lower", files.lower, "lower bounds (vector file)");
  solve->add_option("--upper", files.upper, "upper bounds (vector file)");
  solve->add_option("--truth", files.truth,
                    "a reference solution to report the error against");
  solve->add_option("--sigma", files.data_sigma,
                    "noise standard deviation of b (known noise)");
  solve->add_option("--solver", solve_solver,
                    "lstsq, tsvd, tikhonov, bvls, ceres or ipopt (default lstsq)");
  solve->add_option("--parameter-choice", solve_options.regularisation.parameter_choice,
                    "tikhonov/tsvd: gcv, lcurve, discrepancy, quasi_optimality or fixed");
  solve->add_option("--lambda", solve_options.regularisation.lambda,
                    "tikhonov with --parameter-choice fixed: lambda");
  solve->add_option("--noise-norm", solve_options.regularisation.noise_norm,
                    "discrepancy principle: ||e||");
  solve->add_option("--operator", solve_options.regularisation.op,
                    "tikhonov: identity, first_difference or second_difference");
  solve->add_option("--truncation", solve_options.truncation,
                    "tsvd: singular values kept");
  solve->add_option("-o,--out", solve_out, "output folder (default out/solve)");
  solve->add_flag("--no-plots", solve_no_plots, "write JSON and CSV only");
  solve->add_flag("-q,--quiet", solve_quiet, "print nothing but errors and warnings");

  CLI::App* identify = app.add_subcommand(
      "identify",
      "modes from measured signals: ERA with a stabilisation diagram on a UFF 58 file "
      "(time histories or FRFs) or a CSV time series");
  femup::IdentifyOptions id_options;
  std::string id_out = "out/identify";
  bool id_no_plots = false, id_quiet = false;
  identify->add_option("file", id_options.file, "UFF (.uff, .unv) or CSV (.csv) file")
      ->required();
  identify->add_option("--format", id_options.format,
                       "uff or csv (default: by extension)");
  identify->add_option("--min-order", id_options.stabilisation.min_order,
                       "lowest model order (default 2)");
  identify->add_option("--max-order", id_options.stabilisation.max_order,
                       "highest model order (default 40)");
  identify->add_option("--order-step", id_options.stabilisation.order_step,
                       "order step (default 2)");
  identify->add_option("--stable-orders", id_options.min_consecutive,
                       "consecutive stable orders a mode needs (default 5)");
  identify->add_option("--max-frequency", id_options.max_frequency_hz,
                       "report modes below this frequency, Hz (default Nyquist)");
  identify->add_option("--first-sample", id_options.stabilisation.era.first_sample,
                       "first sample used by ERA (default 1: skips the impulse instant)");
  identify->add_option("-o,--out", id_out, "output folder (default out/identify)");
  identify->add_flag("--no-plots", id_no_plots, "write JSON only");
  identify->add_flag("-q,--quiet", id_quiet, "print nothing but errors and warnings");

  CLI::App* info = app.add_subcommand(
      "info",
      "describe a data file: a UFF file's datasets (58 functions, 55 mode shapes, "
      "15/2411 nodes), a CSV time series' channels, a Matrix Market matrix");
  std::string info_file;
  bool info_json = false;
  info->add_option("file", info_file, "a .uff, .unv, .csv or .mtx file")->required();
  info->add_flag("--json", info_json, "print JSON instead of text");

  CLI11_PARSE(app, argc, argv);

  try {
    std::vector<std::string> warnings;
    if (*check) {
      const femup::Study study = femup::LoadStudy(check_opts.study);
      std::cout << check_opts.study << ": ok: " << study.structure.description << ", "
                << study.model.num_dofs() << " DOFs, " << study.model.num_parameters()
                << " parameters, " << study.measurements.size() << " measured state(s)\n";
      return 0;
    }
    if (*info) {
      const femup::FileInfo described = femup::DescribeFile(info_file);
      std::cout << (info_json ? femup::FileInfoJson(described)
                              : femup::FileInfoReport(described));
      return 0;
    }
    if (*simulate) {
      const femup::Study study = femup::LoadStudy(sim_opts.study);
      const femup::SimulateResult result = femup::RunSimulate(study);
      femup::OutputDir dir(OutputFolder(sim_opts, study));
      femup::WriteSimulateOutputs(result, study.plots && !sim_opts.no_plots, &dir,
                                  &warnings);
      const std::string text = femup::SimulateReport(result);
      if (!sim_opts.quiet) std::cout << text;
      Finish(&dir, warnings, sim_opts.quiet,
             Report("simulate", study.name, {sim_opts.study}, text));
      return 0;
    }
    if (*diagnose) {
      const femup::Study study = femup::LoadStudy(diag_opts.study);
      RequireMeasurements(study);
      if (!study.cantilever) {
        // Every other model type: effects as changes of the model itself.
        const femup::StructureDiagnosisResult result =
            femup::RunStructureDiagnosis(study);
        femup::OutputDir dir(OutputFolder(diag_opts, study));
        femup::WriteStructureDiagnosisOutputs(result, study.plots && !diag_opts.no_plots,
                                              &dir, &warnings);
        const std::string text = femup::StructureDiagnosisReport(result);
        if (!diag_opts.quiet) std::cout << text;
        Finish(&dir, warnings, diag_opts.quiet,
               Report("diagnose", study.name, {diag_opts.study}, text));
        return 0;
      }
      const femup::DiagnosisResult result = femup::RunDiagnosis(study);
      femup::OutputDir dir(OutputFolder(diag_opts, study));
      femup::WriteDiagnosisOutputs(result, study.plots && !diag_opts.no_plots, &dir,
                                   &warnings);
      const std::string text = femup::DiagnosisReport(result);
      if (!diag_opts.quiet) std::cout << text;
      Finish(&dir, warnings, diag_opts.quiet,
             Report("diagnose", study.name, {diag_opts.study}, text));
      return 0;
    }
    if (*bench) {
      if (const femup::Invalid bad = bench_options.Validate()) {
        std::string flag = bad.field;
        std::replace(flag.begin(), flag.end(), '_', '-');  // form_error: --form-error
        throw femup::InputError("--" + flag, bad.message);
      }
      std::filesystem::create_directories(bench_out);
      femup::BenchmarkResult result;
      {
        const auto bar = MakeProgressBar("diagnosing cases", bench_quiet);
        result = femup::RunBenchmark(bench_options, bench_out, bar->Callback());
      }
      femup::OutputDir dir(bench_out);
      femup::WriteBenchmarkOutputs(result, !bench_no_plots, &dir, &warnings);
      const std::string text = femup::BenchmarkReport(result);
      if (!bench_quiet) std::cout << text;
      Finish(&dir, warnings, bench_quiet,
             Report("benchmark",
                    bench_options.suite + " suite, " +
                        std::to_string(bench_options.cases) + " cases",
                    {}, text));
      return 0;
    }
    if (*compare) {
      const femup::CompareResult result = femup::RunCompare(compare_studies);
      femup::OutputDir dir(compare_out);
      femup::WriteCompareOutputs(result, !compare_no_plots, &dir, &warnings);
      const std::string text = femup::CompareReport(result);
      if (!compare_quiet) std::cout << text;
      Finish(&dir, warnings, compare_quiet,
             Report("compare", std::to_string(compare_studies.size()) + " studies",
                    compare_studies, text));
      return 0;
    }
    if (*run) {
      femup::Study study = femup::LoadStudy(run_opts.study);
      RequireMeasurements(study);
      ApplyOverride(run_opts, &study);
      const femup::UpdateResult result = femup::RunUpdate(study);
      femup::OutputDir dir(OutputFolder(run_opts, study));
      femup::WriteUpdateOutputs(result, study.plots && !run_opts.no_plots, &dir,
                                &warnings);
      const std::string text = femup::UpdateReport(result);
      if (!run_opts.quiet) std::cout << text;
      for (const auto& w : result.solution.identifiability.warnings) {
        warnings.push_back("solved system: " + w);
      }
      Finish(&dir, warnings, run_opts.quiet,
             Report("run", study.name, {run_opts.study}, text));
      return result.solution.summary.usable() ? 0 : 3;
    }
    if (*noise) {
      if (const femup::Invalid bad = noise_run.Validate())
        throw femup::InputError("--" + bad.field, bad.message);
      femup::Study study = femup::LoadStudy(noise_opts.study);
      RequireMeasurements(study);
      ApplyOverride(noise_opts, &study);
      if (!study.noise_study) {
        throw femup::InputError(noise_opts.study,
                                "noise_study: the study has no noise_study "
                                "section (levels, draws, seed)");
      }
      femup::NoiseStudyResult result;
      {
        const auto bar = MakeProgressBar("noise draws", noise_opts.quiet);
        noise_run.progress = bar->Callback();
        result = femup::RunNoiseStudy(study, noise_run);
        noise_run.progress = nullptr;  // the bar goes now
      }
      femup::OutputDir dir(OutputFolder(noise_opts, study));
      femup::WriteNoiseOutputs(result, study.plots && !noise_opts.no_plots, &dir,
                               &warnings);
      const std::string text = femup::NoiseReport(result);
      if (!noise_opts.quiet) std::cout << text;
      Finish(&dir, warnings, noise_opts.quiet,
             Report("noise", study.name, {noise_opts.study}, text));
      return 0;
    }
    if (*solve) {
      const femup::SolveResult result =
          femup::RunSolve(files, solve_solver, solve_options);
      femup::OutputDir dir(solve_out);
      femup::WriteSolveOutputs(result, !solve_no_plots, &dir, &warnings);
      const std::string text = femup::SolveReport(result);
      if (!solve_quiet) std::cout << text;
      std::vector<std::string> inputs{files.a, files.b};
      for (const std::string* f : {&files.lower, &files.upper, &files.truth}) {
        if (!f->empty()) inputs.push_back(*f);
      }
      Finish(&dir, warnings, solve_quiet,
             Report("solve", solve_solver + " on " + files.a, inputs, text));
      return result.solution.summary.usable() ? 0 : 3;
    }
    if (*identify) {
      const femup::IdentifyResult result = femup::RunIdentify(id_options);
      femup::OutputDir dir(id_out);
      femup::WriteIdentifyOutputs(result, !id_no_plots, &dir, &warnings);
      const std::string text = femup::IdentifyReport(result);
      if (!id_quiet) std::cout << text;
      Finish(&dir, warnings, id_quiet,
             Report("identify", id_options.file, {id_options.file}, text));
      return result.modes.empty() ? 3 : 0;
    }
    if (*modes) {
      const femup::Study study = femup::LoadStudy(modes_opts.study);
      const femup::ModesResult result = femup::RunModes(study, num_modes);
      femup::OutputDir dir(OutputFolder(modes_opts, study));
      femup::WriteModesOutputs(result, study.plots && !modes_opts.no_plots, &dir,
                               &warnings);
      const std::string text = femup::ModesReport(result);
      if (!modes_opts.quiet) std::cout << text;
      Finish(&dir, warnings, modes_opts.quiet,
             Report("modes", study.name, {modes_opts.study}, text));
      return 0;
    }
  } catch (const femup::InputError& e) {
    std::cerr << "femup: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "femup: internal error: " << e.what() << "\n";
    return 4;
  }
  return 0;
}
