// femup compare: several studies of one structure side by side (added mass
// along the structure, Sa, updated frequencies).
#include "commands.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/compare_study.h"

namespace femup::cli {

namespace {

struct CompareOptions {
  std::vector<std::string> studies;
  OutputOptions output;
};

}  // namespace

Command CompareCommand() {
  auto o = std::make_shared<CompareOptions>();
  return {
      "compare",
      "run several studies of one structure and compare their added mass "
      "(factors along the structure, Sa) and updated frequencies",
      [o](CLI::App* cmd) {
        cmd->add_option("studies", o->studies, "study files (two or more)")->required();
        AddOutputOptions(cmd, &o->output, "JSON", "out/compare");
      },
      [o](const Invocation& invocation) {
        const femup::CompareResult result = femup::RunCompare(o->studies);
        Publish(invocation,
                RunInfo{"compare", std::to_string(o->studies.size()) + " studies",
                        o->studies},
                o->output.out, !o->output.no_plots, o->output.quiet, result,
                femup::WriteCompareOutputs, femup::CompareReport);
        return 0;
      }};
}

}  // namespace femup::cli
