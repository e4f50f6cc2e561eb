// femup identify: modes from measured signals (ERA with a stabilisation
// diagram).
#include "commands.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/identify_study.h"

namespace femup::cli {

namespace {

struct IdentifyCommandOptions {
  femup::IdentifyOptions identify;
  OutputOptions output;
};

void AddOptions(CLI::App* cmd, IdentifyCommandOptions* o) {
  femup::IdentifyOptions& id = o->identify;
  cmd->add_option("file", id.file, "UFF (.uff, .unv) or CSV (.csv) file")->required();
  cmd->add_option("--format", id.format, "uff or csv (default: by extension)");
  cmd->add_option("--min-order", id.stabilisation.min_order,
                  "lowest model order (default 2)");
  cmd->add_option("--max-order", id.stabilisation.max_order,
                  "highest model order (default 40)");
  cmd->add_option("--order-step", id.stabilisation.order_step, "order step (default 2)");
  cmd->add_option("--stable-orders", id.min_consecutive,
                  "consecutive stable orders a mode needs (default 5)");
  cmd->add_option("--max-frequency", id.max_frequency_hz,
                  "report modes below this frequency, Hz (default Nyquist)");
  cmd->add_option("--first-sample", id.stabilisation.era.first_sample,
                  "first sample used by ERA (default 1: skips the impulse instant)");
  AddOutputOptions(cmd, &o->output, "JSON", "out/identify");
}

int Run(const Invocation& invocation, const IdentifyCommandOptions& o) {
  const femup::IdentifyResult result = femup::RunIdentify(o.identify);
  const auto write = [](const femup::IdentifyResult& r, bool plots, femup::OutputDir* dir,
                        std::vector<std::string>* warnings) {
    femup::WriteIdentifyOutputs(r, plots, dir, warnings);
  };
  Publish(invocation, RunInfo{"identify", o.identify.file, {o.identify.file}},
          o.output.out, !o.output.no_plots, o.output.quiet, result, write,
          femup::IdentifyReport);
  return result.modes.empty() ? 3 : 0;  // no stable mode found: written, then exit 3
}

}  // namespace

Command IdentifyCommand() {
  auto o = std::make_shared<IdentifyCommandOptions>();
  return {"identify",
          "modes from measured signals: ERA with a stabilisation diagram on a UFF 58 "
          "file (time histories or FRFs) or a CSV time series",
          [o](CLI::App* cmd) { AddOptions(cmd, o.get()); },
          [o](const Invocation& invocation) { return Run(invocation, *o); }};
}

}  // namespace femup::cli
