#include "femup/core/fe/structure.h"

#include <algorithm>
#include <sstream>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"

namespace femup {

int Structure::FindElement(int id) const {
  for (int i = 0; i < static_cast<int>(elements.size()); ++i) {
    if (elements[i].id == id) return i;
  }
  return -1;
}

ParameterPlan PaperParameterPlan() {
  ParameterPlan plan;
  plan.mass.scope = ParameterFamily::Scope::kPerElement;
  plan.stiffness.scope = ParameterFamily::Scope::kPerElement;
  plan.added_mass.scope = ParameterFamily::Scope::kPerElement;
  plan.added_mass.selection = ParameterFamily::Selection::kWet;
  return plan;
}

namespace {

constexpr EnumName<ParameterFamily::Selection> kSelectionNames[] = {
    {ParameterFamily::Selection::kAll, "all"},
    {ParameterFamily::Selection::kWet, "wet"},
    {ParameterFamily::Selection::kDry, "dry"},
};

const char* SelectionName(ParameterFamily::Selection s) {
  return NameIn(kSelectionNames, s, "all");
}

const SparseMatrix& BasisOf(const ElementMatrices& e, ParameterKind kind) {
  switch (kind) {
    case ParameterKind::kMass:
      return e.mass;
    case ParameterKind::kStiffness:
      return e.stiffness;
    case ParameterKind::kAddedMass:
      return e.added_mass_basis;
  }
  return e.mass;
}

// A compact name for a set of element labels: "e1-e4" when consecutive ids.
std::string GroupLabel(const Structure& s, const std::vector<int>& idx) {
  bool consecutive = idx.size() > 2;
  for (std::size_t i = 1; i < idx.size() && consecutive; ++i) {
    consecutive = s.elements[idx[i]].id == s.elements[idx[i - 1]].id + 1;
  }
  if (consecutive)
    return s.elements[idx.front()].label + "-" + s.elements[idx.back()].label;
  std::string out;
  for (std::size_t i = 0; i < idx.size(); ++i) {
    out += (i ? "+" : "") + s.elements[idx[i]].label;
  }
  return out;
}

void AddFamily(const Structure& s, ParameterKind kind, const ParameterFamily& family,
               ParametrisedModel* model) {
  using Scope = ParameterFamily::Scope;
  using Selection = ParameterFamily::Selection;
  const std::string field = std::string("parameters.") + ToString(kind);
  if (family.scope == Scope::kNone) return;
  Selection selection = family.selection;
  if (kind == ParameterKind::kAddedMass) selection = Selection::kWet;

  std::vector<std::vector<int>> sets;  // indices into s.elements
  if (family.scope == Scope::kGroups) {
    if (family.groups.empty()) throw InputError(field, "groups: the list is empty");
    for (const auto& group : family.groups) {
      std::vector<int> idx;
      for (int id : group) {
        const int i = s.FindElement(id);
        if (i < 0) {
          throw InputError(field + ".groups", "element " + std::to_string(id) +
                                                  " does not exist (elements are 1.." +
                                                  std::to_string(s.elements.size()) +
                                                  ")");
        }
        if (kind == ParameterKind::kAddedMass && !s.elements[i].wet) {
          throw InputError(field + ".groups",
                           "element " + std::to_string(id) +
                               " is not wet: it cannot carry added mass");
        }
        if (std::find(idx.begin(), idx.end(), i) != idx.end()) {
          throw InputError(field + ".groups", "element " + std::to_string(id) +
                                                  " is listed twice in a group");
        }
        idx.push_back(i);
      }
      if (idx.empty()) throw InputError(field + ".groups", "a group is empty");
      sets.push_back(idx);
    }
  } else {
    std::vector<int> selected;
    for (int i = 0; i < static_cast<int>(s.elements.size()); ++i) {
      const bool wet = s.elements[i].wet;
      if (selection == Selection::kAll || (selection == Selection::kWet && wet) ||
          (selection == Selection::kDry && !wet)) {
        selected.push_back(i);
      }
    }
    if (selected.empty()) {
      throw InputError(field, std::string("no element is ") +
                                  (selection == Selection::kWet ? "wet" : "selected") +
                                  (kind == ParameterKind::kAddedMass
                                       ? " (check the water depth or the wet list)"
                                       : ""));
    }
    if (family.scope == Scope::kPerElement) {
      for (int i : selected) sets.push_back({i});
    } else {
      sets.push_back(selected);
    }
  }

  for (const auto& idx : sets) {
    Parameter p;
    p.kind = kind;
    SparseMatrix basis(model->num_dofs(), model->num_dofs());
    int wet = 0;
    for (int i : idx) {
      basis += BasisOf(s.elements[i], kind);
      p.elements.push_back(s.elements[i].id);
      p.tags.push_back("element:" + std::to_string(s.elements[i].id));
      wet += s.elements[i].wet ? 1 : 0;
    }
    std::string label;
    if (family.scope == Scope::kSingle) {
      label = SelectionName(selection);
    } else if (idx.size() == 1) {
      label = s.elements[idx[0]].label;
    } else {
      label = GroupLabel(s, idx);
    }
    p.name = std::string(ToString(kind)) + "[" + label + "]";
    p.tags.insert(p.tags.begin(), wet == static_cast<int>(idx.size()) ? "wet"
                                  : wet == 0                          ? "dry"
                                                                      : "mixed");
    if (basis.nonZeros() == 0) {
      throw InputError(field, "parameter '" + p.name + "' has an empty basis matrix");
    }
    p.basis = std::move(basis);
    model->AddParameter(std::move(p));
  }
}

}  // namespace

ParametrisedModel BuildModel(const Structure& structure, const ParameterPlan& plan) {
  ParametrisedModel model(structure.stiffness, structure.mass, structure.dof_labels);
  AddFamily(structure, ParameterKind::kMass, plan.mass, &model);
  AddFamily(structure, ParameterKind::kStiffness, plan.stiffness, &model);
  AddFamily(structure, ParameterKind::kAddedMass, plan.added_mass, &model);
  return model;
}

}  // namespace femup
