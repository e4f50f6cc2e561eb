// ParametrisedPencil: what an output-error fit of measured modes varies — the
// stiffness K(x) and the mass M(x) of a state (dry or wet) as functions of the
// unknowns x, with their derivatives dK/dx_p, dM/dx_p. The one output-error
// engine (eigen_sensitivity.h: pairing, residuals on frequencies and on shapes
// at sensors, analytic eigenvalue and Nelson eigenvector derivatives) takes any
// pencil, so the same code fits
//   - correction factors of a ParametrisedModel (linear in x: the iterative
//     eigen-sensitivity updating), ModelPencil below;
//   - unmodelled effects as changes of a structure (model_effects.h: nonlinear
//     in x), ModelEffectPencil (model_effect_pencil.h).
#pragma once

#include <Eigen/Core>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/fe/basis_matrix.h"
#include "femup/core/fe/model.h"

namespace femup {

// The derivatives of K and M with respect to every unknown at one x, for one
// state: null where the unknown does not change that matrix. The pointers point
// into the pencil itself or into `storage`.
struct PencilDerivatives {
  std::vector<const BasisMatrix*> stiffness, mass;
  std::deque<BasisMatrix> storage;  // stable addresses
};

class ParametrisedPencil {
 public:
  virtual ~ParametrisedPencil() = default;
  virtual int num_parameters() const = 0;
  virtual const std::vector<std::string>& dof_labels() const = 0;
  int num_dofs() const { return static_cast<int>(dof_labels().size()); }
  // Names and groups ("mass", "stiffness", an effect's kind) of the unknowns.
  virtual std::vector<std::string> ParameterNames() const = 0;
  virtual std::vector<std::string> ParameterGroups() const = 0;
  // K(x) and the state's M(x). Throws InputError when x is not usable.
  virtual void Assemble(const Eigen::VectorXd& x, bool wet, SparseMatrix* stiffness,
                        SparseMatrix* mass) const = 0;
  // dK/dx and dM/dx at x for the state.
  virtual void Derivatives(const Eigen::VectorXd& x, bool wet,
                           PencilDerivatives* out) const = 0;
};

// A ParametrisedModel's correction factors: K = K0 + sum d_b K_b, M_dry = M0 +
// sum d_a M_a, M_wet = M_dry + sum d_w Mw_w (model.h). The derivatives are the
// basis matrices themselves (added mass only in wet states).
class ModelPencil : public ParametrisedPencil {
 public:
  explicit ModelPencil(ParametrisedModel model) : model_(std::move(model)) {}
  const ParametrisedModel& model() const { return model_; }
  int num_parameters() const override { return model_.num_parameters(); }
  const std::vector<std::string>& dof_labels() const override {
    return model_.dof_labels();
  }
  std::vector<std::string> ParameterNames() const override;
  std::vector<std::string> ParameterGroups() const override;
  void Assemble(const Eigen::VectorXd& x, bool wet, SparseMatrix* stiffness,
                SparseMatrix* mass) const override;
  void Derivatives(const Eigen::VectorXd& x, bool wet,
                   PencilDerivatives* out) const override;

 private:
  ParametrisedModel model_;
};

}  // namespace femup
