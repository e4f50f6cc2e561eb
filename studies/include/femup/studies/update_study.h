// The linear correction-factor update (the paper's steps 1-4): FEM modes,
// Z d = F from the measured states, solve, the added-mass matrix and the
// updated model, and the comparison with measurement.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "femup/problems/linear_problem.h"
#include "femup/solvers/linear_solver.h"
#include "femup/studies/study.h"

namespace femup {

struct StateComparison {
  std::string state;
  Immersion immersion = Immersion::kDry;
  Eigen::VectorXd measured_hz;
  Eigen::VectorXd model_hz;    // nominal model (no factors), paired to each measured mode
  Eigen::VectorXd updated_hz;  // updated model, paired to each measured mode
  Eigen::VectorXd model_mac;   // MAC at the sensors (NaN without measured shapes)
  Eigen::VectorXd updated_mac;
  // Shapes for plots, at the measurement DOFs (rows) per measured mode.
  Eigen::MatrixXd measured_shapes, model_shapes, updated_shapes;
  std::vector<int> shape_dofs;  // model DOF of each shape row
};

// The identified added mass in the paper's terms and in physical units.
struct AddedMassSummary {
  bool present = false;  // the model has added-mass factors
  // Sensitivity indicator Sa (Eq. 36): the mean added-mass factor over the wet
  // elements (a group's factor counts once for each element it covers).
  double sa = 0;
  int wet_elements = 0;
  // Added mass of a rigid unit translation along the transverse DOFs ("...:ux";
  // every DOF for models without such labels): r' dMa r, kg.
  double total_kg = 0;
  double wet_length_m = 0;  // length of the wet elements (0 when unknown)
  double per_length = 0;    // total_kg / wet_length_m, kg/m
  // Eq. 2 from measured frequencies, (f_air / f_water)^2 - 1 per mode, when the
  // study has a dry and a wet state (their first modes paired by order).
  std::vector<double> eq2_coefficients;
};

struct UpdateResult {
  std::string study_name;
  std::string model_description;
  int num_dofs = 0;
  std::vector<Parameter> parameters;  // without basis matrices
  std::optional<Eigen::VectorXd> preset;
  std::vector<bool> fixed;
  std::string method = "linear";  // "linear" or "sensitivity"
  std::string solver_name;
  LinearProblem problem;  // Z, F (fixed values recorded)
  SystemForm form = SystemForm::kStacked;
  int num_fem_modes = 0;
  // True when Z d = F was weighted by all FEM modes through M^-1 and compressed
  // to one row per factor (normal_correction_system.h) instead of built from
  // the eigenbasis: a large model.
  bool normal_system = false;
  Identifiability identifiability_unconstrained;  // of the full Z, before fixing
  LinearSolution solution;
  std::vector<StateComparison> states;
  std::vector<PreparedState> sources;  // per state: identification and expansion
  AddedMassSummary added_mass_summary;
  SparseMatrix added_mass, updated_stiffness, updated_dry_mass;
  std::vector<double> dof_positions;
  std::vector<int> plot_dofs;  // Structure::plot_dofs
  std::vector<std::string> dof_labels;
};

// Runs the update. Throws InputError for unusable input; a rank-deficient or
// failed solve is reported in result.solution.summary.
UpdateResult RunUpdate(const Study& study);

}  // namespace femup
