#include "femup/core/fe/model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"
#include "femup/core/linalg/node_ordering.h"

namespace femup {

constexpr EnumName<ParameterKind> kParameterKindNames[] = {
    {ParameterKind::kMass, "mass"},
    {ParameterKind::kStiffness, "stiffness"},
    {ParameterKind::kAddedMass, "added_mass"},
};

const char* ToString(ParameterKind kind) {
  return NameIn(kParameterKindNames, kind, "unknown");
}

bool ParameterKindFromString(const std::string& text, ParameterKind* kind) {
  return ValueIn(kParameterKindNames, text, kind);
}

namespace {

// Moves `from` into `to` without copying the basis matrix.
void MoveParameter(Parameter* from, Parameter* to) {
  to->name = std::move(from->name);
  to->kind = from->kind;
  to->basis.swap(from->basis);
  to->elements = std::move(from->elements);
  to->tags = std::move(from->tags);
}

}  // namespace

bool Parameter::HasTag(const std::string& tag) const {
  for (const auto& t : tags) {
    if (t == tag) return true;
  }
  return false;
}

bool IsSymmetric(const SparseMatrix& a, double relative_tolerance) {
  if (a.rows() != a.cols()) return false;
  double scale = 0;
  for (int k = 0; k < a.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) {
      scale = std::max(scale, std::abs(it.value()));
    }
  }
  double worst = 0;
  if (a.isCompressed()) {
    // Each stored a(r, c) against a(c, r), found by binary search in column r
    // (inner indices are sorted): O(nnz log) and no O(n) temporaries, which
    // matters for thousands of factor bases of a large model.
    const int* outer = a.outerIndexPtr();
    const int* inner = a.innerIndexPtr();
    const double* value = a.valuePtr();
    for (int c = 0; c < a.outerSize(); ++c) {
      for (int p = outer[c]; p < outer[c + 1]; ++p) {
        const int r = inner[p];
        const int* first = inner + outer[r];
        const int* last = inner + outer[r + 1];
        const int* hit = std::lower_bound(first, last, c);
        const double mirror = (hit != last && *hit == c) ? value[hit - inner] : 0.0;
        worst = std::max(worst, std::abs(value[p] - mirror));
      }
    }
    return worst <= relative_tolerance * scale;
  }
  SparseMatrix diff = SparseMatrix(a.transpose()) - a;
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
  if (!AllFinite(parameter.basis.local())) {
    throw InputError(where, "basis matrix has a NaN or infinite entry");
  }
  if (!IsSymmetric(parameter.basis.local())) {
    throw InputError(where, "basis matrix is not symmetric");
  }
  // Eigen 3.4's SparseMatrix has no move constructor, so push_back and the
  // vector's growth would copy every basis; grow by hand and swap instead.
  if (parameters_.size() == parameters_.capacity()) {
    std::vector<Parameter> grown;
    grown.reserve(std::max<std::size_t>(16, 2 * parameters_.size()));
    for (Parameter& p : parameters_) {
      grown.emplace_back();
      MoveParameter(&p, &grown.back());
    }
    parameters_.swap(grown);
  }
  parameters_.emplace_back();
  MoveParameter(&parameter, &parameters_.back());
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

std::vector<int> ParametrisedModel::DofNodes() const {
  return DofNodesFromLabels(dof_labels_);
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
  // One triplet list over the bases' entries: O(entries), not O(n) per basis.
  std::vector<Eigen::Triplet<double>> t;
  std::size_t entries = 0;
  for (int i = 0; i < num_parameters(); ++i) {
    if (parameters_[i].kind == kind && d[i] != 0.0)
      entries += static_cast<std::size_t>(parameters_[i].basis.nonZeros());
  }
  t.reserve(entries);
  for (int i = 0; i < num_parameters(); ++i) {
    if (parameters_[i].kind == kind && d[i] != 0.0)
      parameters_[i].basis.AppendTriplets(d[i], &t);
  }
  SparseMatrix sum(num_dofs(), num_dofs());
  sum.setFromTriplets(t.begin(), t.end());
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
