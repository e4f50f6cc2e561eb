// Built-in structures: the spring-mass chain of the reference paper and a 2D
// frame cantilever on any mesh.
#pragma once

#include <string>
#include <vector>

#include "femup/core/fe/fe.h"
#include "femup/core/fe/structure.h"

namespace femup {

// Chain fixed at one end: spring 1 joins the ground and mass 1, spring n joins
// masses n-1 and n. Element n is (spring n, mass n); DOF n is "x<n>".
struct ChainSpec {
  std::vector<double> masses;   // kg, > 0
  std::vector<double> springs;  // N/m, > 0, same count as masses
  std::vector<bool> wet;        // which masses are in water (empty: none)
  // The chain idealises a building's storeys (a shear building): its
  // Structure then carries the flexural part of a building's deformation as
  // two form variants, falling from the base and rising to the roof (the
  // diagnosis allows for them as model form error).
  bool shear_building = false;
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

  // Local modifications along the height z (m above the base, 0 <= z0 < z1 <=
  // tip), exact on elements they cover only in part (beam_modifications.h).
  // They are added to the global stiffness and mass after assembly, like the
  // supports and lumped masses: the elements' own matrices (and so the factors
  // and added-mass bases built on them) do not include them.
  struct DistributedMass {
    double z0 = 0, z1 = 0;
    double mass_per_length = 0;  // kg/m, >= 0, on transverse motion only
    double fade = 0;  // m, >= 0: linear fade to zero over the top `fade` m below z1
  };
  struct StiffnessChange {
    double z0 = 0, z1 = 0;
    double factor = 0;  // E I becomes E I (1 + factor) over [z0, z1]; factor > -1
  };
  struct PointMass {
    double height = 0;          // m, 0 <= height <= tip, between nodes allowed
    double mass = 0;            // kg, >= 0, on both translations
    double rotary_inertia = 0;  // kg m^2, >= 0
  };
  // Uniform axial force along the whole beam, N: tension positive, compression
  // negative; its geometric stiffness (AxialForceStiffness in
  // beam_modifications.h) is added to K like the modifications below. 0: none.
  double axial_force = 0;
  std::vector<DistributedMass> distributed_masses;
  // Overlapping changes add up: 1 + the sum of the factors must stay > 0.
  std::vector<StiffnessChange> stiffness_changes;
  std::vector<PointMass> point_masses;
  // Keep each element's own matrices (for correction factors). False builds
  // only the global K and M, faster, for fits that rebuild the model often;
  // the elements then carry their ids and extents with empty matrices.
  bool element_matrices = true;
  // The section's shear area kappa A (m^2, 0 < kappa A <= A; 0: A / 2, a
  // thin-walled section's, as a plane frame's default) for the model's form
  // variant (Structure::form_variants): the same beam of Timoshenko elements,
  // shear deformation (Frame2dStiffness and Frame2dConsistentMass with a
  // BeamShear, nu 0.3) and the sections' rotary inertia
  // (Frame2dRotaryInertiaMass), the supports, masses and modifications as they
  // are, built with the element matrices only. The diagnosis allows for it as
  // the model's own form error.
  double shear_area = 0;
};
// `num_elements` equal elements over `length`.
std::vector<double> UniformHeights(double length, int num_elements);
Structure BuildCantilever(const CantileverSpec& spec);

}  // namespace femup
