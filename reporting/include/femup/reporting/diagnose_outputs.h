// What a person reads of the cantilever's diagnosis (`femup diagnose`): the files written
// into the command's output folder and the summary the terminal prints. The pipeline
// (femup/studies/diagnose_study.h) returns the result; this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/diagnose_study.h"

namespace femup {

// diagnosis.json and, when `plots`, localisation.png, effects.png, gap.png.
void WriteDiagnosisOutputs(const DiagnosisResult& result, bool plots, OutputDir* out,
                           std::vector<std::string>* warnings);

std::string DiagnosisReport(const DiagnosisResult& result);

}  // namespace femup
