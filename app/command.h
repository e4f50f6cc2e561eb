// The command line as a table: each subcommand of femup is a Command (its
// name, its one-line description, the options it adds and what it runs), made
// by one file under app/commands/ and listed in the table in app/main.cc.
// What commands share is here: the study file and output options, the
// --solver/--method override, the output folder rule, the progress bar and
// the end of every run that writes a folder (write, print, report, Finish).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/progress.h"
#include "femup/reporting/output_dir.h"
#include "femup/studies/study.h"

namespace femup::cli {

inline constexpr const char* kVersion = "femup 0.1.0";

// What every command may need from the command line as a whole.
struct Invocation {
  std::string command_line;  // as typed, each argument quoted where needed
};

// One subcommand. `add_options` declares its options on the CLI11 subcommand
// (into storage the Command owns); `run` does the work after parsing and
// returns the exit code. Bad input is thrown as femup::InputError (exit 1),
// anything else thrown is an internal error (exit 4): main.cc decides.
struct Command {
  std::string name;
  std::string description;
  std::function<void(CLI::App*)> add_options;
  std::function<int(const Invocation&)> run;
};

// The command line as typed, argv[0] given as "femup", each argument quoted
// where the shell would need it.
std::string QuotedCommandLine(int argc, char** argv);

// -o/--out, --no-plots and -q/--quiet, the same for every command that writes
// an output folder.
struct OutputOptions {
  std::string out;  // the folder given, or the command's default
  bool no_plots = false;
  bool quiet = false;
};

// Adds -o,--out ("output folder (default <default_folder>)", the folder set as
// the default), --no-plots ("write <without_plots> only") and -q,--quiet.
// With no default folder, the help names the study rule of OutputFolder:
// "output folder (default: out/<study name>)".
void AddOutputOptions(CLI::App* cmd, OutputOptions* options,
                      const std::string& without_plots,
                      const std::string& default_folder = "");

// --solver and --method: the study file's solver replaced for this run.
struct SolverChoice {
  std::string name;    // --solver: overrides the study file's solver.name
  std::string method;  // --method: overrides solver.method
};

// The options of a command on one study file: the file, the output options
// and (for the commands that solve) the solver override.
struct StudyOptions {
  std::string study;
  OutputOptions output;
  SolverChoice solver;
};

// The required positional "study" (a YAML or JSON study file).
void AddStudyFile(CLI::App* cmd, std::string* study);
// The study file and the output options (plots off: "write JSON and matrices only").
void AddStudyOptions(CLI::App* cmd, StudyOptions* options);
void AddSolverOverride(CLI::App* cmd, SolverChoice* choice);

// Applies --solver / --method and checks the result before any work.
void ApplyOverride(const SolverChoice& choice, femup::Study* study);

// Fails for a study without measurements (one only to simulate).
void RequireMeasurements(const femup::Study& study);

// The folder given by -o, else out/<study name> (creating out/).
std::string OutputFolder(const OutputOptions& output, const femup::Study& study);

// Reports of long work as a bar on stderr, only when stderr is a terminal and
// the command is not --quiet.
std::unique_ptr<femup::ProgressBar> MakeProgressBar(const std::string& label, bool quiet);

// What report.html says of a run besides the output folder's files and the
// printed summary.
struct RunInfo {
  std::string command;  // the subcommand, e.g. "run"
  std::string name;     // the study's name or the job's label
  std::vector<std::string> inputs;
};

// Stages report.html, moves every file into place, then prints the warnings
// and what was written.
void Finish(const Invocation& invocation, femup::OutputDir* dir,
            const std::vector<std::string>& warnings, bool quiet, const RunInfo& info,
            const std::string& summary);

// The end of every command that writes a folder: the result's files (plots
// when `plots`) staged in `folder`, its report printed unless quiet, then
// Finish. `more_warnings` follow the writer's own.
template <typename Result, typename Write, typename Describe>
void Publish(const Invocation& invocation, const RunInfo& info, const std::string& folder,
             bool plots, bool quiet, const Result& result, Write write, Describe describe,
             const std::vector<std::string>& more_warnings = {}) {
  femup::OutputDir dir(folder);
  std::vector<std::string> warnings;
  write(result, plots, &dir, &warnings);
  const std::string text = describe(result);
  if (!quiet) std::cout << text;
  warnings.insert(warnings.end(), more_warnings.begin(), more_warnings.end());
  Finish(invocation, &dir, warnings, quiet, info, text);
}

// Publish for a command on one study file: the folder by OutputFolder, plots
// when the study and the options both want them, the study named in the report.
template <typename Result, typename Write, typename Describe>
void PublishStudy(const Invocation& invocation, const std::string& command,
                  const femup::Study& study, const StudyOptions& options,
                  const Result& result, Write write, Describe describe,
                  const std::vector<std::string>& more_warnings = {}) {
  const std::string folder = OutputFolder(options.output, study);
  Publish(invocation, RunInfo{command, study.name, {options.study}}, folder,
          study.plots && !options.output.no_plots, options.output.quiet, result, write,
          describe, more_warnings);
}

}  // namespace femup::cli
