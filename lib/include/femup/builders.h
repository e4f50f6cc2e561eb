// Built-in structures: the spring-mass chain of the reference paper and a 2D
// frame cantilever on any mesh.
#pragma once

#include <string>
#include <vector>

#include "femup/fe.h"
#include "femup/structure.h"

namespace femup {

// Chain fixed at one end: spring 1 joins the ground and mass 1, spring n joins
// masses n-1 and n. Element n is (spring n, mass n); DOF n is "x<n>".
struct ChainSpec {
  std::vector<double> masses;   // kg, > 0
  std::vector<double> springs;  // N/m, > 0, same count as masses
  std::vector<bool> wet;        // which masses are in water (empty: none)
};
Structure BuildSpringMassChain(const ChainSpec& spec);

enum class AddedMassBasis {
  kElementMass,  // the element's own consistent mass matrix (the paper)
  kTransverse,   // consistent mass of transverse motion only (physical)
};
// "element_mass", "transverse".
const char* ToString(AddedMassBasis basis);
bool AddedMassBasisFromString(const std::string& text, AddedMassBasis* basis);

struct LumpedMass {
  int node = 0;               // 0 = base node, n = n-th node above it
  double mass = 0;            // kg, on both translations
  double rotary_inertia = 0;  // kg m^2
};

// A vertical cantilever: base node at height 0, nodes up to the free end. Node
// heights need not be equally spaced (the paper's Models B-E). DOFs per free
// node: "n<k>:ux" (transverse), "n<k>:uy" (axial), "n<k>:rz".
struct CantileverSpec {
  std::vector<double> node_heights;  // m, strictly increasing, first = 0 (base)
  BeamSection section;
  double water_depth =
      0;  // m above the base; an element is wet when its midpoint is below
  AddedMassBasis added_mass_basis = AddedMassBasis::kElementMass;
  // Support springs at the base node (N/m, N m/rad). A value of 0 (the default)
  // makes that base DOF rigid; a positive value frees it and holds it by the
  // spring. All three zero: the paper's clamped base.
  double support_transverse = 0;
  double support_axial = 0;
  double support_rotation = 0;
  std::vector<LumpedMass> lumped_masses;
};
// `num_elements` equal elements over `length`.
std::vector<double> UniformHeights(double length, int num_elements);
Structure BuildCantilever(const CantileverSpec& spec);

}  // namespace femup
