// femup diagnose: the sim-to-real gap of a study, located and explained by
// unmodelled effects. The cantilever has its own diagnosis (effects on the
// paper's beam); every other model type has effects as changes of the model.
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
            if (!study.cantilever) {
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
