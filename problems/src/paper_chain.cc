#include "femup/problems/paper_chain.h"

#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"

namespace femup {

const double kPaperMassFactors[5] = {-0.0087, -0.0333, 0.0025, 0.0058, -0.0230};
const double kPaperStiffnessFactors[5] = {0.0119, 0.0119, -0.0004, 0.0033, 0.0017};
const double kPaperAddedMassFactors[3] = {0.15, 0.25, 0.20};

PaperChainScenario PaperChain(int wet_masses) {
  if (wet_masses < 1 || wet_masses > 3) {
    throw InputError("paper chain", "wet_masses must be 1, 2 or 3");
  }
  ChainSpec spec;
  spec.masses.assign(5, 50.0);
  spec.springs.assign(5, 2.9e7);
  spec.wet.assign(5, false);
  for (int i = 0; i < wet_masses; ++i) spec.wet[i] = true;
  PaperChainScenario s;
  s.structure = BuildSpringMassChain(spec);
  s.model = BuildModel(s.structure, PaperParameterPlan());
  s.preset.resize(s.model.num_parameters());
  for (int i = 0; i < 5; ++i) {
    s.preset[s.model.FindParameter("mass[" + std::to_string(i + 1) + "]")] =
        kPaperMassFactors[i];
    s.preset[s.model.FindParameter("stiffness[" + std::to_string(i + 1) + "]")] =
        kPaperStiffnessFactors[i];
  }
  for (int i = 0; i < wet_masses; ++i) {
    s.preset[s.model.FindParameter("added_mass[" + std::to_string(i + 1) + "]")] =
        kPaperAddedMassFactors[i];
  }
  s.fixed_parameter = "mass[4]";
  return s;
}

}  // namespace femup
