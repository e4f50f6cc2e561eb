#include "femup/problems/parametrised_pencil.h"

namespace femup {

std::vector<std::string> ModelPencil::ParameterNames() const {
  return model_.ParameterNames();
}

std::vector<std::string> ModelPencil::ParameterGroups() const {
  std::vector<std::string> groups;
  for (const Parameter& p : model_.parameters()) groups.push_back(ToString(p.kind));
  return groups;
}

void ModelPencil::Assemble(const Eigen::VectorXd& x, bool wet, SparseMatrix* stiffness,
                           SparseMatrix* mass) const {
  *stiffness = model_.UpdatedStiffness(x);
  *mass = wet ? model_.UpdatedWetMass(x) : model_.UpdatedDryMass(x);
}

void ModelPencil::Derivatives(const Eigen::VectorXd&, bool wet,
                              PencilDerivatives* out) const {
  const int n = model_.num_parameters();
  out->stiffness.assign(n, nullptr);
  out->mass.assign(n, nullptr);
  out->storage.clear();
  for (int p = 0; p < n; ++p) {
    const Parameter& parameter = model_.parameter(p);
    switch (parameter.kind) {
      case ParameterKind::kStiffness:
        out->stiffness[p] = &parameter.basis;
        break;
      case ParameterKind::kMass:
        out->mass[p] = &parameter.basis;
        break;
      case ParameterKind::kAddedMass:
        if (wet) out->mass[p] = &parameter.basis;
        break;
    }
  }
}

}  // namespace femup
