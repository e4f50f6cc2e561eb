#include "femup/core/fe/form_variant.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "femup/core/errors.h"
#include "femup/core/fe/dof_labels.h"
#include "femup/core/linalg/modal.h"

namespace femup {
namespace {

// The largest coordinate magnitude of a model's nodes (at least 1 m).
double Size(const Structure& s) {
  double size = 1.0;
  for (const ModelNode& n : s.nodes) size = std::max(size, n.xyz.cwiseAbs().maxCoeff());
  return size;
}

}  // namespace

std::vector<int> MatchDofs(const Structure& model, const Structure& finer) {
  if (model.nodes.empty() || finer.nodes.empty()) {
    throw InputError("form variant", std::string("cannot match DOFs: the ") +
                                         (model.nodes.empty() ? "model" : "finer model") +
                                         " has no node coordinates");
  }
  const double tolerance = 1e-9 * std::max(Size(model), Size(finer));
  std::map<std::string, int> finer_label;
  for (std::size_t i = 0; i < finer.dof_labels.size(); ++i)
    finer_label.emplace(finer.dof_labels[i], static_cast<int>(i));
  std::map<std::string, const ModelNode*> model_node;
  for (const ModelNode& n : model.nodes) model_node.emplace(n.name, &n);
  std::vector<int> out;
  out.reserve(model.dof_labels.size());
  for (const std::string& label : model.dof_labels) {
    const auto [node, direction] = internal::SplitDofLabel(label);
    const auto at = model_node.find(node);
    std::string match;  // the finer model's label of this DOF
    if (at == model_node.end()) {
      match = label;
    } else {
      for (const ModelNode& f : finer.nodes) {
        if ((f.xyz - at->second->xyz).cwiseAbs().maxCoeff() <= tolerance) {
          match = f.name + ":" + direction;
          break;
        }
      }
    }
    const auto found = finer_label.find(match);
    if (match.empty() || found == finer_label.end()) {
      throw InputError("form variant", "the model's DOF " + label +
                                           " has no DOF at its place in the finer model");
    }
    out.push_back(found->second);
  }
  return out;
}

FormVariant FinerMeshVariant(const Structure& model, const Structure& finer,
                             std::string name) {
  FormVariant v;
  v.name = std::move(name);
  v.stiffness = finer.stiffness;
  v.mass = finer.mass;
  v.dofs = MatchDofs(model, finer);
  return v;
}

FormVariant OnModelDofs(const Structure& model, const FormVariant& variant, int modes) {
  if (variant.dofs.empty()) return variant;
  const int n = static_cast<int>(model.stiffness.rows());
  if (modes < 1 || modes > n) {
    throw InputError("form variant", "modes must be in 1.." + std::to_string(n) +
                                         ", got " + std::to_string(modes));
  }
  if (static_cast<int>(variant.dofs.size()) != n) {
    throw InputError("form variant", "dofs has " + std::to_string(variant.dofs.size()) +
                                         " entries for a model of " + std::to_string(n) +
                                         " DOFs");
  }
  EigenOptions own;
  own.num_modes = modes;
  const Modes m = SolveModes(model.stiffness, model.mass, own);
  // A few more of the variant's, so that a mode that moved above another is
  // still there to pair.
  const int rows = static_cast<int>(variant.stiffness.rows());
  EigenOptions finer;
  finer.num_modes = std::min(rows, modes + 4);  // kAuto: dense from rows - 1
  const Modes v = SolveModes(variant.stiffness, variant.mass, finer);
  const Eigen::MatrixXd at_model = v.shapes(variant.dofs, Eigen::all);
  constexpr double kMinMac = 0.8;
  const std::vector<ModePair> pairs = PairModesByMac(m.shapes, at_model, kMinMac);
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(m.size());
  for (const ModePair& p : pairs) {
    if (p.candidate >= 0)
      shift[p.reference] = v.eigenvalues[p.candidate] - m.eigenvalues[p.reference];
  }
  const Eigen::MatrixXd mphi = model.mass * m.shapes;
  const Eigen::MatrixXd dk = mphi * shift.asDiagonal() * mphi.transpose();
  FormVariant out;
  out.name = variant.name;
  out.stiffness = (model.stiffness + SparseMatrix(dk.sparseView())).pruned();
  out.mass = model.mass;
  return out;
}

}  // namespace femup
