// The linear equations Z d = F for the correction factors (method.md section 2):
// the residual of each measured eigenpair, (K~ - lambda M~) phi = 0, projected
// on FEM modes Phi_i, is linear in the factors d.
#pragma once

#include <string>
#include <vector>

#include "femup/measurement.h"
#include "femup/modal.h"
#include "femup/model.h"
#include "femup/problems/linear_problem.h"

namespace femup {

enum class SystemForm {
  kStacked,  // one row per (FEM mode i, measured mode j) in each state
  kSummed,   // the paper's Eq. 20-31: one row per (i, air mode j, water mode p)
};
const char* ToString(SystemForm form);  // "stacked", "summed"
bool SystemFormFromString(const std::string& text, SystemForm* form);

struct CorrectionSystemOptions {
  SystemForm form = SystemForm::kStacked;
  int num_fem_modes = -1;  // -1: every FEM mode given; otherwise the first k
  // false: no row_labels on the problem (repeated builds nobody reads them from,
  // e.g. a noise study's draws); A, b, names and groups are the same.
  bool row_labels = true;
};

// Builds Z and F. `fem_modes` are M-normalised modes of the baseline (K, M);
// `states` hold measured modes with shapes on every model DOF (dry states see
// M~dry, wet states M~wet). Added-mass columns are zero in dry rows.
// The summed form needs exactly one dry and one wet state. Throws InputError
// on size mismatches, incomplete shapes, or a form the states do not allow.
LinearProblem BuildCorrectionSystem(const ParametrisedModel& model,
                                    const Modes& fem_modes,
                                    const std::vector<ModalData>& states,
                                    const CorrectionSystemOptions& options);

}  // namespace femup
