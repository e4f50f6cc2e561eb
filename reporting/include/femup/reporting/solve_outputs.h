// What a person reads of a linear inverse problem solved from files (`femup solve`): the
// files written into the command's output folder and the summary the terminal prints. The
// pipeline (femup/studies/solve_study.h) returns the result; this layer writes it.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/studies/solve_study.h"

namespace femup {

void WriteSolveOutputs(const SolveResult& result, bool plots, OutputDir* out,
                       std::vector<std::string>* warnings);
std::string SolveReport(const SolveResult& result);

}  // namespace femup
