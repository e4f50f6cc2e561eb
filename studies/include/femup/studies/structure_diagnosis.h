// `femup diagnose` on every model type (a chain or shear building, a cantilever,
// a plane or space frame, a Matrix Market model with element matrices): which
// unmodelled effect, where and how large, from the study's measured modes, by
// RankModelEffects (effect_ranking.h) over the families that apply to the
// model: the one engine, every study's default. A cantilever's study may
// still choose its own pipeline (diagnose_study.h) with engine: cantilever.
#pragma once

#include <string>
#include <vector>

#include "femup/studies/diagnosis_map.h"
#include "femup/studies/effect_ranking.h"
#include "femup/studies/study.h"

namespace femup {

struct StructureDiagnosisResult {
  std::string study_name;
  std::string description;
  std::string model_type;
  std::vector<ModalData> measured;  // at the sensors
  std::vector<std::string> dof_labels;
  EffectRanking ranking;
  double confidence = 0.9;
  double gap_confidence = 0;       // DiagnosisSpec::gap_confidence
  double gap_explained = 1.0 / 3;  // DiagnosisSpec::gap_explained
  StatedPriors priors;             // as the study states them (diagnosis.priors, weights)
  DiagnosisMap map;                // the model's geometry, for diagnosis_map.png
};

// Throws InputError (naming the study file and field) for a study without
// measurements, a candidate family that does not apply to the model, a stated
// prior that does not fit the model's families (each before any fit runs), or
// data the fit cannot use.
StructureDiagnosisResult RunStructureDiagnosis(const Study& study);

}  // namespace femup
