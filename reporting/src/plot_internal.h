// Private to femup_core: running gnuplot (plot_gnuplot.cc), which RenderFigure
// (plot.cc) does once it has written a figure's data and script.
#pragma once

#include <string>

#include "femup/reporting/plot.h"

namespace femup::plot_internal {

// The gnuplot executable found on PATH, or "" when there is none.
std::string FindGnuplot();

// Runs `gnuplot script` and collects what it writes to stderr.
PlotStatus RunGnuplot(const std::string& gnuplot, const std::string& directory,
                      const std::string& script, const std::string& png);

}  // namespace femup::plot_internal
