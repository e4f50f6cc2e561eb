// 3D frame (space beam) element: axial, torsion and bending in two planes, 12
// DOF, Euler-Bernoulli by default or shear-deformable (Timoshenko, after
// Przemieniecki, Theory of Matrix Structural Analysis, 1968, sections 5.6 and
// 11.6). The 2D elements are in fe.h.
//
// Local axes: x runs from end 1 to end 2; y is the component of a reference
// vector normal to x; z = x cross y (right-handed). Bending in the local x-y
// plane (displacement v, rotation theta_z) uses Iz and shear area As_y; bending
// in the local x-z plane (w, theta_y) uses Iy and As_z.
//
// DOF order per element, local or global alike:
//   [u1 v1 w1 rx1 ry1 rz1  u2 v2 w2 rx2 ry2 rz2]
// translations (m) along x, y, z, then rotations (rad) about x, y, z, end 1
// then end 2. Global matrices refer to the global X, Y, Z axes.
// SI units throughout: E, G (Pa), A, As (m^2), I, J (m^4), rho (kg/m^3).
#pragma once

#include <Eigen/Core>
#include <string>

#include "femup/core/invalid.h"

namespace femup {

using Matrix12 = Eigen::Matrix<double, 12, 12>;

enum class BeamTheory {
  kEulerBernoulli,  // no shear deformation (default)
  kTimoshenko,      // shear deformation through the shear areas
};
// "euler_bernoulli", "timoshenko".
const char* ToString(BeamTheory theory);
// Returns false when `text` names no theory.
bool BeamTheoryFromString(const std::string& text, BeamTheory* theory);

struct FrameSection3d {
  double E = 0;     // Young's modulus (Pa)
  double G = 0;     // shear modulus (Pa); 0: E / (2 (1 + nu))
  double nu = 0.3;  // Poisson's ratio, used only when G == 0; in (-1, 0.5]
  double A = 0;     // area (m^2)
  double Iy = 0;    // second moment of area about local y (m^4): bending in x-z
  double Iz = 0;    // second moment of area about local z (m^4): bending in x-y
  double J = 0;     // torsion constant (m^4): torsional stiffness G J / L
  double rho = 0;   // density (kg/m^3)
  double Ip = 0;    // polar moment for torsional inertia rho Ip (m^4); 0: Iy + Iz
  // Shear areas kappa * A (m^2) for shear along local y and z; used by
  // BeamTheory::kTimoshenko only, where they must be positive.
  double shear_area_y = 0;
  double shear_area_z = 0;

  double ShearModulus() const { return G > 0 ? G : E / (2 * (1 + nu)); }
  double PolarInertia() const { return Ip > 0 ? Ip : Iy + Iz; }
  // Ok when valid for `theory`; otherwise the field and what is wrong.
  Invalid Validate(BeamTheory theory = BeamTheory::kEulerBernoulli) const;
};

// A thin- or thick-walled circular tube of outer diameter `diameter` and wall
// `wall` (m, 0 < wall <= diameter / 2): A, Iy = Iz, J = Ip = Iy + Iz, shear
// areas A / 2 (the thin-tube shear coefficient), G from nu.
FrameSection3d CircularTube(double diameter, double wall, double E, double nu,
                            double rho);

// Local 12 x 12 stiffness of an element of length `length` (m). For
// kTimoshenko, phi_y = 12 E Iz / (G As_y L^2) and phi_z = 12 E Iy / (G As_z L^2)
// (Przemieniecki); phi = 0 is Euler-Bernoulli. Throws InputError for an invalid
// section (the message names the field) or a length that is not positive.
Matrix12 Frame3dLocalStiffness(const FrameSection3d& s, double length,
                               BeamTheory theory = BeamTheory::kEulerBernoulli);

// Local 12 x 12 consistent mass: axial rho A L / 6 [2 1; 1 2], torsion
// rho Ip L / 6 [2 1; 1 2], transverse translational inertia rho A of the
// element's own interpolation (cubic Hermitian for Euler-Bernoulli, the
// phi-dependent Przemieniecki matrix for Timoshenko). The rotary inertia of the
// cross-section in bending is left out. Throws as Frame3dLocalStiffness.
Matrix12 Frame3dLocalConsistentMass(const FrameSection3d& s, double length,
                                    BeamTheory theory = BeamTheory::kEulerBernoulli);

// The transverse translational consistent mass only (no axial, torsional or
// rotary inertia), Euler-Bernoulli interpolation, `mass_per_length` (kg/m):
// the basis for water added mass, which acts on motion normal to the member.
// Throws InputError unless mass_per_length and length are positive and finite.
Matrix12 Frame3dLocalTransverseMass(double mass_per_length, double length);

// The 12 x 12 rotation T with local = T * global: four copies of the 3 x 3
// matrix whose rows are the local x, y, z axes in global coordinates. `end1`,
// `end2`: end coordinates (m); `reference`: any vector not parallel to the
// member that, with the member axis, spans the local x-y plane (its component
// normal to the member is local y). Throws InputError("frame element", ...) for
// coincident or non-finite ends or a reference vector parallel to the member
// (or zero).
Matrix12 Frame3dTransformation(const Eigen::Vector3d& end1, const Eigen::Vector3d& end2,
                               const Eigen::Vector3d& reference);

// Global matrices T' K_local T and T' M_local T, exactly symmetric, for the
// element from `end1` to `end2` with local y from `reference`.
Matrix12 Frame3dStiffness(const FrameSection3d& s, const Eigen::Vector3d& end1,
                          const Eigen::Vector3d& end2, const Eigen::Vector3d& reference,
                          BeamTheory theory = BeamTheory::kEulerBernoulli);
Matrix12 Frame3dConsistentMass(const FrameSection3d& s, const Eigen::Vector3d& end1,
                               const Eigen::Vector3d& end2,
                               const Eigen::Vector3d& reference,
                               BeamTheory theory = BeamTheory::kEulerBernoulli);
Matrix12 Frame3dTransverseMass(double mass_per_length, const Eigen::Vector3d& end1,
                               const Eigen::Vector3d& end2,
                               const Eigen::Vector3d& reference);

}  // namespace femup
