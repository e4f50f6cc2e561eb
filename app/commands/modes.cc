// femup modes: modal analysis of a study's nominal model.
#include "commands.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/modes_study.h"

namespace femup::cli {

namespace {

struct ModesOptions {
  StudyOptions study;
  int num_modes = 0;
};

}  // namespace

Command ModesCommand() {
  auto o = std::make_shared<ModesOptions>();
  return {"modes", "modal analysis of the study's nominal model",
          [o](CLI::App* cmd) {
            AddStudyOptions(cmd, &o->study);
            cmd->add_option("-n,--modes", o->num_modes,
                            "number of lowest modes (default: all, or 10)");
          },
          [o](const Invocation& invocation) {
            const femup::Study study = femup::LoadStudy(o->study.study);
            const femup::ModesResult result = femup::RunModes(study, o->num_modes);
            PublishStudy(invocation, "modes", study, o->study, result,
                         femup::WriteModesOutputs, femup::ModesReport);
            return 0;
          }};
}

}  // namespace femup::cli
