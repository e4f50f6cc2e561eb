// What a person reads of several updates side by side (`femup compare`): the files
// written into the command's output folder and the summary the terminal prints. The
// pipeline (femup/studies/compare_study.h) returns the result; this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/compare_study.h"

namespace femup {

// comparison.json and, when `plots`, added_mass_factors.png and sa.png.
void WriteCompareOutputs(const CompareResult& result, bool plots, OutputDir* out,
                         std::vector<std::string>* warnings);

std::string CompareReport(const CompareResult& result);

}  // namespace femup
