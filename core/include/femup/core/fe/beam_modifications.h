// Local modifications along a vertical cantilever made by BuildCantilever: mass
// spread over part of the height, a change of bending stiffness over part of the
// height, and a point mass anywhere. Each is a matrix to add to the global
// stiffness K or mass M, exact also where the modified part covers only a piece
// of an element (the element's own shape functions, integrated exactly; nothing
// is moved to the nearest node).
//
// Heights z are in m above the base (0) up to the tip (the top element's x1).
// Every function returns a num_dofs x num_dofs symmetric sparse matrix in the
// structure's free DOFs (its `dof_labels` order); fixed base DOFs get nothing.
// The structure's nodes and DOFs are found from `dof_labels` ("n<k>:ux"
// transverse, "n<k>:uy" axial, "n<k>:rz"), `dof_positions` and the elements'
// x0/x1, as in WetTransverseAddedMass (strip_theory.h). Throws InputError naming
// the argument for a structure that is not such a cantilever and for bad values
// (not finite, out of range), with the value and what was expected.
#pragma once

#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"

namespace femup {

// Transverse-only mass (kg, kg m, kg m^2 entries) of a mass per length along the
// height, acting on the transverse displacement ux only (nothing on axial uy):
//   m(z) = mass_per_length * min(1, (z1 - z) / fade_length)   z0 <= z < z1
//   m(z) = 0                                                   elsewhere
// i.e. constant `mass_per_length` (kg/m, >= 0) over [z0, z1], faded linearly to
// zero over the top `fade_length` metres (>= 0; 0 = a sharp upper end; a fade
// longer than z1 - z0 starts below z0, so m(z0) < mass_per_length). Entries are
// the integrals of N_i(z) N_j(z) m(z), N the cubic Hermite shape of ux in terms
// of the element's ux and rz DOFs. Requires 0 <= z0 < tip and z1 > z0; the part
// of [z0, z1] above the tip is dropped (e.g. water above the tip). Positive
// semi-definite.
SparseMatrix TransverseMassOverInterval(const Structure& s, double z0, double z1,
                                        double mass_per_length, double fade_length = 0);

// Change of bending stiffness (N/m, N, N m entries): the integral over [z0, z1] of
// delta_ei * N''(z) N''(z)^T, N the Hermite shape of ux as above, '' = d2/dz2.
// `delta_ei` (N m^2, finite, may be negative: a loss) is the change of E I over
// [z0, z1]; 0 <= z0 < z1 <= tip. Over a whole element with delta_ei = E I it is
// the bending part of Frame2dStiffness. Axial stiffness is unchanged.
SparseMatrix BendingStiffnessOverInterval(const Structure& s, double z0, double z1,
                                          double delta_ei);

// Geometric stiffness of a uniform axial force along the whole beam (N/m, N,
// N m entries): the integral over the height of axial_force * N'(z) N'(z)^T, N
// the Hermite shape of ux, ' = d/dz; per element the textbook
// P/(30 l) [36, 3l, -36, 3l; 3l, 4l^2, -3l, -l^2; ...] on (ux, rz) at both ends.
// `axial_force` (N, finite) is a tension when positive (a riser's or tendon's
// tension: it stiffens the bending modes), a compression when negative (a
// pile's load: it softens them, and K + this loses positive definiteness at
// the buckling load, pi^2 E I / (4 L^2) for a uniform cantilever). Axial
// stiffness and the mass are unchanged.
SparseMatrix AxialForceStiffness(const Structure& s, double axial_force);

// A rigid point mass at height z (0 <= z <= tip, between nodes allowed): kinetic
// energy of `mass` (kg, >= 0) moving with ux (Hermite interpolation) and with uy
// (linear interpolation), and of `rotary_inertia` (kg m^2, >= 0) turning with the
// rotation dux/dz of the Hermite shape (= -rz at nodes). At a node this is a
// lumped mass: `mass` on its ux and uy, `rotary_inertia` on its rz, as
// CantileverSpec::lumped_masses (builders.h).
SparseMatrix PointMassAt(const Structure& s, double z, double mass,
                         double rotary_inertia);

}  // namespace femup
