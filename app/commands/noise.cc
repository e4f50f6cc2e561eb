// femup noise: the noise study of a study file (the added-mass factors'
// spread as the data are corrupted).
#include "commands.h"
#include "femup/core/errors.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/noise_study.h"

namespace femup::cli {

namespace {

struct NoiseOptions {
  StudyOptions study;
  femup::NoiseRunOptions run;
};

}  // namespace

Command NoiseCommand() {
  auto o = std::make_shared<NoiseOptions>();
  return {"noise", "the noise study: Rm of the added-mass factors vs corruption",
          [o](CLI::App* cmd) {
            AddStudyOptions(cmd, &o->study);
            AddSolverOverride(cmd, &o->study.solver);
            o->run.threads = 2;
            cmd->add_option("--threads", o->run.threads,
                            "draws solved in parallel (default 2); the results are "
                            "identical for any number");
          },
          [o](const Invocation& invocation) {
            if (const femup::Invalid bad = o->run.Validate())
              throw femup::InputError("--" + bad.field, bad.message);
            femup::Study study = femup::LoadStudy(o->study.study);
            RequireMeasurements(study);
            ApplyOverride(o->study.solver, &study);
            if (!study.noise_study) {
              throw femup::InputError(o->study.study,
                                      "noise_study: the study has no noise_study "
                                      "section (levels, draws, seed)");
            }
            femup::NoiseStudyResult result;
            {
              const auto bar = MakeProgressBar("noise draws", o->study.output.quiet);
              o->run.progress = bar->Callback();
              result = femup::RunNoiseStudy(study, o->run);
              o->run.progress = nullptr;  // the bar goes now
            }
            PublishStudy(invocation, "noise", study, o->study, result,
                         femup::WriteNoiseOutputs, femup::NoiseReport);
            return 0;
          }};
}

}  // namespace femup::cli
