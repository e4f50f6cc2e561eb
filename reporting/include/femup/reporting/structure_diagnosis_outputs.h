// What a person reads of the diagnosis of a structure that is not a cantilever (`femup
// diagnose`): the files written into the command's output folder and the summary the
// terminal prints. The pipeline (femup/studies/structure_diagnosis.h) returns the result;
// this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/structure_diagnosis.h"

namespace femup {

// diagnosis.json (every class with kind, region, probability, chi2, evidence,
// parameters and magnitudes; the families' probabilities; the noise
// temperature; the families that do not apply and why; the stated priors),
// effects.png (the families' probabilities) and diagnosis_map.png (where:
// diagnosis_map.h).
void WriteStructureDiagnosisOutputs(const StructureDiagnosisResult& r, bool plots,
                                    OutputDir* out, std::vector<std::string>* warnings);

// The terminal report: the verdict and the ranked classes.
std::string StructureDiagnosisReport(const StructureDiagnosisResult& r);

}  // namespace femup
