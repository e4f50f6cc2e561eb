// The eigensolver's fill-reducing ordering from a model's nodes. A frame's
// DOFs come three or six to a node, labelled "<node>:<dof>" ("n12:ux"); the
// sparse eigensolver orders the node graph rather than the DOF graph when it
// is given each DOF's node (EigenOptions::dof_groups), several times faster
// for about the same fill (docs/benchmarks.md, issue 29). Every caller that
// holds a model's DOF labels takes its options from here, so a study, a fit
// and a ranking solve a large frame the same way.
#pragma once

#include <string>
#include <vector>

#include "femup/core/linalg/modal.h"

namespace femup {

// The node of each DOF, numbered 0, 1, ... in order of first appearance: the
// label's part before ':'. A label without ':' is a node of its own.
std::vector<int> DofNodesFromLabels(const std::vector<std::string>& dof_labels);

// `options` with dof_groups set to the labels' nodes when some node holds more
// than one DOF; unchanged otherwise (one DOF per node, a chain's masses: the
// DOF graph is the node graph, and no labels). The labels must be those of the
// matrices solved (the sparse solve refuses groups of another size). Only the
// sparse eigensolver reads dof_groups; the modes are the same to its tolerance.
EigenOptions WithNodeOrdering(EigenOptions options,
                              const std::vector<std::string>& dof_labels);

}  // namespace femup
