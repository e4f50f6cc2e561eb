// femup run: the paper's method on a study (Z d = F, or the sensitivity
// method), the updated model and its comparison with the measurements.
#include "commands.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/update_study.h"

namespace femup::cli {

Command RunCommand() {
  auto o = std::make_shared<StudyOptions>();
  return {"run",
          "identify correction factors (Z d = F), build the updated model, compare",
          [o](CLI::App* cmd) {
            AddStudyOptions(cmd, o.get());
            AddSolverOverride(cmd, &o->solver);
          },
          [o](const Invocation& invocation) {
            femup::Study study = femup::LoadStudy(o->study);
            RequireMeasurements(study);
            ApplyOverride(o->solver, &study);
            const femup::UpdateResult result = femup::RunUpdate(study);
            std::vector<std::string> solved;
            for (const auto& w : result.solution.identifiability.warnings) {
              solved.push_back("solved system: " + w);
            }
            PublishStudy(invocation, "run", study, *o, result, femup::WriteUpdateOutputs,
                         femup::UpdateReport, solved);
            // An unusable solution (see SolutionSummary) is written, then exit 3.
            return result.solution.summary.usable() ? 0 : 3;
          }};
}

}  // namespace femup::cli
