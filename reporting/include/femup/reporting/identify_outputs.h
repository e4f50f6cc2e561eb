// What a person reads of modes identified from measured signals (`femup identify`): the
// files written into the command's output folder and the summary the terminal prints. The
// pipeline (femup/studies/identify_study.h) returns the result; this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/identify_study.h"

namespace femup {

// Writes <prefix>modes.json and, when `plots`, <prefix>stabilisation.png and
// <prefix>identified_shapes.png.
void WriteIdentifyOutputs(const IdentifyResult& result, bool plots, OutputDir* out,
                          std::vector<std::string>* warnings,
                          const std::string& prefix = "");
std::string IdentifyReport(const IdentifyResult& result);

}  // namespace femup
