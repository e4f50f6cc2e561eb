// The paper's noise study (Figs. 4-5): the measured modes are corrupted at a
// series of levels, many draws per level, and the added-mass error
// Rm = |ea_est - ea| / |ea| * 100 % is summarised per factor and level.
#pragma once

#include <string>
#include <vector>

#include "femup/core/invalid.h"
#include "femup/core/progress.h"
#include "femup/studies/study.h"

namespace femup {

struct RmStatistics {
  double mean = 0, std_dev = 0, median = 0, p90 = 0;
};

// One solver's scores in a comparison (every solver sees the same noisy draws).
struct SolverScores {
  std::string label;
  std::vector<double> rm_average;  // per level: mean over factors of the mean Rm (%)
  std::vector<double> rm_median;   // per level: median over draws of the factors' mean Rm
  std::vector<int> usable_draws;   // per level
  double seconds = 0;              // total solve time
};

struct NoiseStudyResult {
  std::string study_name;
  NoiseStudySpec spec;
  std::vector<std::string> parameter_names;
  Eigen::VectorXd preset;
  std::vector<int> added_mass_indices;  // parameters with an Rm
  // rm[level][k]: statistics of added-mass factor k (in added_mass_indices order).
  std::vector<std::vector<RmStatistics>> rm;
  std::vector<double> rm_average;  // mean over factors of the mean Rm, per level
  std::vector<int> usable_draws;   // per level: draws the solver could solve
  // Estimates at spec.figure_level (or the nearest level): mean and std per parameter.
  double figure_level = 0;
  Eigen::VectorXd figure_mean, figure_std, figure_first_draw;
  // Every solver compared (the first is the one the fields above describe).
  std::vector<SolverScores> comparison;
};

// How to run a noise study; the results do not depend on any of it.
struct NoiseRunOptions {
  // Draws solved in parallel (std::threads). Every draw has its own generator
  // and its own result slot, reduced in draw order: the results are
  // bit-identical for any thread count (solve times aside).
  int threads = 1;
  // Called after each chunk of draws as (draws done, levels x draws), from the
  // worker threads; empty: no reports. See femup/progress.h.
  ProgressCallback progress;
  Invalid Validate() const;  // ok, or the field and what is wrong
};

// Runs the study described by study.noise_study (throws InputError if absent,
// and InputError "noise.threads" for invalid options). Draw d at level l uses
// its own counter-based generator, CounterRng(seed, l, d): results do not
// depend on the order of evaluation.
NoiseStudyResult RunNoiseStudy(const Study& study, const NoiseRunOptions& options = {});

}  // namespace femup
