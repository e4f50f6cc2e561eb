// Strip-theory added mass: the water that moves with a slender member vibrating
// normal to its axis, taken section by section (2D potential flow, no free
// surface waves, no viscous effects) and spread along the wet length.
//
// Per unit length, a section of width 2a normal to the motion carries
//   m_a = C_A * rho_w * pi * a^2   (kg/m),
// with rho_w the fluid density (kg/m^3) and C_A the section's added-mass
// coefficient referred to the area pi a^2. The finite element form for a
// vertical cantilever (BuildCantilever) is the consistent mass of transverse
// motion, integrated only over the wet part of each element.
#pragma once

#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"

namespace femup {

// C_A of a long rectangular section that moves normal to its side of length
// `width_normal` (2a, m, > 0); `depth_along` (2b, m, >= 0) is the side along the
// motion. Referred to the area pi a^2, a = width_normal / 2. Dimensionless.
//
// Source: DNV-RP-C205 (2010), Appendix A, Table A-1 (rectangle; after Patton and
// Blevins), tabulated against a/b:
//   a/b  inf   10    5     2     1     0.5   0.2   0.1
//   C_A  1.00  1.14  1.21  1.36  1.51  1.70  1.98  2.23
// Between tabulated points with a/b in [0.1, 10] C_A is interpolated linearly in
// log(a/b). Above a/b = 10 it is interpolated linearly in b/a between b/a = 0.1
// (1.14) and b/a = 0 (1.00, the flat plate, which is also the value for
// depth_along = 0). The result is continuous and falls monotonically as a/b
// rises. Throws InputError for a non-positive or non-finite width, a negative or
// non-finite depth, or a/b < 0.1 (outside the table).
double RectangleAddedMassCoefficient(double width_normal, double depth_along);

// C_A of a circular section of diameter 2a, referred to pi a^2: exactly 1 in 2D
// potential flow (the added mass equals the displaced fluid mass).
double CircleAddedMassCoefficient();

// m_a = coefficient * fluid_density * pi * (width_normal / 2)^2 in kg/m, with
// fluid_density in kg/m^3 (1000 fresh water, ~1025 sea water), width_normal the
// section width normal to the motion in m (the diameter for a circle) and the
// dimensionless coefficient C_A referred to pi (width_normal / 2)^2. All three
// must be positive and finite, else InputError.
double StripAddedMassPerLength(double fluid_density, double width_normal,
                               double coefficient);

// Added-mass matrix (num_dofs x num_dofs, in the structure's global free DOFs,
// kg and kg m / kg m^2 entries) of transverse motion of a vertical cantilever
// made by BuildCantilever, in water from the base (height 0) up to
// `water_depth` (m, >= 0; above the tip means fully submerged).
//
// Added mass per length along the height z (m above the base):
//   m(z) = mass_per_length * min(1, (water_depth - z) / fade_length)  z < water_depth
//   m(z) = 0                                                          z >= water_depth
// i.e. constant `mass_per_length` (kg/m, > 0) at depth, faded linearly to zero
// over the `fade_length` metres (>= 0; 0 = a sharp water line) just below the
// free surface. For each element the entries are the integrals over the element
// of N_i(z) N_j(z) m(z), with N the cubic Hermite shape functions of the global
// transverse displacement ux in terms of the element's ux and rz DOFs (axial uy
// DOFs get nothing). The integrand is piecewise polynomial (degree <= 7), split
// at the start of the fade and at the water line and integrated by
// Gauss-Legendre quadrature exact for that degree, so an element that is only
// partly wet gets the exact matrix. A fully wet element with no fade gets
// Frame2dTransverseMass(mass_per_length, ...) scattered into the global DOFs.
//
// The result is symmetric and positive semi-definite. It does not depend on the
// elements' `wet` flags or `added_mass_basis`; the element's nodes and global
// DOFs are found from `dof_labels` ("n<k>:ux", "n<k>:uy", "n<k>:rz"),
// `dof_positions` (node heights) and the elements' x0/x1 (element i of
// `elements` joins nodes i and i+1), and a base node with no labels is taken as
// fully fixed. Throws InputError for a structure that is not such a cantilever
// (missing or unparsable labels, positions that do not match x0/x1, elements not
// in increasing height from 0) and for bad depth, fade or mass per length.
SparseMatrix WetTransverseAddedMass(const Structure& s, double mass_per_length,
                                    double water_depth, double fade_length = 0);

}  // namespace femup
