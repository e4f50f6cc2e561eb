// ParametrisedModel: a baseline finite element model (sparse K and M on the free
// DOFs) plus named correction factors, each scaling one sparse symmetric basis
// matrix. With factors d:
//   K~     = K + sum_b d_b K_b               (kind kStiffness)
//   M~dry  = M + sum_a d_a M_a               (kind kMass)
//   dMa    =     sum_w d_w Mw_w              (kind kAddedMass)
//   M~wet  = M~dry + dMa
// Units are the caller's, consistently (SI throughout femup's builders).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "femup/core/fe/basis_matrix.h"

namespace femup {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, symmetric where stated

enum class ParameterKind { kMass, kStiffness, kAddedMass };

// "mass", "stiffness", "added_mass".
const char* ToString(ParameterKind kind);
// Returns false when `text` names no kind.
bool ParameterKindFromString(const std::string& text, ParameterKind* kind);

struct Parameter {
  std::string name;  // unique, readable: "mass[3]", "stiffness[e7]", "added_mass[e2]"
  ParameterKind kind = ParameterKind::kMass;
  BasisMatrix basis;              // num_dofs x num_dofs, symmetric, held on its DOFs
  std::vector<int> elements;      // element ids the factor covers (may be empty)
  std::vector<std::string> tags;  // e.g. "wet", "dry", "element:3", "region:splash"
  bool HasTag(const std::string& tag) const;
};

class ParametrisedModel {
 public:
  ParametrisedModel() = default;
  // K and M: square, same size, symmetric; dof_labels: one per DOF ("n3:ux").
  // Throws InputError when sizes disagree or an entry is not finite.
  ParametrisedModel(SparseMatrix stiffness, SparseMatrix mass,
                    std::vector<std::string> dof_labels);

  int num_dofs() const { return static_cast<int>(dof_labels_.size()); }
  int num_parameters() const { return static_cast<int>(parameters_.size()); }
  const SparseMatrix& stiffness() const { return stiffness_; }
  const SparseMatrix& mass() const { return mass_; }
  const std::vector<std::string>& dof_labels() const { return dof_labels_; }
  const std::vector<Parameter>& parameters() const { return parameters_; }
  const Parameter& parameter(int i) const { return parameters_.at(i); }

  // Adds a parameter; returns its index. Throws InputError on a duplicate name,
  // a basis of the wrong size, an asymmetric basis or a non-finite entry.
  int AddParameter(Parameter parameter);
  // Index of the parameter called `name`, or -1.
  int FindParameter(const std::string& name) const;
  std::vector<int> ParametersOfKind(ParameterKind kind) const;
  std::vector<std::string> ParameterNames() const;
  // Index of the DOF labelled `label`, or -1.
  int FindDof(const std::string& label) const;
  // The node of each DOF, numbered 0, 1, ... in order of first appearance: DOFs
  // whose labels share the part before ':' ("n3:ux", "n3:rz") share a node; a
  // label without ':' is a node of its own. Sparse factorisations order the
  // node graph with it (SparseCholeskyOptions::groups).
  std::vector<int> DofNodes() const;

  // Assembled matrices for a factor vector d (size num_parameters()).
  SparseMatrix UpdatedStiffness(const Eigen::VectorXd& d) const;
  SparseMatrix UpdatedDryMass(const Eigen::VectorXd& d) const;
  SparseMatrix AddedMass(const Eigen::VectorXd& d) const;  // dMa (Eq. 32-33)
  SparseMatrix UpdatedWetMass(const Eigen::VectorXd& d) const;

 private:
  SparseMatrix Sum(ParameterKind kind, const Eigen::VectorXd& d) const;
  void CheckFactors(const Eigen::VectorXd& d) const;

  SparseMatrix stiffness_;
  SparseMatrix mass_;
  std::vector<std::string> dof_labels_;
  std::vector<Parameter> parameters_;
};

// True when A is symmetric to a relative tolerance (max |A - A'| <= tol max |A|).
bool IsSymmetric(const SparseMatrix& a, double relative_tolerance = 1e-10);
// True when every stored entry is finite.
bool AllFinite(const SparseMatrix& a);

}  // namespace femup
