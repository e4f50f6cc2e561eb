// What a person reads of the noise study (`femup noise`): the files written into the
// command's output folder and the summary the terminal prints. The pipeline
// (femup/studies/noise_study.h) returns the result; this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/noise_study.h"

namespace femup {

void WriteNoiseOutputs(const NoiseStudyResult& result, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings);
std::string NoiseReport(const NoiseStudyResult& result);

}  // namespace femup
