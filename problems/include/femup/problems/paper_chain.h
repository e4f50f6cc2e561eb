// The reference paper's numerical study (Liu et al. 2014, section 4): a 5-dof
// spring-mass chain fixed at x1's end, 50 kg masses, 2.9e7 N/m springs, with
// preset correction factors. A test problem with a known answer.
#pragma once

#include <string>

#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"

namespace femup {

struct PaperChainScenario {
  Structure structure;
  ParametrisedModel model;      // mass[1..5], stiffness[1..5], added_mass[wet masses]
  Eigen::VectorXd preset;       // the paper's factors, in model parameter order
  std::string fixed_parameter;  // "mass[4]": the paper's constraint
};

// wet_masses = 3: masses 1-3 in water (Fig. 2); 2: masses 1-2 (Fig. 3).
PaperChainScenario PaperChain(int wet_masses);

// The paper's preset factors (method.md section 4).
extern const double kPaperMassFactors[5];
extern const double kPaperStiffnessFactors[5];
extern const double kPaperAddedMassFactors[3];

}  // namespace femup
