// The linear equations Z d = F for the correction factors (method.md section 2):
// the residual of each measured eigenpair, (K~ - lambda M~) phi = 0, projected
// on FEM modes Phi_i, is linear in the factors d.
#pragma once

#include <string>
#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
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

// The correction system of one model and FEM basis, prepared for many sets of
// measured modes (a noise study's draws): what does not depend on the measured
// modes is computed once (Phi' B_k on the support of each basis, Phi' K and
// Phi' M), so a set of modes costs O(modes x (FEM modes x (DOFs + basis
// supports))). BuildCorrectionSystem is Build on a fresh one. Holds a
// reference to the model, which must outlive it. Fill and Build are const and
// may run concurrently with their own work space.
class PreparedCorrectionSystem {
 public:
  // Throws InputError as BuildCorrectionSystem for the model, the FEM modes
  // and options.num_fem_modes.
  PreparedCorrectionSystem(const ParametrisedModel& model, const Modes& fem_modes,
                           const CorrectionSystemOptions& options);

  // Scratch for Fill (per mode blocks); reuse it between calls to allocate
  // nothing once sizes have settled.
  struct Workspace {
    std::vector<std::vector<Eigen::MatrixXd>> z;  // per state, per mode: nf x p
    std::vector<std::vector<Eigen::VectorXd>> f;
    Eigen::MatrixXd shapes;              // a state's shapes on every DOF (sensor layouts)
    std::vector<std::string> where;      // "measurements.<state>", per state
    Eigen::MatrixXd k_shapes, m_shapes;  // Phi' K and Phi' M times a state's shapes
  };

  // Z into *a and F into *b for `states` (resized only when their size
  // changes). Throws InputError as BuildCorrectionSystem.
  void Fill(const std::vector<ModalData>& states, Workspace* work, Eigen::MatrixXd* a,
            Eigen::VectorXd* b) const;
  // The whole problem: Fill plus names, groups and (options.row_labels) labels.
  LinearProblem Build(const std::vector<ModalData>& states) const;

 private:
  struct Projection {
    const std::vector<int>* support = nullptr;  // the basis's DOFs (the model holds them)
    Eigen::MatrixXd phi_t_b;  // nf x |support|: Phi(support, :)' B(support, support)
    ParameterKind kind;
  };
  // The rows of the summed form: one dry and one wet state (indices).
  void SummedStates(const std::vector<ModalData>& states, int* dry, int* wet) const;

  const ParametrisedModel* model_;
  CorrectionSystemOptions options_;
  int nf_ = 0;
  Eigen::MatrixXd phi_t_k_, phi_t_m_;  // nf x n: Phi' K, Phi' M
  std::vector<Projection> projections_;
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
