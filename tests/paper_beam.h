// Test fixture shared by the unit tests: the steel beam of the reference
// paper's cantilever (docs/method.md). One definition, so that a test that
// says "the paper's section" means the same numbers everywhere.
#pragma once

#include <vector>

#include "femup/core/fe/builders.h"
#include "femup/core/fe/fe.h"

namespace femup {
namespace fixtures {

// E 206 GPa, A 8.8 cm^2, I 8.53e-8 m^4, rho 7850 kg/m^3.
inline BeamSection PaperSection() { return BeamSection{206e9, 8.8e-4, 8.53e-8, 7850}; }

// A non-uniform mesh of 5 elements over 0.9 m (node heights, m).
inline const std::vector<double> kNonUniformHeights = {0.0, 0.15, 0.32, 0.5, 0.71, 0.9};

// The paper's section on `heights`; with `flexible_base`, on support springs
// (transverse 1e6 N/m, axial 1e9 N/m, rotation 1e4 N m/rad) instead of clamped.
inline CantileverSpec PaperCantilever(const std::vector<double>& heights,
                                      bool flexible_base = false) {
  CantileverSpec spec;
  spec.node_heights = heights;
  spec.section = PaperSection();
  if (flexible_base) {
    spec.support_transverse = 1e6;
    spec.support_axial = 1e9;
    spec.support_rotation = 1e4;
  }
  return spec;
}

// The nominal beam of the effect tests: the paper's section, clamped, 2 m in 20
// uniform elements.
inline constexpr double kEffectBeamLength = 2.0;
inline constexpr int kEffectBeamElements = 20;
inline CantileverSpec EffectBeam() {
  return PaperCantilever(UniformHeights(kEffectBeamLength, kEffectBeamElements));
}

}  // namespace fixtures
}  // namespace femup
