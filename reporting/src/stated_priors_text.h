// Private: the stated priors of a diagnosis (effect_priors.h) as JSON for
// diagnosis.json and as one line of text for the report.
#pragma once

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "femup/problems/effect_priors.h"

namespace femup {

inline nlohmann::json StatedPriorsJson(const StatedPriors& priors) {
  nlohmann::json j = nlohmann::json::object();
  nlohmann::json families = nlohmann::json::object();
  for (const FamilyPrior& f : priors.families) {
    nlohmann::json fj = nlohmann::json::object();
    for (const QuantityPrior& q : f.quantities) {
      fj[q.quantity] = q.normal ? nlohmann::json{{"normal", {q.mean, q.sigma}}}
                                : nlohmann::json{q.lower, q.upper};
    }
    if (!f.regions.empty()) fj["regions"] = f.regions;
    families[f.kind] = fj;
  }
  j["families"] = families;
  j["weights"] = priors.weights;
  return j;
}

// "attached_mass mass_kg [1500, 2500] at n6, n7; material_scaling factor
// normal(1, 0.05); weights none 1, stiffness_loss 2"; empty when none.
inline std::string StatedPriorsLine(const StatedPriors& priors) {
  std::ostringstream o;
  for (const FamilyPrior& f : priors.families) {
    if (o.tellp() > 0) o << "; ";
    o << f.kind;
    for (const QuantityPrior& q : f.quantities) {
      o << " " << q.quantity << " ";
      if (q.normal) {
        o << "normal(" << q.mean << ", " << q.sigma << ")";
      } else {
        o << "[" << q.lower << ", " << q.upper << "]";
      }
    }
    for (std::size_t k = 0; k < f.regions.size(); ++k)
      o << (k == 0 ? " at " : ", ") << f.regions[k];
  }
  if (!priors.weights.empty()) {
    if (o.tellp() > 0) o << "; ";
    o << "weights";
    bool first = true;
    for (const auto& [kind, w] : priors.weights) {
      o << (first ? " " : ", ") << kind << " " << w;
      first = false;
    }
  }
  return o.str();
}

}  // namespace femup
