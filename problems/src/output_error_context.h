// Private to femup_problems: what an output-error problem's evaluate needs
// (BuildOutputErrorProblem, eigen_sensitivity.cc): each measured state as
// prepared for evaluation, and the context shared by the problem's copies.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/linalg/modal.h"
#include "femup/problems/parametrised_pencil.h"
#include "femup/problems/ritz_basis.h"

namespace femup::output_error {

// One measured state, prepared for evaluation.
struct StateTerms {
  std::string name;
  bool wet = false;
  std::vector<int> sensors;  // model DOF of each shape row (when observe is empty)
  SparseMatrix observe;      // sensors between nodes: row i reads observe.row(i) phi
  Eigen::VectorXd lambdas;   // measured eigenvalues
  Eigen::MatrixXd shapes;    // measured shapes at the sensors (or empty)
  // The measured shapes as the residuals compare them, when shape residuals
  // are on: psi / max |psi| ("fit"), psi / ||psi|| ("unit") or psi ("mass").
  Eigen::MatrixXd targets;
  Eigen::MatrixXd shape_weights;  // 1 / standard deviation, per sensor and mode
  bool shape_residuals = false;
  std::string scaling;  // EigenSensitivityOptions::shape_scaling
  bool pair_by_mac = false;
  int num_model_modes = 0;  // model modes solved for pairing
  int first_row = 0;
  int rows_per_mode() const { return 1 + (shape_residuals ? num_sensors() : 0); }
  int num_sensors() const {
    return observe.size() > 0 ? static_cast<int>(observe.rows())
                              : static_cast<int>(sensors.size());
  }
};

// What the state's sensors read of full-DOF vectors (one per column).
inline Eigen::MatrixXd AtSensors(const StateTerms& st, const Eigen::MatrixXd& x) {
  if (st.observe.size() > 0) return st.observe * x;
  return x(st.sensors, Eigen::all);
}
inline Eigen::VectorXd AtSensors(const StateTerms& st, const Eigen::VectorXd& x) {
  if (st.observe.size() > 0) return st.observe * x;
  return x(st.sensors);
}

// Everything evaluate needs, shared by copies of the problem.
struct Context {
  std::shared_ptr<const ParametrisedPencil> pencil;
  std::vector<StateTerms> states;
  double frequency_sigma = 0;
  double min_mac = 0;
  int threads = 1;  // modes whose Jacobian rows are computed at once
  EigenOptions eigen;
  std::shared_ptr<const RitzBasis> ritz;  // null: the full model
  std::vector<int> prior_index;           // parameters with a prior
  Eigen::VectorXd prior_mean;             // n (zero when none given)
  Eigen::VectorXd prior_sigma;            // n, used at prior_index
  Eigen::MatrixXd tikhonov;               // lambda L (p x n), or empty
  int prior_first_row = 0;
  int num_residuals = 0;
};

}  // namespace femup::output_error
