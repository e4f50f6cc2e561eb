// Simulated test records (`femup simulate`): the structure a study describes,
// with its `truth` factors and, per state, strip-theory water, struck by an
// impulse and recorded at the sensors (accelerations, modal damping, noise).
// One UFF 58 or CSV file per state, and truth.json with the modes the records
// hold, so that identification and updating can be checked against a known
// answer.
#pragma once

#include <string>
#include <vector>

#include "femup/core/sysid/time_response.h"
#include "femup/studies/study.h"

namespace femup {

struct SimulatedState {
  RecordStateSpec spec;
  TimeResponse response;             // channels x samples
  std::vector<std::string> sensors;  // DOF label per channel
  // The modes in the records (those below the cut-off): frequency, damping
  // ratio, shape at the sensors (largest entry 1).
  Eigen::VectorXd frequencies_hz, damping_ratios;
  Eigen::MatrixXd shapes;
  double cutoff_hz = 0;              // modes above it are not in the records
  double added_mass_per_length = 0;  // strip theory, kg/m (0 without water)
  double added_mass_coefficient = 0;
  double structural_mass_per_length = 0;  // rho A of the first element, kg/m
};

struct SimulateResult {
  std::string study_name;
  std::string description;
  double sample_rate_hz = 0;
  int impulse_dof = -1;
  std::string impulse_label;
  std::vector<SimulatedState> states;
};

// Throws InputError when the study has no `records` section or the records
// cannot be made (strip-theory water on a structure that is not a cantilever).
SimulateResult RunSimulate(const Study& study);

}  // namespace femup
