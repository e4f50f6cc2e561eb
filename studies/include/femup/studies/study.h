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
#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/noise.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/structure.h"

namespace femup {

// Where a measured state's modes come from.
struct MeasurementSpec {
  std::string state;  // "air", "water"
  Immersion immersion = Immersion::kDry;
  int simulate_modes = 0;  // > 0: simulate this many modes from `truth`
  ModalData data;          // given modes (when simulate_modes == 0)
};

// How the factors are found: the paper's linear method (Z d = F) on a linear
// solver, or iterative eigen-sensitivity updating on a nonlinear one.
struct SolverSpec {
  std::string label;              // for comparisons ("linear", "nonlinear + prior")
  std::string method = "linear";  // "linear" or "sensitivity"
  std::string name = "lstsq";     // a linear solver, or ceres / ipopt for sensitivity
  LinearSolverOptions linear;
  NonlinearSolverOptions nonlinear;
  EigenSensitivityOptions sensitivity;  // prior_sigma there is per parameter
  // Linear method: the regularisation prior x0 per parameter (empty = zero).
  Eigen::VectorXd prior_mean;
};

struct NoiseStudySpec {
  std::vector<double> levels;  // relative corruption levels (0.05 = 5 %)
  // Shape entries are corrupted at level * shape_level_ratio (eigenvalues at level).
  double shape_level_ratio = 1.0;
  // Shape noise relative to each entry ("entry", the paper's) or to the shape's
  // largest entry ("peak": additive, the same size on every sensor).
  std::string shape_noise = "entry";
  // Solvers compared draw by draw on the same noisy data; empty = the study's solver.
  std::vector<SolverSpec> compare;
  int draws = 200;  // random draws per level
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
  // Bounds per parameter (model order; -inf / +inf where none; empty = none) and
  // linear equalities C d = e over the factors.
  Eigen::VectorXd lower, upper;
  Eigen::MatrixXd equality_matrix;
  Eigen::VectorXd equality_rhs;
  std::vector<MeasurementSpec> measurements;
  CorrectionSystemOptions system;
  SolverSpec solver;
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
