// Private to femup_studies: what the blind benchmark's generation and running of
// cases (blind_benchmark.cc) and its scoring and report
// (blind_benchmark_scores.cc) share.
#pragma once

#include <limits>
#include <string>

#include "femup/evaluation/blind_benchmark.h"

namespace femup::blind_benchmark {

const double kNan = std::numeric_limits<double>::quiet_NaN();

// `v` with 10 significant digits.
std::string Num(double v);

// The true class: "none", or the true effects' kinds sorted and joined by "+".
std::string TruthLabel(const BenchmarkCase& c);

// No effect, or every effect's shift below the noise level (the definition
// says more).
bool AtNoiseLevel(const BenchmarkCase& c);

}  // namespace femup::blind_benchmark
