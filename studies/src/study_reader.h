// Private to femup_studies: the readers of a study file's sections that
// study.cc (ReadStudy) calls, each defined in the study_reader_*.cc file of its
// concept (models, diagnosis, measurements, parameters and solver).
#pragma once

#include <string>
#include <vector>

#include "femup/studies/study.h"
#include "study_reader_field.h"

namespace femup::study_reader {

// study_reader_models.cc: the model section, one reader per model type.
Structure ReadChain(const Field& m);
Structure ReadCantilever(const Field& m, CantileverSpec* out);
Structure ReadMatrixMarketModel(const Field& m);
Structure ReadPlaneFrame(const Field& m);
ParametrisedModel ReadSpaceFrame(const Field& m, Structure* structure);
void CheckMassPositiveDefinite(const Field& model_field, const ParametrisedModel& model);

// study_reader_diagnosis.cc: the diagnosis section, checked against the
// study's model.
DiagnosisSpec ReadDiagnosis(const Field& f, const Study& study);

// study_reader_measurements.cc: the records to simulate and the measured states.
RecordsSpec ReadRecords(const Field& f, const ParametrisedModel& model);
MeasurementSpec ReadMeasurement(const Field& f, const ParametrisedModel& model,
                                bool have_truth, const Structure& structure);

// study_reader_solver.cc: parameter families and bounds, the solver section.
ParameterFamily ReadFamily(const Field& f);
double BoundValue(const Field& f);
SolverSpec ReadSolver(const Field& sf, const ParametrisedModel& model);

// A value per parameter from a mapping whose keys are parameter kinds ("mass",
// "stiffness", "added_mass": every parameter of that kind) or parameter names
// (which override their kind). `read` turns one value field into a number pair.
// (A template, so here: study.cc reads bounds and truth with it,
// study_reader_solver.cc prior_mean and prior_sigma.)
template <typename Read>
void ForEachParameterKey(const Field& f, const ParametrisedModel& model, Read read) {
  if (!f.IsMap()) f.Fail("expected a mapping of parameter names or kinds to values");
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& kv : f.node()) {
      const std::string key = f.Key(kv.first);
      const Field value(kv.second, f.file(), f.path() + "." + key);
      ParameterKind kind;
      const bool is_kind = ParameterKindFromString(key, &kind);
      if (pass == 0 && is_kind) {
        for (int i : model.ParametersOfKind(kind)) read(value, i);
      } else if (pass == 1 && !is_kind) {
        const int i = model.FindParameter(key);
        if (i < 0) {
          std::string names;
          for (const auto& n : model.ParameterNames())
            names += (names.empty() ? "" : ", ") + n;
          value.Fail("no parameter or kind is called '" + key +
                     "' (kinds: mass, stiffness, added_mass; parameters: " + names + ")");
        }
        read(value, i);
      }
    }
  }
}

}  // namespace femup::study_reader
