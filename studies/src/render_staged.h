// Private: renders a figure into an OutputDir's staging folder as
// <name>.png/.dat/.gp; a render that fails becomes a warning.
#pragma once

#include <string>
#include <vector>

#include "femup/output_dir.h"
#include "femup/plot.h"

namespace femup {
void RenderStaged(const Figure& figure, const std::string& name, OutputDir* out,
                  std::vector<std::string>* warnings);
}  // namespace femup
