#include "femup/studies/structure_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {

StructureDiagnosisResult RunStructureDiagnosis(const Study& study) {
  if (study.measurements.empty())
    throw InputError(study.path, "measurements: missing (nothing to diagnose)");
  if (study.structure.stiffness.rows() == 0 && study.structure.type == "space_frame") {
    throw InputError(study.path,
                     "model: femup diagnose runs on space_frame models up to 60000 DOF "
                     "(each stiffness group's matrices are held apart); this one has " +
                         std::to_string(study.model.num_dofs()) +
                         ": fewer levels, bays or elements_per_member");
  }
  if (study.structure.stiffness.rows() == 0) {
    throw InputError(
        study.path, "model.type: femup diagnose does not run on " + study.structure.type +
                        " models yet (they are assembled without per-member matrices, "
                        "which every effect family acts on); chain, cantilever, "
                        "plane_frame and matrix_market models with element matrices "
                        "can be diagnosed");
  }
  const DiagnosisSpec spec = study.diagnosis.value_or(DiagnosisSpec());
  StructureDiagnosisResult r;
  r.study_name = study.name;
  r.description = study.description;
  r.model_type = study.structure.type;
  r.dof_labels = study.model.dof_labels();
  r.confidence = spec.confidence;
  r.map = MapGeometry(study.structure);

  EffectRankingOptions options;
  options.kinds = spec.candidates;
  options.frequency_sigma = spec.frequency_noise;
  options.shape_sigma = spec.shape_noise;
  options.use_shapes = spec.use_shapes;
  options.solver = spec.solver;
  options.priors = spec.priors;
  options.formulation_error = spec.formulation_error;
  options.bagging_copies = spec.bagging_copies;
  options.max_members = spec.max_members;
  options.members_fitted = spec.members_fitted;
  r.priors = spec.priors;
  // A named family that does not apply is the study's error, before any fit.
  for (const std::string& kind : options.kinds) {
    const auto known = ModelEffectKinds();
    if (std::find(known.begin(), known.end(), kind) == known.end()) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError(study.path, "diagnosis.candidates: '" + kind +
                                       "' is not a family a " + r.model_type +
                                       " model knows (" + list + ")");
    }
    for (const FamilyApplicability& a : ApplicableModelEffects(study.structure)) {
      if (a.kind == kind && !a.why_not.empty()) {
        throw InputError(study.path, "diagnosis.candidates: " + kind +
                                         " does not apply to this " + r.model_type +
                                         " model: " + a.why_not);
      }
    }
  }
  for (const PreparedState& p : PrepareMeasurements(study))
    r.measured.push_back(p.at_sensors);
  try {
    r.ranking = RankModelEffects(study.structure, r.measured, options);
  } catch (const InputError& e) {
    // The study's own fields (diagnosis.priors.*, ...): name the study file.
    if (e.where().rfind("diagnosis", 0) == 0) throw InputError(study.path, e.what());
    throw;
  }
  return r;
}

}  // namespace femup
