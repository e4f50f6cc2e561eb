// report.html: the one page a person opens after a command. It is written into
// the command's output folder beside the JSON, and holds the run's facts, its
// warnings, the summary the terminal prints (verdict, factors, tables), every
// plot staged in the folder (inline, with the titles of its panels), the study
// file itself, and the list of files written, linked.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"

namespace femup {

struct RunReport {
  std::string command;       // the subcommand, e.g. "run"
  std::string name;          // the study's name or the job's label
  std::string command_line;  // as typed, for reproducing the run
  std::string version;       // e.g. "femup 0.1.0"
  // Input files: study files (YAML/JSON) are shown in full, other files (data,
  // matrices) are named with their size.
  std::vector<std::string> inputs;
  std::string summary;  // the text the command prints on the terminal
  std::vector<std::string> warnings;
};

// The page for `report` and the files staged in `dir` so far (PNG plots are
// embedded; their .gp scripts give the captions).
std::string RenderRunReport(const RunReport& report, OutputDir* dir);

// Stages "report.html" in `dir` (committed with the rest, all or nothing).
void WriteRunReport(const RunReport& report, OutputDir* dir);

}  // namespace femup
