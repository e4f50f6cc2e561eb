// femup: the command line. Each subcommand reads its input (a study file or
// data files), runs one pipeline from studies/, and writes its JSON, matrices
// and plots into an output folder all at once (nothing is left behind when a
// run fails). The subcommands are the table below, one file each under
// app/commands/; what they share is app/command.h.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands/commands.h"
#include "femup/core/errors.h"
#include "femup/core/linalg/blas.h"

namespace femup::cli {
namespace {

// The commands, in the order `femup --help` lists them.
std::vector<Command> Commands() {
  return {RunCommand(),      NoiseCommand(),     ModesCommand(),   SimulateCommand(),
          DiagnoseCommand(), BenchmarkCommand(), CompareCommand(), CheckCommand(),
          SolveCommand(),    IdentifyCommand(),  InfoCommand()};
}

}  // namespace
}  // namespace femup::cli

int main(int argc, char** argv) {
  // OpenBLAS's kernels for this processor where Debian's OpenBLAS does not
  // know it, and one BLAS thread per caller: femup parallelises above the
  // BLAS, with results that do not depend on `--threads`
  // (femup/core/linalg/blas.h).
  femup::SetUpBlasForProgram(argv);
  CLI::App app{
      "femup: find where a finite element model is wrong, and by how much, from "
      "vibration measurements"};
  app.require_subcommand(1);
  app.set_version_flag("--version", [] {
    return std::string(femup::cli::kVersion) + "\n" + femup::BlasSummary();
  });
  const femup::cli::Invocation invocation{femup::cli::QuotedCommandLine(argc, argv)};

  const std::vector<femup::cli::Command> commands = femup::cli::Commands();
  std::vector<CLI::App*> subcommands;
  for (const femup::cli::Command& command : commands) {
    CLI::App* sub = app.add_subcommand(command.name, command.description);
    command.add_options(sub);
    subcommands.push_back(sub);
  }

  CLI11_PARSE(app, argc, argv);

  // Exit codes: 0 done, 1 bad input, 3 a result not usable (the command's
  // own, or a numerical failure on valid input), 4 a bug; CLI11's own for a
  // bad command line.
  try {
    for (std::size_t i = 0; i < commands.size(); ++i) {
      if (*subcommands[i]) return commands[i].run(invocation);
    }
  } catch (const femup::InputError& e) {
    std::cerr << "femup: error: " << e.what() << "\n";
    return 1;
  } catch (const femup::NumericalError& e) {
    // Valid input on which a numerical method failed (an eigensolver that did
    // not converge): no usable result, as for a solver that failed.
    std::cerr << "femup: numerical failure: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "femup: internal error: " << e.what() << "\n";
    return 4;
  }
  return 0;
}
