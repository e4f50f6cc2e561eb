// The commands of femup, one factory per file of app/commands/; app/main.cc
// lists them, in the order `femup --help` shows them.
#pragma once

#include "../command.h"

namespace femup::cli {

Command RunCommand();        // run.cc
Command NoiseCommand();      // noise.cc
Command ModesCommand();      // modes.cc
Command SimulateCommand();   // simulate.cc
Command DiagnoseCommand();   // diagnose.cc
Command BenchmarkCommand();  // benchmark.cc
Command CompareCommand();    // compare.cc
Command CheckCommand();      // check.cc
Command SolveCommand();      // solve.cc
Command IdentifyCommand();   // identify.cc
Command InfoCommand();       // info.cc

}  // namespace femup::cli
