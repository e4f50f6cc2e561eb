// A model's form variants (Structure::form_variants) on their own DOFs, such
// as the model on a finer mesh, made comparable with the model: the DOFs they
// share, and the change on the model's DOFs that moves the model's modes as
// the variant moves them.
#pragma once

#include <string>
#include <vector>

#include "femup/core/fe/structure.h"
#include "femup/core/linalg/modal.h"

namespace femup {

// The DOF of `finer` at each of `model`'s DOFs: the DOF with the same
// direction (the label's part after ':') at the node of `finer` at the same
// position (ModelNode::xyz, within 1e-9 of the models' size); a DOF whose
// label names no node (a base spring's) is matched by its label. InputError
// naming the DOF where one has no match or either model has no nodes.
std::vector<int> MatchDofs(const Structure& model, const Structure& finer);

// `model` on a finer mesh (`finer`, the same structure with more elements) as
// a form variant on its own DOFs (FormVariant::dofs from MatchDofs), named
// `name`.
FormVariant FinerMeshVariant(const Structure& model, const Structure& finer,
                             std::string name);

// `finer` (the same structure on a finer mesh) as a model the diagnosis can
// run on in place of `model`, in the model's terms: each of its nodes at a
// model node's place takes that node's name (its DOF labels too), its other
// nodes "f<k>" (k: 1-based in `finer`); an attached mass is looked for where
// the model would look (Structure::attached_mass_nodes: the model's, or every
// model node with translational DOFs), and between them along each of the
// model's segments (or its attached_mass_segments where it names its nodes),
// one candidate per model segment made of the finer segments along it
// (Structure::attached_mass_lines). Form variants are `finer`'s. InputError
// where a model node or segment has no place in `finer` (MatchDofs).
Structure RefinedModel(const Structure& model, Structure finer);

// The model's lowest `modes` modes, and how far the variant moves each: its
// paired mode's eigenvalue less the model's, the modes paired by MAC >= 0.8
// over the model's DOFs (0 where a mode pairs with none), the variant's equal
// pairs first turned to the model's modes (AlignRepeatedModes). 1 <= modes <=
// the model's DOF count, and a variant's dofs sized as the model's, or
// InputError.
struct ModeChanges {
  Modes modes;
  Eigen::VectorXd eigenvalue_change;  // rad^2/s^2, one per mode
};
ModeChanges PairedModeChanges(const Structure& model, const FormVariant& variant,
                              int modes);

// The variant on the model's DOFs. A variant already there is returned as it
// is. Otherwise the model's lowest `modes` modes are paired, by MAC over the
// model's DOFs, with the variant's (solved on its own DOFs), and the variant
// becomes the model's mass and its stiffness plus
//   dK = sum_i dlambda_i (M phi_i)(M phi_i)',
// dlambda_i the paired variant mode's eigenvalue less the model's (0 where a
// mode pairs with none at MAC >= 0.8): to first order dK moves the model's
// mode i by exactly dlambda_i (phi_i' dK phi_i = dlambda_i, the phi_i being
// M-orthonormal), which is what the diagnosis reads of a variant. dK is dense
// on the model's DOFs: for models of a few thousand DOFs. 1 <= modes <= the
// model's DOF count, or InputError.
FormVariant OnModelDofs(const Structure& model, const FormVariant& variant, int modes);

}  // namespace femup
