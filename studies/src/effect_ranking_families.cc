#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "effect_ranking_steps.h"
#include "femup/core/errors.h"
#include "femup/core/linalg/node_ordering.h"
#include "femup/problems/effect_priors.h"

namespace femup::effect_ranking_steps {

std::vector<std::vector<char>> HeldOutModes(
    const std::vector<ModalData>& states,
    const std::vector<std::pair<int, int>>& held_out) {
  std::vector<std::vector<char>> held(states.size());
  for (std::size_t i = 0; i < states.size(); ++i)
    held[i].assign(static_cast<std::size_t>(states[i].num_modes()), 0);
  for (const auto& [state, mode] : held_out) {
    if (state < 0 || state >= static_cast<int>(states.size()) || mode < 0 ||
        mode >= states[static_cast<std::size_t>(state)].num_modes()) {
      throw InputError("diagnosis.held_out", "state " + std::to_string(state + 1) +
                                                 " mode " + std::to_string(mode + 1) +
                                                 " is not measured");
    }
    held[static_cast<std::size_t>(state)][static_cast<std::size_t>(mode)] = 1;
  }
  if (!held_out.empty() &&
      std::all_of(held.begin(), held.end(), [](const std::vector<char>& h) {
        return std::all_of(h.begin(), h.end(), [](char c) { return c != 0; });
      })) {
    throw InputError("diagnosis.held_out", "every measured mode is held out; none left");
  }
  return held;
}

Families TriedFamilies(const Structure& structure, const EffectRankingOptions& options,
                       ModelEffectOptions effect_options, EffectRanking* out) {
  std::vector<std::string> kinds = options.kinds;
  if (kinds.empty()) {
    for (const FamilyApplicability& a : ApplicableModelEffects(structure)) {
      if (!a.by_default) continue;  // tried where named
      if (a.why_not.empty()) {
        kinds.push_back(a.kind);
      } else {
        out->skipped.push_back(a.kind + ": " + a.why_not);
      }
    }
  }

  // Stated priors for families not tried are the study's error, before any fit.
  auto tried = [&](const std::string& kind) {
    return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
  };
  auto not_tried = [&](const std::string& kind) {
    std::string why = "is not among the families tried (";
    for (std::size_t i = 0; i < kinds.size(); ++i) why += (i ? ", " : "") + kinds[i];
    why += ")";
    for (const std::string& s : out->skipped)
      if (s.rfind(kind + ": ", 0) == 0)
        why = "does not apply: " + s.substr(kind.size() + 2);
    return why;
  };
  for (const FamilyPrior& f : options.priors.families)
    if (!tried(f.kind)) throw InputError("diagnosis.priors." + f.kind, not_tried(f.kind));
  for (const auto& [kind, w] : options.priors.weights)
    if (kind != "none" && !tried(kind))
      throw InputError("diagnosis.weights." + kind, not_tried(kind));
  // Every family's instances with their stated priors, made (and checked)
  // before any fit.
  std::vector<std::vector<std::unique_ptr<ModelEffect>>> instances;
  effect_options.max_members = options.max_members;
  effect_options.rotary_inertia = options.rotary_inertia;
  for (const std::string& kind : kinds) {
    const FamilyPrior* prior = options.priors.Find(kind);
    // Stated regions pick their places among every member.
    ModelEffectOptions kind_options = effect_options;
    if (prior && !prior->regions.empty()) kind_options.max_members = -1;
    std::vector<std::unique_ptr<ModelEffect>> made =
        CreateModelEffects(kind, structure, kind_options);
    if (kind == "stiffness_loss" && kind_options.max_members >= 0 &&
        static_cast<int>(structure.members.size()) > kind_options.max_members) {
      out->notes.push_back(
          "stiffness_loss was tried on the " + std::to_string(structure.elements.size()) +
          " groups, not on each of the " + std::to_string(structure.members.size()) +
          " members (more than diagnosis.max_members = " +
          std::to_string(kind_options.max_members) +
          "); name the groups or members to look in under "
          "diagnosis.priors.stiffness_loss.regions");
    }
    if (prior) {
      const std::string field = "diagnosis.priors." + kind;
      try {
        made = KeepStatedRegions(std::move(made), structure, *prior);
        for (auto& m : made) m = WithFamilyPrior(std::move(m), *prior);
      } catch (const InputError& e) {
        const std::string what = e.what();
        throw InputError(field + "." + e.where(), what.substr(e.where().size() + 2));
      }
    }
    instances.push_back(std::move(made));
  }
  return Families{std::move(kinds), std::move(instances)};
}

EigenSensitivityOptions FitOptions(const Structure& structure,
                                   const EffectRankingOptions& options) {
  EigenSensitivityOptions fit;
  fit.frequency_sigma = 2 * options.frequency_sigma;  // of lambda = (2 pi f)^2
  fit.shape_sigma = options.shape_sigma;
  fit.use_shapes = options.use_shapes;
  // A space frame's few lowest modes, at every size, and any other model's from
  // kSparseFitMinDofs DOFs (a plane frame on its finer mesh), by sparse
  // shift-invert: a dense solve of all its modes (kAuto up to 1500 DOF) costs
  // 0.1 s per evaluation at 600 DOF, and every fit evaluates hundreds of times.
  constexpr std::size_t kSparseFitMinDofs = 100;
  if (structure.type == "space_frame" || structure.dof_labels.size() >= kSparseFitMinDofs)
    fit.eigen.method = EigenOptions::Method::kSparseShiftInvert;
  // A frame's sparse solves order its node graph (node_ordering.h).
  fit.eigen = WithNodeOrdering(fit.eigen, structure.dof_labels);
  return fit;
}

}  // namespace femup::effect_ranking_steps
