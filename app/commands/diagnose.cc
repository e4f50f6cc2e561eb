// femup diagnose: the sim-to-real gap of a study, located and explained by
// unmodelled effects as changes of the model (every model type, the default),
// or, on a cantilever whose diagnosis.engine is cantilever, by its own
// pipeline (effects on the paper's beam).
#include "commands.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/diagnose_study.h"
#include "femup/studies/structure_diagnosis.h"

namespace femup::cli {

Command DiagnoseCommand() {
  auto o = std::make_shared<StudyOptions>();
  return {"diagnose",
          "the sim-to-real gap: where it lies, which unmodelled effect causes it "
          "(ranked, with probabilities), how far it shrinks on fitted and held-out "
          "modes",
          [o](CLI::App* cmd) { AddStudyOptions(cmd, o.get()); },
          [o](const Invocation& invocation) {
            const femup::Study study = femup::LoadStudy(o->study);
            RequireMeasurements(study);
            const femup::DiagnosisSpec spec =
                study.diagnosis.value_or(femup::DiagnosisSpec());
            if (spec.Engine() == "model_effects") {
              const femup::StructureDiagnosisResult result =
                  femup::RunStructureDiagnosis(study);
              PublishStudy(invocation, "diagnose", study, *o, result,
                           femup::WriteStructureDiagnosisOutputs,
                           femup::StructureDiagnosisReport);
              return 0;
            }
            const femup::DiagnosisResult result = femup::RunDiagnosis(study);
            PublishStudy(invocation, "diagnose", study, *o, result,
                         femup::WriteDiagnosisOutputs, femup::DiagnosisReport);
            return 0;
          }};
}

}  // namespace femup::cli
