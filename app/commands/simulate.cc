// femup simulate: test records of a study's structure, as a test would give
// them, with the truth kept beside.
#include "commands.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/simulate_study.h"

namespace femup::cli {

Command SimulateCommand() {
  auto o = std::make_shared<StudyOptions>();
  return {"simulate",
          "test records of the study's structure (its truth factors, strip-theory "
          "water): impulse responses at the sensors as UFF 58 or CSV, with truth.json",
          [o](CLI::App* cmd) { AddStudyOptions(cmd, o.get()); },
          [o](const Invocation& invocation) {
            const femup::Study study = femup::LoadStudy(o->study);
            const femup::SimulateResult result = femup::RunSimulate(study);
            PublishStudy(invocation, "simulate", study, *o, result,
                         femup::WriteSimulateOutputs, femup::SimulateReport);
            return 0;
          }};
}

}  // namespace femup::cli
