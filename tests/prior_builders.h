// Test fixtures shared by the tests of stated priors (effect_priors.h): a
// family's prior and its quantities' uniform and normal priors, each in one
// call (the fields a prior does not use keep their defaults, 0).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "femup/problems/effect_priors.h"

namespace femup {
namespace fixtures {

// The prior of family `kind` on `quantities`, limited to `regions` (all when
// empty).
inline FamilyPrior Prior(const std::string& kind, std::vector<QuantityPrior> quantities,
                         std::vector<std::string> regions = {}) {
  FamilyPrior f;
  f.kind = kind;
  f.quantities = std::move(quantities);
  f.regions = std::move(regions);
  return f;
}

// Quantity `q` uniform in [lower, upper].
inline QuantityPrior Range(const std::string& q, double lower, double upper) {
  return QuantityPrior{q, false, lower, upper, 0, 0};
}

// Quantity `q` normal with `mean` and `sigma`.
inline QuantityPrior Normal(const std::string& q, double mean, double sigma) {
  return QuantityPrior{q, true, 0, 0, mean, sigma};
}

}  // namespace fixtures
}  // namespace femup
