// What the commands of app/commands/ share (see command.h).
#include "command.h"

#include <filesystem>

#include "femup/core/errors.h"
#include "femup/reporting/run_report.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/nonlinear_solver.h"

namespace femup::cli {

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

void AddOutputOptions(CLI::App* cmd, OutputOptions* options,
                      const std::string& without_plots,
                      const std::string& default_folder) {
  options->out = default_folder;
  cmd->add_option("-o,--out", options->out,
                  default_folder.empty()
                      ? std::string("output folder (default: out/<study name>)")
                      : "output folder (default " + default_folder + ")");
  cmd->add_flag("--no-plots", options->no_plots, "write " + without_plots + " only");
  cmd->add_flag("-q,--quiet", options->quiet, "print nothing but errors and warnings");
}

void AddStudyFile(CLI::App* cmd, std::string* study) {
  cmd->add_option("study", *study, "study file (YAML or JSON)")->required();
}

void AddStudyOptions(CLI::App* cmd, StudyOptions* options) {
  AddStudyFile(cmd, &options->study);
  AddOutputOptions(cmd, &options->output, "JSON and matrices");
}

void AddSolverOverride(CLI::App* cmd, SolverChoice* choice) {
  cmd->add_option(
      "--solver", choice->name,
      "solver name, overriding the study file (linear: lstsq, tsvd, tikhonov, "
      "bvls, ceres, ipopt; sensitivity: ceres, ipopt)");
  cmd->add_option(
      "--method", choice->method,
      "linear (the paper's Z d = F) or sensitivity (iterative eigen-sensitivity)");
}

void ApplyOverride(const SolverChoice& choice, femup::Study* study) {
  if (!choice.method.empty()) {
    if (choice.method != "linear" && choice.method != "sensitivity")
      throw femup::InputError(
          "--method", "expected linear or sensitivity, got '" + choice.method + "'");
    study->solver.method = choice.method;
    if (choice.name.empty() && choice.method == "sensitivity")
      study->solver.name = "ceres";
  }
  if (!choice.name.empty()) study->solver.name = choice.name;
  if (choice.name.empty() && choice.method.empty()) return;
  study->solver.label = study->solver.method + " (" + study->solver.name + ")";
  // The factories are the one place that knows the names and checks the
  // options (the study file's own solver is checked the same way when read);
  // the solver made here is dropped.
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

std::string OutputFolder(const OutputOptions& output, const femup::Study& study) {
  if (!output.out.empty()) return output.out;
  std::filesystem::create_directories("out");
  return "out/" + study.name;
}

std::unique_ptr<femup::ProgressBar> MakeProgressBar(const std::string& label,
                                                    bool quiet) {
  return std::make_unique<femup::ProgressBar>(label, &std::cerr,
                                              !quiet && femup::StderrIsTerminal());
}

void Finish(const Invocation& invocation, femup::OutputDir* dir,
            const std::vector<std::string>& warnings, bool quiet, const RunInfo& info,
            const std::string& summary) {
  femup::RunReport report;
  report.command = info.command;
  report.name = info.name;
  report.command_line = invocation.command_line;
  report.version = kVersion;
  report.inputs = info.inputs;
  report.summary = summary;
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

}  // namespace femup::cli
