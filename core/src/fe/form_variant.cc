#include "femup/core/fe/form_variant.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
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

Structure RefinedModel(const Structure& model, Structure finer) {
  MatchDofs(model, finer);  // every model DOF has its place
  const double tolerance = 1e-9 * std::max(Size(model), Size(finer));
  const auto same_place = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return (a - b).cwiseAbs().maxCoeff() <= tolerance;
  };
  // Names: the model's where a model node is; "f<k>" elsewhere.
  std::map<std::string, std::string> renamed;
  for (std::size_t k = 0; k < finer.nodes.size(); ++k) {
    ModelNode& f = finer.nodes[k];
    std::string name = "f" + std::to_string(k + 1);
    for (const ModelNode& m : model.nodes) {
      if (same_place(m.xyz, f.xyz)) {
        name = m.name;
        break;
      }
    }
    renamed[f.name] = name;
    f.name = name;
  }
  for (std::string& label : finer.dof_labels) {
    const auto [node, direction] = internal::SplitDofLabel(label);
    const auto it = renamed.find(node);
    if (it != renamed.end()) label = it->second + ":" + direction;
  }
  // Attached-mass candidates: the model's nodes.
  finer.attached_mass_nodes = model.attached_mass_nodes;
  if (finer.attached_mass_nodes.empty()) {
    std::set<std::string> translating;
    for (const std::string& label : model.dof_labels) {
      const auto [node, direction] = internal::SplitDofLabel(label);
      if (!direction.empty() && direction[0] == 'u') translating.insert(node);
    }
    for (const ModelNode& m : model.nodes)
      if (translating.count(m.name)) finer.attached_mass_nodes.push_back(m.name);
  }
  // And the model's segments, each as the finer segments along it in order.
  std::vector<int> from_model;
  if (model.attached_mass_nodes.empty()) {
    for (std::size_t i = 0; i < model.segments.size(); ++i)
      from_model.push_back(static_cast<int>(i));
  } else {
    from_model = model.attached_mass_segments;
  }
  finer.attached_mass_segments.clear();
  finer.attached_mass_lines.clear();
  for (const int i : from_model) {
    const LineSegment& g = model.segments.at(static_cast<std::size_t>(i));
    const Eigen::Vector3d axis = g.b - g.a;
    const double length2 = axis.squaredNorm();
    // Fraction along g of a point on its line, or -1 off it.
    const auto along = [&](const Eigen::Vector3d& p) {
      const double t = (p - g.a).dot(axis) / length2;
      return same_place(g.a + t * axis, p) && t > -1e-9 && t < 1 + 1e-9 ? t : -1.0;
    };
    std::vector<std::pair<double, int>> pieces;
    double covered = 0;
    for (std::size_t k = 0; k < finer.segments.size(); ++k) {
      const LineSegment& f = finer.segments[k];
      const double ta = along(f.a), tb = along(f.b);
      if (ta < 0 || tb < 0 || tb <= ta) continue;
      pieces.emplace_back(ta, static_cast<int>(k));
      covered += tb - ta;
    }
    if (pieces.empty() || std::abs(covered - 1) > 1e-6) {
      throw InputError("form variant",
                       "the model's segment " + std::to_string(i + 1) +
                           " is not made of the finer model's segments, end to end");
    }
    std::sort(pieces.begin(), pieces.end());
    finer.attached_mass_lines.emplace_back();
    for (const auto& [t, k] : pieces) finer.attached_mass_lines.back().push_back(k);
  }
  return finer;
}

ModeChanges PairedModeChanges(const Structure& model, const FormVariant& variant,
                              int modes) {
  const int n = static_cast<int>(model.stiffness.rows());
  if (modes < 1 || modes > n) {
    throw InputError("form variant", "modes must be in 1.." + std::to_string(n) +
                                         ", got " + std::to_string(modes));
  }
  if (!variant.dofs.empty() && static_cast<int>(variant.dofs.size()) != n) {
    throw InputError("form variant", "dofs has " + std::to_string(variant.dofs.size()) +
                                         " entries for a model of " + std::to_string(n) +
                                         " DOFs");
  }
  EigenOptions own;
  own.num_modes = modes;
  ModeChanges out;
  out.modes = SolveModes(model.stiffness, model.mass, own);
  // A few more of the variant's, so that a mode that moved above another is
  // still there to pair.
  const int rows = static_cast<int>(variant.stiffness.rows());
  EigenOptions finer;
  finer.num_modes = std::min(rows, modes + 4);  // kAuto: dense from rows - 1
  Modes v = SolveModes(variant.stiffness, variant.mass, finer);
  auto on_model = [&] {
    return variant.dofs.empty() ? v.shapes
                                : Eigen::MatrixXd(v.shapes(variant.dofs, Eigen::all));
  };
  // The variant's equal pairs (a square frame's x and y sway modes) turned to
  // the model's modes, so that MAC pairing does not meet their arbitrary
  // rotation (the model's own is as arbitrary; the variant follows it).
  AlignRepeatedModes(out.modes.shapes, on_model(), &v);
  const Eigen::MatrixXd at_model = on_model();
  constexpr double kMinMac = 0.8;
  const std::vector<ModePair> pairs = PairModesByMac(out.modes.shapes, at_model, kMinMac);
  out.eigenvalue_change = Eigen::VectorXd::Zero(out.modes.size());
  for (const ModePair& p : pairs) {
    if (p.candidate >= 0)
      out.eigenvalue_change[p.reference] =
          v.eigenvalues[p.candidate] - out.modes.eigenvalues[p.reference];
  }
  return out;
}

FormVariant OnModelDofs(const Structure& model, const FormVariant& variant, int modes) {
  if (variant.dofs.empty()) return variant;
  const ModeChanges c = PairedModeChanges(model, variant, modes);
  const Eigen::MatrixXd mphi = model.mass * c.modes.shapes;
  const Eigen::MatrixXd dk = mphi * c.eigenvalue_change.asDiagonal() * mphi.transpose();
  FormVariant out;
  out.name = variant.name;
  out.stiffness = (model.stiffness + SparseMatrix(dk.sparseView())).pruned();
  out.mass = model.mass;
  return out;
}

}  // namespace femup
