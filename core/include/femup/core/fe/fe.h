// Finite element library: 2D frame (Euler-Bernoulli beam with axial stiffness)
// element matrices in global coordinates. DOF order per element:
// [u1 v1 theta1 u2 v2 theta2] with u, v global x, y translations (m) and theta
// the rotation about z (rad). SI units: E (Pa), A (m^2), I (m^4), rho (kg/m^3).
#pragma once

#include <Eigen/Core>

namespace femup {

struct BeamSection {
  double E = 0;    // Young's modulus (Pa)
  double A = 0;    // area (m^2)
  double I = 0;    // second moment of area (m^4)
  double rho = 0;  // density (kg/m^3)
};

using Matrix6 = Eigen::Matrix<double, 6, 6>;

// Shear deformation of a 2D frame element (Timoshenko): the shear area
// kappa A (m^2; 0: none, Euler-Bernoulli) and Poisson's ratio, G = E / (2 (1 +
// nu)).
struct BeamShear {
  double area = 0;
  double nu = 0.3;
};

// Element stiffness between nodes (x1, y1) and (x2, y2).
Matrix6 Frame2dStiffness(const BeamSection& s, double x1, double y1, double x2,
                         double y2);
// Consistent mass (axial linear + cubic Hermitian transverse), mass rho*A*L.
Matrix6 Frame2dConsistentMass(const BeamSection& s, double x1, double y1, double x2,
                              double y2);
// The same element with shear deformation: the in-plane part (ux, uy, rz at
// each end) of frame3d.h's element with the member in the x-y plane, bending
// about z through I and `shear.area` (Timoshenko, after Przemieniecki; the
// mass's translational inertia is phi-dependent, the sections' rotary inertia
// is left out as in frame3d.h; Frame2dRotaryInertiaMass is that term, which
// the cantilever's form variant adds). With shear.area == 0 both equal the
// Euler-Bernoulli matrices above. Throws InputError for a bad section, a
// negative shear area or nu outside (-1, 0.5].
Matrix6 Frame2dStiffness(const BeamSection& s, const BeamShear& shear, double x1,
                         double y1, double x2, double y2);
Matrix6 Frame2dConsistentMass(const BeamSection& s, const BeamShear& shear, double x1,
                              double y1, double x2, double y2);
// The rotary inertia of the section in bending, rho I per unit length, on the
// slope of the element's cubic transverse field (the consistent matrix
// rho I / (30 L) [36 3L -36 3L; 3L 4L^2 -3L -L^2; ...] on v1, theta1, v2,
// theta2): what a Rayleigh or Timoshenko beam adds to the Euler-Bernoulli
// mass. Throws InputError for a bad section.
Matrix6 Frame2dRotaryInertiaMass(const BeamSection& s, double x1, double y1, double x2,
                                 double y2);
// The transverse part of the consistent mass only (no axial inertia): the
// physically right basis for water added mass, which acts on motion normal to
// the member. `mass_per_length` (kg/m) replaces rho*A.
Matrix6 Frame2dTransverseMass(double mass_per_length, double x1, double y1, double x2,
                              double y2);

}  // namespace femup
