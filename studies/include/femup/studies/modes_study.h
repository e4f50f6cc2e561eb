// Modal analysis of a study's model: the nominal model in air (dry) and, when
// it has wet elements and a truth, the "real" structure's modes per state.
#pragma once

#include <string>
#include <vector>

#include "femup/core/linalg/modal.h"
#include "femup/studies/study.h"

namespace femup {

struct ModesResult {
  std::string study_name;
  std::string model_description;
  Modes nominal;  // lowest modes of (K, M)
  std::vector<std::string> dof_labels;
  std::vector<double> dof_positions;
  double max_residual = 0;             // max_j ||K phi - lambda M phi|| / ||K phi||
  double max_orthogonality_error = 0;  // max |Phi' M Phi - I|
};

// `num_modes` <= 0: every mode for models up to 1500 DOFs, else 10.
ModesResult RunModes(const Study& study, int num_modes);

}  // namespace femup
