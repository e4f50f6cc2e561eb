// Several updates of one structure side by side (`femup compare`): each study
// is run as `femup run` would, and their added mass (factor per element along
// the structure, the indicator Sa of Eq. 36, kg per metre) and their updated
// frequencies are compared — e.g. the paper's Models A-E (Figs. 13(a), (b) and
// Table 2).
#pragma once

#include <string>
#include <vector>

#include "femup/studies/update_study.h"

namespace femup {

struct CompareResult {
  std::vector<std::string> paths;
  std::vector<UpdateResult> updates;  // one per study, in the given order
  // Per study: the added-mass factor of each wet element and its extent (m).
  std::vector<std::vector<double>> element_x0, element_x1, element_factor;
};

// Throws InputError for a study that cannot be read or run (naming it); a
// solve that fails is a result (its status is reported).
CompareResult RunCompare(const std::vector<std::string>& study_paths);

}  // namespace femup
