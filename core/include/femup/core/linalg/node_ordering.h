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

// Below this many DOFs the DOF graph's ordering (CHOLMOD's own) is as fast or
// faster: a 10,560-DOF jacket's diagnosis, thousands of small solves, took
// 64.1 s with the node graph against 52.5 s without, and the lowest 10 modes of
// 51,360 and 168,480-DOF jackets 1.53 and 4.32 s against 1.73 and 4.68 s
// (docs/benchmarks.md, issue 29, session 29).
inline constexpr int kNodeOrderingMinDofs = 50000;

// `options` with dof_groups set to the labels' nodes when there are at least
// `min_dofs` labels and some node holds more than one DOF; unchanged otherwise
// (a small model; one DOF per node, a chain's masses: the DOF graph is the
// node graph; no labels). The labels must be those of the matrices solved (the
// sparse solve refuses groups of another size). Only the sparse eigensolver
// reads dof_groups; the modes are the same to its tolerance.
EigenOptions WithNodeOrdering(EigenOptions options,
                              const std::vector<std::string>& dof_labels,
                              int min_dofs = kNodeOrderingMinDofs);

}  // namespace femup
