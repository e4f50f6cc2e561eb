// What a person reads of each pipeline's result: Write<Name>Outputs writes
// the files into the command's output folder (JSON, matrices, record files
// and, when `plots`, the pictures; warnings gathered for report.html) and
// <Name>Report is the summary the terminal prints. The pipelines
// (femup/studies/) return the results and write nothing; the command line and
// Python call these. One definition file per pipeline: reporting/src/<name>_outputs.cc.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/compare_study.h"
#include "femup/studies/diagnose_study.h"
#include "femup/studies/identify_study.h"
#include "femup/studies/modes_study.h"
#include "femup/studies/noise_study.h"
#include "femup/studies/simulate_study.h"
#include "femup/studies/solve_study.h"
#include "femup/studies/structure_diagnosis.h"
#include "femup/studies/update_study.h"

namespace femup {

// ---- the update of the reference paper's method (`femup run`)

// Writes result.json, the updated matrices (Matrix Market) and, when `plots`,
// factors.png, frequencies.png and shapes_<state>.png into `out`.
void WriteUpdateOutputs(const UpdateResult& result, bool plots, OutputDir* out,
                        std::vector<std::string>* warnings);

// Human-readable summary for the terminal.
std::string UpdateReport(const UpdateResult& result);

// ---- the noise study (`femup noise`)

void WriteNoiseOutputs(const NoiseStudyResult& result, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings);
std::string NoiseReport(const NoiseStudyResult& result);

// ---- the nominal model's modes (`femup modes`)

void WriteModesOutputs(const ModesResult& result, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings);
std::string ModesReport(const ModesResult& result);

// ---- a linear inverse problem solved from files (`femup solve`)

void WriteSolveOutputs(const SolveResult& result, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings);
std::string SolveReport(const SolveResult& result);

// ---- modes identified from measured signals (`femup identify`)

// Writes <prefix>modes.json and, when `plots`, <prefix>stabilisation.png and
// <prefix>identified_shapes.png.
void WriteIdentifyOutputs(const IdentifyResult& result, bool plots, OutputDir* out,
                          std::vector<std::string>* warnings,
                          const std::string& prefix = "");
std::string IdentifyReport(const IdentifyResult& result);

// ---- simulated test records (`femup simulate`)

// Writes each state's record file, truth.json and, when `plots`, records.png.
void WriteSimulateOutputs(const SimulateResult& result, bool plots, OutputDir* out,
                          std::vector<std::string>* warnings);

std::string SimulateReport(const SimulateResult& result);

// ---- several updates side by side (`femup compare`)

// comparison.json and, when `plots`, added_mass_factors.png and sa.png.
void WriteCompareOutputs(const CompareResult& result, bool plots, OutputDir* out,
                         std::vector<std::string>* warnings);

std::string CompareReport(const CompareResult& result);

// ---- the cantilever's diagnosis (`femup diagnose`)

// diagnosis.json and, when `plots`, localisation.png, effects.png, gap.png.
void WriteDiagnosisOutputs(const DiagnosisResult& result, bool plots, OutputDir* out,
                           std::vector<std::string>* warnings);

std::string DiagnosisReport(const DiagnosisResult& result);

// ---- the diagnosis of a structure that is not a cantilever (`femup

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
