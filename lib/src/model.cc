#include "femup/model.h"

#include <cmath>
#include <sstream>

#include "femup/errors.h"

namespace femup {

const char* ToString(ParameterKind kind) {
  switch (kind) {
    case ParameterKind::kMass:
      return "mass";
    case ParameterKind::kStiffness:
      return "stiffness";
    case ParameterKind::kAddedMass:
      return "added_mass";
  }
  return "unknown";
}

bool ParameterKindFromString(const std::string& text, ParameterKind* kind) {
  for (ParameterKind k :
       {ParameterKind::kMass, ParameterKind::kStiffness, ParameterKind::kAddedMass}) {
    if (text == ToString(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

bool Parameter::HasTag(const std::string& tag) const {
  for (const auto& t : tags) {
    if (t == tag) return true;
  }
  return false;
}

bool IsSymmetric(const SparseMatrix& a, double relative_tolerance) {
  if (a.rows() != a.cols()) return false;
  SparseMatrix diff = SparseMatrix(a.transpose()) - a;
  double scale = 0;
  for (int k = 0; k < a.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) {
      scale = std::max(scale, std::abs(it.value()));
    }
  }
  double worst = 0;
  for (int k = 0; k < diff.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(diff, k); it; ++it) {
      worst = std::max(worst, std::abs(it.value()));
    }
  }
  return worst <= relative_tolerance * scale;
}

bool AllFinite(const SparseMatrix& a) {
  for (int k = 0; k < a.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) {
      if (!std::isfinite(it.value())) return false;
    }
  }
  return true;
}

ParametrisedModel::ParametrisedModel(SparseMatrix stiffness, SparseMatrix mass,
                                     std::vector<std::string> dof_labels)
    : stiffness_(std::move(stiffness)),
      mass_(std::move(mass)),
      dof_labels_(std::move(dof_labels)) {
  const auto n = static_cast<Eigen::Index>(dof_labels_.size());
  if (stiffness_.rows() != n || stiffness_.cols() != n) {
    std::ostringstream msg;
    msg << "stiffness matrix is " << stiffness_.rows() << " x " << stiffness_.cols()
        << ", expected " << n << " x " << n << " (one row per DOF)";
    throw InputError("model.stiffness", msg.str());
  }
  if (mass_.rows() != n || mass_.cols() != n) {
    std::ostringstream msg;
    msg << "mass matrix is " << mass_.rows() << " x " << mass_.cols() << ", expected "
        << n << " x " << n << " (one row per DOF)";
    throw InputError("model.mass", msg.str());
  }
  if (!AllFinite(stiffness_)) {
    throw InputError("model.stiffness", "has a NaN or infinite entry");
  }
  if (!AllFinite(mass_)) throw InputError("model.mass", "has a NaN or infinite entry");
  if (!IsSymmetric(stiffness_)) {
    throw InputError("model.stiffness", "is not symmetric");
  }
  if (!IsSymmetric(mass_)) throw InputError("model.mass", "is not symmetric");
  stiffness_.makeCompressed();
  mass_.makeCompressed();
}

int ParametrisedModel::AddParameter(Parameter parameter) {
  const std::string where = "parameter '" + parameter.name + "'";
  if (parameter.name.empty()) throw InputError("parameter", "has an empty name");
  if (FindParameter(parameter.name) >= 0) {
    throw InputError(where, "is defined twice (names must be unique)");
  }
  if (parameter.basis.rows() != num_dofs() || parameter.basis.cols() != num_dofs()) {
    std::ostringstream msg;
    msg << "basis matrix is " << parameter.basis.rows() << " x " << parameter.basis.cols()
        << ", expected " << num_dofs() << " x " << num_dofs();
    throw InputError(where, msg.str());
  }
  if (!AllFinite(parameter.basis)) {
    throw InputError(where, "basis matrix has a NaN or infinite entry");
  }
  if (!IsSymmetric(parameter.basis)) {
    throw InputError(where, "basis matrix is not symmetric");
  }
  parameter.basis.makeCompressed();
  parameters_.push_back(std::move(parameter));
  return num_parameters() - 1;
}

int ParametrisedModel::FindParameter(const std::string& name) const {
  for (int i = 0; i < num_parameters(); ++i) {
    if (parameters_[i].name == name) return i;
  }
  return -1;
}

std::vector<int> ParametrisedModel::ParametersOfKind(ParameterKind kind) const {
  std::vector<int> out;
  for (int i = 0; i < num_parameters(); ++i) {
    if (parameters_[i].kind == kind) out.push_back(i);
  }
  return out;
}

std::vector<std::string> ParametrisedModel::ParameterNames() const {
  std::vector<std::string> out;
  out.reserve(parameters_.size());
  for (const auto& p : parameters_) out.push_back(p.name);
  return out;
}

int ParametrisedModel::FindDof(const std::string& label) const {
  for (int i = 0; i < num_dofs(); ++i) {
    if (dof_labels_[i] == label) return i;
  }
  return -1;
}

void ParametrisedModel::CheckFactors(const Eigen::VectorXd& d) const {
  if (d.size() != num_parameters()) {
    std::ostringstream msg;
    msg << "factor vector has " << d.size() << " entries, the model has "
        << num_parameters() << " parameters";
    throw InputError("factors", msg.str());
  }
  if (!d.allFinite()) throw InputError("factors", "has a NaN or infinite entry");
}

SparseMatrix ParametrisedModel::Sum(ParameterKind kind, const Eigen::VectorXd& d) const {
  CheckFactors(d);
  SparseMatrix sum(num_dofs(), num_dofs());
  for (int i = 0; i < num_parameters(); ++i) {
    if (parameters_[i].kind == kind && d[i] != 0.0) sum += d[i] * parameters_[i].basis;
  }
  return sum;
}

SparseMatrix ParametrisedModel::UpdatedStiffness(const Eigen::VectorXd& d) const {
  return stiffness_ + Sum(ParameterKind::kStiffness, d);
}

SparseMatrix ParametrisedModel::UpdatedDryMass(const Eigen::VectorXd& d) const {
  return mass_ + Sum(ParameterKind::kMass, d);
}

SparseMatrix ParametrisedModel::AddedMass(const Eigen::VectorXd& d) const {
  return Sum(ParameterKind::kAddedMass, d);
}

SparseMatrix ParametrisedModel::UpdatedWetMass(const Eigen::VectorXd& d) const {
  return UpdatedDryMass(d) + AddedMass(d);
}

}  // namespace femup
