// What a person reads of simulated test records (`femup simulate`): the files written
// into the command's output folder and the summary the terminal prints. The pipeline
// (femup/studies/simulate_study.h) returns the result; this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/simulate_study.h"

namespace femup {

// Writes each state's record file, truth.json and, when `plots`, records.png.
void WriteSimulateOutputs(const SimulateResult& result, bool plots, OutputDir* out,
                          std::vector<std::string>* warnings);

std::string SimulateReport(const SimulateResult& result);

}  // namespace femup
