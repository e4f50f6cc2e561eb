// What a person reads of the update of the reference paper's method (`femup run`): the
// files written into the command's output folder and the summary the terminal prints. The
// pipeline (femup/studies/update_study.h) returns the result; this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/update_study.h"

namespace femup {

// Writes result.json, the updated matrices (Matrix Market) and, when `plots`,
// factors.png, frequencies.png and shapes_<state>.png into `out`.
void WriteUpdateOutputs(const UpdateResult& result, bool plots, OutputDir* out,
                        std::vector<std::string>* warnings);

// Human-readable summary for the terminal.
std::string UpdateReport(const UpdateResult& result);

}  // namespace femup
