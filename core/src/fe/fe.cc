#include "femup/core/fe/fe.h"

#include <cmath>

#include "femup/core/errors.h"
#include "femup/core/fe/frame3d.h"

namespace femup {
namespace {

struct Geometry {
  double length;
  Matrix6 transform;  // local = T * global
};

Geometry ElementGeometry(double x1, double y1, double x2, double y2) {
  const double dx = x2 - x1, dy = y2 - y1;
  const double length = std::hypot(dx, dy);
  if (!(length > 0) || !std::isfinite(length)) {
    throw InputError("frame element", "nodes coincide or are not finite");
  }
  const double c = dx / length, s = dy / length;
  Matrix6 t = Matrix6::Zero();
  for (int node = 0; node < 2; ++node) {
    const int o = 3 * node;
    t(o, o) = c;
    t(o, o + 1) = s;
    t(o + 1, o) = -s;
    t(o + 1, o + 1) = c;
    t(o + 2, o + 2) = 1;
  }
  return {length, t};
}

void CheckSection(const BeamSection& s) {
  if (!(s.E > 0) || !(s.A > 0) || !(s.I > 0) || !(s.rho > 0) || !std::isfinite(s.E) ||
      !std::isfinite(s.A) || !std::isfinite(s.I) || !std::isfinite(s.rho)) {
    throw InputError("beam section", "E, A, I and rho must be positive and finite");
  }
}

// Cubic Hermitian transverse consistent mass (coefficient m L / 420) on the
// local (v, theta) DOFs; axial rows left zero.
void AddTransverseConsistent(double mass_per_length, double length, Matrix6* m) {
  const double l = length, c = mass_per_length * l / 420.0;
  const int v1 = 1, t1 = 2, v2 = 4, t2 = 5;
  (*m)(v1, v1) += 156 * c;
  (*m)(v1, t1) += 22 * l * c;
  (*m)(v1, v2) += 54 * c;
  (*m)(v1, t2) += -13 * l * c;
  (*m)(t1, t1) += 4 * l * l * c;
  (*m)(t1, v2) += 13 * l * c;
  (*m)(t1, t2) += -3 * l * l * c;
  (*m)(v2, v2) += 156 * c;
  (*m)(v2, t2) += -22 * l * c;
  (*m)(t2, t2) += 4 * l * l * c;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < i; ++j) (*m)(i, j) = (*m)(j, i);
  }
}

// The 3D section of a member in the x-y plane bending about z: the
// out-of-plane properties (Iy, J, shear along z) do not enter the in-plane
// part, and are given only so that the section is valid.
FrameSection3d InPlaneSection(const BeamSection& s, const BeamShear& shear) {
  CheckSection(s);
  if (!(shear.area >= 0) || !std::isfinite(shear.area)) {
    throw InputError("beam section", "the shear area must be >= 0 and finite");
  }
  FrameSection3d t;
  t.E = s.E;
  t.nu = shear.nu;
  t.A = s.A;
  t.Iy = t.Iz = t.J = s.I;
  t.rho = s.rho;
  t.shear_area_y = t.shear_area_z = shear.area;
  return t;
}

BeamTheory Theory(const BeamShear& shear) {
  return shear.area > 0 ? BeamTheory::kTimoshenko : BeamTheory::kEulerBernoulli;
}

// Rows and columns ux, uy, rz of both ends of a 12 x 12 frame3d.h matrix.
Matrix6 InPlane(const Matrix12& g) {
  constexpr int kDofs[6] = {0, 1, 5, 6, 7, 11};
  Matrix6 out;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) out(i, j) = g(kDofs[i], kDofs[j]);
  return out;
}

// Local y in the plane, normal to the member: local z is then global z.
Eigen::Vector3d InPlaneNormal(double x1, double y1, double x2, double y2) {
  return {-(y2 - y1), x2 - x1, 0.0};
}

}  // namespace

Matrix6 Frame2dStiffness(const BeamSection& s, const BeamShear& shear, double x1,
                         double y1, double x2, double y2) {
  return InPlane(Frame3dStiffness(InPlaneSection(s, shear), {x1, y1, 0.0}, {x2, y2, 0.0},
                                  InPlaneNormal(x1, y1, x2, y2), Theory(shear)));
}

Matrix6 Frame2dConsistentMass(const BeamSection& s, const BeamShear& shear, double x1,
                              double y1, double x2, double y2) {
  return InPlane(Frame3dConsistentMass(InPlaneSection(s, shear), {x1, y1, 0.0},
                                       {x2, y2, 0.0}, InPlaneNormal(x1, y1, x2, y2),
                                       Theory(shear)));
}

Matrix6 Frame2dStiffness(const BeamSection& s, double x1, double y1, double x2,
                         double y2) {
  CheckSection(s);
  const Geometry g = ElementGeometry(x1, y1, x2, y2);
  const double l = g.length;
  const double ea = s.E * s.A / l;
  const double ei = s.E * s.I;
  const double k1 = 12 * ei / (l * l * l), k2 = 6 * ei / (l * l), k3 = 4 * ei / l,
               k4 = 2 * ei / l;
  Matrix6 k;
  // clang-format off
  k <<  ea,   0,   0, -ea,   0,   0,
         0,  k1,  k2,   0, -k1,  k2,
         0,  k2,  k3,   0, -k2,  k4,
       -ea,   0,   0,  ea,   0,   0,
         0, -k1, -k2,   0,  k1, -k2,
         0,  k2,  k4,   0, -k2,  k3;
  // clang-format on
  return g.transform.transpose() * k * g.transform;
}

Matrix6 Frame2dRotaryInertiaMass(const BeamSection& s, double x1, double y1, double x2,
                                 double y2) {
  CheckSection(s);
  const Geometry g = ElementGeometry(x1, y1, x2, y2);
  const double l = g.length, r = s.rho * s.I / (30 * l);
  Matrix6 local = Matrix6::Zero();
  const int idx[4] = {1, 2, 4, 5};  // v1, theta1, v2, theta2
  // clang-format off
  const double m[4][4] = {{   36,   3 * l,   -36,   3 * l},
                          {3 * l, 4 * l * l, -3 * l,  -l * l},
                          {  -36,  -3 * l,    36,  -3 * l},
                          {3 * l,  -l * l, -3 * l, 4 * l * l}};
  // clang-format on
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) local(idx[i], idx[j]) = r * m[i][j];
  return g.transform.transpose() * local * g.transform;
}

Matrix6 Frame2dConsistentMass(const BeamSection& s, double x1, double y1, double x2,
                              double y2) {
  CheckSection(s);
  const Geometry g = ElementGeometry(x1, y1, x2, y2);
  const double m = s.rho * s.A;
  Matrix6 local = Matrix6::Zero();
  const double axial = m * g.length / 6.0;
  local(0, 0) = local(3, 3) = 2 * axial;
  local(0, 3) = local(3, 0) = axial;
  AddTransverseConsistent(m, g.length, &local);
  return g.transform.transpose() * local * g.transform;
}

Matrix6 Frame2dTransverseMass(double mass_per_length, double x1, double y1, double x2,
                              double y2) {
  if (!(mass_per_length > 0) || !std::isfinite(mass_per_length)) {
    throw InputError("transverse mass", "mass per length must be positive and finite");
  }
  const Geometry g = ElementGeometry(x1, y1, x2, y2);
  Matrix6 local = Matrix6::Zero();
  AddTransverseConsistent(mass_per_length, g.length, &local);
  return g.transform.transpose() * local * g.transform;
}

}  // namespace femup
