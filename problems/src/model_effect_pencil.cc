#include "femup/problems/model_effect_pencil.h"

#include "femup/core/errors.h"

namespace femup {

ModelEffectPencil::ModelEffectPencil(
    std::shared_ptr<const Structure> structure,
    std::vector<std::shared_ptr<const ModelEffect>> effects)
    : structure_(std::move(structure)), effects_(std::move(effects)) {
  if (!structure_) throw InputError("structure", "no structure is given");
  if (effects_.empty()) throw InputError("effects", "no effect is given");
  for (const auto& e : effects_) {
    offset_.push_back(num_parameters_);
    num_parameters_ += static_cast<int>(e->Parameters().size());
  }
}

std::vector<std::string> ModelEffectPencil::ParameterNames() const {
  std::vector<std::string> names;
  for (const auto& e : effects_) {
    for (const EffectParameter& p : e->Parameters())
      names.push_back(e->kind() + "[" + e->region().name + "]." + p.name);
  }
  return names;
}

std::vector<std::string> ModelEffectPencil::ParameterGroups() const {
  std::vector<std::string> groups;
  for (const auto& e : effects_)
    groups.insert(groups.end(), e->Parameters().size(), e->kind());
  return groups;
}

std::vector<Eigen::VectorXd> ModelEffectPencil::Split(const Eigen::VectorXd& x) const {
  if (x.size() != num_parameters_) {
    throw InputError("x", "has " + std::to_string(x.size()) + " entries; expected " +
                              std::to_string(num_parameters_));
  }
  std::vector<Eigen::VectorXd> thetas;
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    const int size =
        (k + 1 < effects_.size() ? offset_[k + 1] : num_parameters_) - offset_[k];
    thetas.push_back(x.segment(offset_[k], size));
  }
  return thetas;
}

void ModelEffectPencil::Assemble(const Eigen::VectorXd& x, bool wet,
                                 SparseMatrix* stiffness, SparseMatrix* mass) const {
  std::vector<const ModelEffect*> effects;
  for (const auto& e : effects_) effects.push_back(e.get());
  ApplyModelEffects(*structure_, effects, Split(x),
                    wet ? Immersion::kWet : Immersion::kDry, stiffness, mass);
}

void ModelEffectPencil::Derivatives(const Eigen::VectorXd& x, bool wet,
                                    PencilDerivatives* out) const {
  out->stiffness.assign(num_parameters_, nullptr);
  out->mass.assign(num_parameters_, nullptr);
  out->storage.clear();
  const std::vector<Eigen::VectorXd> thetas = Split(x);
  const Immersion immersion = wet ? Immersion::kWet : Immersion::kDry;
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    for (int i = 0; i < thetas[k].size(); ++i) {
      const ModelChange d = effects_[k]->Derivative(thetas[k], i, immersion);
      const int p = offset_[k] + i;
      if (d.stiffness.size() > 0) {
        out->storage.emplace_back(d.stiffness);
        out->stiffness[p] = &out->storage.back();
      }
      if (d.mass.size() > 0) {
        out->storage.emplace_back(d.mass);
        out->mass[p] = &out->storage.back();
      }
    }
  }
}

Eigen::VectorXd ModelEffectPencil::Lower() const {
  Eigen::VectorXd v(num_parameters_);
  int i = 0;
  for (const auto& e : effects_)
    for (const EffectParameter& p : e->Parameters()) v[i++] = p.lower;
  return v;
}

Eigen::VectorXd ModelEffectPencil::Upper() const {
  Eigen::VectorXd v(num_parameters_);
  int i = 0;
  for (const auto& e : effects_)
    for (const EffectParameter& p : e->Parameters()) v[i++] = p.upper;
  return v;
}

NonlinearProblem BuildModelEffectFitProblem(
    std::shared_ptr<const Structure> structure,
    std::vector<std::shared_ptr<const ModelEffect>> effects,
    const std::vector<ModalData>& states, const EigenSensitivityOptions& options,
    const Eigen::VectorXd& start) {
  Eigen::VectorXd x0 = start;
  if (x0.size() == 0) {
    std::vector<double> first;
    for (const auto& e : effects) {
      const std::vector<Eigen::VectorXd> starts = e->Starts();
      if (starts.empty()) continue;
      first.insert(first.end(), starts.front().data(),
                   starts.front().data() + starts.front().size());
    }
    x0 = Eigen::Map<const Eigen::VectorXd>(first.data(),
                                           static_cast<Eigen::Index>(first.size()));
  }
  auto pencil =
      std::make_shared<const ModelEffectPencil>(std::move(structure), std::move(effects));
  NonlinearProblem problem = BuildOutputErrorProblem(pencil, states, options, x0);
  problem.lower = pencil->Lower();
  problem.upper = pencil->Upper();
  return problem;
}

}  // namespace femup
