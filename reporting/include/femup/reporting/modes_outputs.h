// What a person reads of the nominal model's modes (`femup modes`): the files written
// into the command's output folder and the summary the terminal prints. The pipeline
// (femup/studies/modes_study.h) returns the result; this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/modes_study.h"

namespace femup {

void WriteModesOutputs(const ModesResult& result, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings);
std::string ModesReport(const ModesResult& result);

}  // namespace femup
