// ModelEffectPencil: a structure changed by a set of unmodelled effects
// (model_effects.h) as a pencil of the one output-error engine
// (parametrised_pencil.h, BuildOutputErrorProblem in eigen_sensitivity.h): the
// unknowns are the effects' parameters, concatenated in the given order, named
// "<kind>[<region>].<parameter>" and grouped by kind; K and M are the
// structure's plus every effect's change, with exact derivatives.
//
// BuildModelEffectFitProblem adds the effects' prior ranges as bounds: the fit
// that `femup diagnose` runs for each candidate class, on any structure.
#pragma once

#include <memory>
#include <vector>

#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/model_effects.h"
#include "femup/problems/parametrised_pencil.h"

namespace femup {

class ModelEffectPencil : public ParametrisedPencil {
 public:
  // The effects must have been made for `structure` (CreateModelEffects on it);
  // the pencil keeps both alive. Throws InputError when there is no effect.
  ModelEffectPencil(std::shared_ptr<const Structure> structure,
                    std::vector<std::shared_ptr<const ModelEffect>> effects);
  int num_parameters() const override { return num_parameters_; }
  const std::vector<std::string>& dof_labels() const override {
    return structure_->dof_labels;
  }
  std::vector<std::string> ParameterNames() const override;
  std::vector<std::string> ParameterGroups() const override;
  void Assemble(const Eigen::VectorXd& x, bool wet, SparseMatrix* stiffness,
                SparseMatrix* mass) const override;
  void Derivatives(const Eigen::VectorXd& x, bool wet,
                   PencilDerivatives* out) const override;
  // The prior ranges, concatenated.
  Eigen::VectorXd Lower() const;
  Eigen::VectorXd Upper() const;

 private:
  std::vector<Eigen::VectorXd> Split(const Eigen::VectorXd& x) const;
  std::shared_ptr<const Structure> structure_;
  std::vector<std::shared_ptr<const ModelEffect>> effects_;
  std::vector<int> offset_;  // first unknown of each effect
  int num_parameters_ = 0;
};

// The output-error fit of `effects` on `structure` to the measured states
// (sensor DOFs index the structure's DOFs), bounded by the prior ranges,
// starting at `start` (empty: the first start of every effect).
NonlinearProblem BuildModelEffectFitProblem(
    std::shared_ptr<const Structure> structure,
    std::vector<std::shared_ptr<const ModelEffect>> effects,
    const std::vector<ModalData>& states, const EigenSensitivityOptions& options,
    const Eigen::VectorXd& start = {});

}  // namespace femup
