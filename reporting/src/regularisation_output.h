// Private: how every command reports a regularised solve (tikhonov: lambda;
// tsvd: the kept singular values): its JSON and its L-curve and GCV plots.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "femup/reporting/plot.h"
#include "femup/solvers/regularisation.h"

namespace femup {

// The rule, the chosen lambda or k, each rule's lambda, and the path on the grid.
nlohmann::json RegularisationJson(const RegularisationReport& report);

// Two panels: the L-curve (residual norm against solution semi-norm, log-log) and
// the GCV function, each with the chosen point. Empty when there is no path.
std::vector<Plot> RegularisationPlots(const RegularisationReport& report,
                                      const std::string& residual_label,
                                      const std::string& norm_label);

}  // namespace femup
