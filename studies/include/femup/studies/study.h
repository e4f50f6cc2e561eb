// A study file (YAML; JSON is accepted, being YAML) describes one job: the
// model, its correction factors, the measured states, the linear system and
// the solver, and optional noise and output settings. LoadStudy reads and
// checks all of it before any work is done; every error names the file, the
// line and the field.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "femup/measurement.h"
#include "femup/model.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/noise.h"
#include "femup/solvers/linear_solver.h"
#include "femup/structure.h"

namespace femup {

// Where a measured state's modes come from.
struct MeasurementSpec {
  std::string state;  // "air", "water"
  Immersion immersion = Immersion::kDry;
  int simulate_modes = 0;  // > 0: simulate this many modes from `truth`
  ModalData data;          // given modes (when simulate_modes == 0)
};

struct NoiseStudySpec {
  std::vector<double> levels;  // relative corruption levels (0.05 = 5 %)
  int draws = 200;             // random draws per level
  unsigned long long seed = 1;
  NoiseDistribution distribution = NoiseDistribution::kGaussian;
  double figure_level = 0.05;  // level shown in the estimated-vs-preset figure
};

struct Study {
  std::string path;  // the study file
  std::string name;
  std::string description;
  Structure structure;
  ParametrisedModel model;
  std::optional<Eigen::VectorXd> truth;  // preset factors (model order), if given
  std::map<std::string, double> fixed;   // known factor values by name
  std::vector<MeasurementSpec> measurements;
  CorrectionSystemOptions system;
  std::string solver_name = "lstsq";
  LinearSolverOptions solver_options;
  std::optional<NoiseStudySpec> noise_study;
  bool plots = true;
};

// Reads and checks a study file. Throws InputError naming file, line and field
// for a missing file, a syntax error, an unknown key, a wrong type or size, a
// NaN, a non-positive-definite mass, shapes that do not match the sensors, or
// a name that matches no parameter.
Study LoadStudy(const std::string& path);

// The measured states: given ones as they are, simulated ones from the truth.
std::vector<ModalData> MeasuredStates(const Study& study);

}  // namespace femup
