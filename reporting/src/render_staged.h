// Private: renders a figure into an OutputDir's staging folder as
// <name>.png/.dat/.gp; a render that fails becomes a warning.
#pragma once

#include <string>
#include <vector>

#include "femup/reporting/output_dir.h"
#include "femup/reporting/plot.h"

namespace femup {
void RenderStaged(const Figure& figure, const std::string& name, OutputDir* out,
                  std::vector<std::string>* warnings);

// Which of `dofs` (model DOF indices) a shape plot shows: the transverse DOFs
// of a frame (labels ending ":ux") when there are any, else all of them.
// Returns positions into `dofs`.
std::vector<int> TransverseRows(const std::vector<std::string>& dof_labels,
                                const std::vector<int>& dofs);
}  // namespace femup
