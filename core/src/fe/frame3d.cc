#include "femup/core/fe/frame3d.h"

#include <Eigen/Geometry>
#include <cmath>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"

namespace femup {
namespace {

// Local DOF indices.
constexpr int kU = 0, kV = 1, kW = 2, kRx = 3, kRy = 4, kRz = 5;

bool PositiveFinite(double x) { return x > 0 && std::isfinite(x); }
bool NonNegativeFinite(double x) { return x >= 0 && std::isfinite(x); }

void Check(const FrameSection3d& s, double length, BeamTheory theory) {
  ThrowIfInvalid(s.Validate(theory), "frame section");
  if (!PositiveFinite(length)) {
    throw InputError("frame element", "length must be positive and finite");
  }
}

// Fills the upper triangle's mirror.
void Symmetrise(Matrix12* m) {
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < i; ++j) (*m)(i, j) = (*m)(j, i);
  }
}

// Two-node bar block c [1 -1; -1 1] (stiffness) or c [2 1; 1 2] (mass) on the
// local DOF d of both ends, upper triangle.
void AddBar(int d, double c, bool mass, Matrix12* m) {
  const int a = d, b = d + 6;
  (*m)(a, a) += mass ? 2 * c : c;
  (*m)(b, b) += mass ? 2 * c : c;
  (*m)(a, b) += mass ? c : -c;
}

// Bending in one plane: translation t, rotation r (local indices at end 1; end
// 2 is +6), sign s = +1 for the x-y plane (v, rz) and -1 for the x-z plane
// (w, ry), where a positive rotation ry lowers w. Upper triangle.
void AddBendingStiffness(int t, int r, double s, double ei, double phi, double l,
                         Matrix12* k) {
  const int t1 = t, r1 = r, t2 = t + 6, r2 = r + 6;
  const double c = ei / ((1 + phi) * l * l * l);
  (*k)(t1, t1) += 12 * c;
  (*k)(t1, r1) += s * 6 * l * c;
  (*k)(t1, t2) += -12 * c;
  (*k)(t1, r2) += s * 6 * l * c;
  (*k)(r1, r1) += (4 + phi) * l * l * c;
  (*k)(r1, t2) += -s * 6 * l * c;
  (*k)(r1, r2) += (2 - phi) * l * l * c;
  (*k)(t2, t2) += 12 * c;
  (*k)(t2, r2) += -s * 6 * l * c;
  (*k)(r2, r2) += (4 + phi) * l * l * c;
}

// Translational consistent mass of the same plane for mass per length mu
// (Przemieniecki's shear-deformable interpolation; phi = 0 gives the cubic
// Hermitian m L / 420 [156 22L 54 -13L; ...]). Upper triangle.
void AddBendingMass(int t, int r, double s, double mu, double phi, double l,
                    Matrix12* m) {
  const int t1 = t, r1 = r, t2 = t + 6, r2 = r + 6;
  const double q = mu * l / ((1 + phi) * (1 + phi)), p2 = phi * phi;
  const double tt = q * (13.0 / 35 + 7.0 / 10 * phi + p2 / 3);
  const double tt_far = q * (9.0 / 70 + 3.0 / 10 * phi + p2 / 6);
  const double tr = q * l * (11.0 / 210 + 11.0 / 120 * phi + p2 / 24);
  const double tr_far = q * l * (13.0 / 420 + 3.0 / 40 * phi + p2 / 24);
  const double rr = q * l * l * (1.0 / 105 + phi / 60 + p2 / 120);
  const double rr_far = q * l * l * (1.0 / 140 + phi / 60 + p2 / 120);
  (*m)(t1, t1) += tt;
  (*m)(t1, r1) += s * tr;
  (*m)(t1, t2) += tt_far;
  (*m)(t1, r2) += -s * tr_far;
  (*m)(r1, r1) += rr;
  (*m)(r1, t2) += s * tr_far;
  (*m)(r1, r2) += -rr_far;
  (*m)(t2, t2) += tt;
  (*m)(t2, r2) += -s * tr;
  (*m)(r2, r2) += rr;
}

// Shear parameters (phi_y for the x-y plane, phi_z for the x-z plane).
void ShearPhis(const FrameSection3d& s, double l, BeamTheory theory, double* phi_y,
               double* phi_z) {
  *phi_y = *phi_z = 0;
  if (theory != BeamTheory::kTimoshenko) return;
  const double g = s.ShearModulus();
  *phi_y = 12 * s.E * s.Iz / (g * s.shear_area_y * l * l);
  *phi_z = 12 * s.E * s.Iy / (g * s.shear_area_z * l * l);
}

Matrix12 Rotate(const Matrix12& t, const Matrix12& local) {
  Matrix12 g = t.transpose() * local * t;
  return 0.5 * (g + g.transpose());
}

}  // namespace

constexpr EnumName<BeamTheory> kBeamTheoryNames[] = {
    {BeamTheory::kEulerBernoulli, "euler_bernoulli"},
    {BeamTheory::kTimoshenko, "timoshenko"},
};

const char* ToString(BeamTheory theory) {
  return NameIn(kBeamTheoryNames, theory, "unknown");
}

bool BeamTheoryFromString(const std::string& text, BeamTheory* theory) {
  return ValueIn(kBeamTheoryNames, text, theory);
}

Invalid FrameSection3d::Validate(BeamTheory theory) const {
  const std::pair<const char*, double> positive[] = {{"E", E},   {"A", A}, {"Iy", Iy},
                                                     {"Iz", Iz}, {"J", J}, {"rho", rho}};
  for (const auto& [name, value] : positive) {
    if (!PositiveFinite(value)) return {name, "must be positive and finite"};
  }
  if (!NonNegativeFinite(G)) return {"G", "must be >= 0 and finite (0: from nu)"};
  if (G == 0 && !(nu > -1 && nu <= 0.5))
    return {"nu", "must be in (-1, 0.5] when G is 0"};
  if (!NonNegativeFinite(Ip)) return {"Ip", "must be >= 0 and finite (0: Iy + Iz)"};
  const bool timoshenko = theory == BeamTheory::kTimoshenko;
  const std::pair<const char*, double> shear[] = {{"shear_area_y", shear_area_y},
                                                  {"shear_area_z", shear_area_z}};
  for (const auto& [name, value] : shear) {
    if (timoshenko ? !PositiveFinite(value) : !NonNegativeFinite(value)) {
      return {name, timoshenko ? "must be positive for a Timoshenko beam"
                               : "must be >= 0 and finite"};
    }
  }
  return {};
}

FrameSection3d CircularTube(double diameter, double wall, double E, double nu,
                            double rho) {
  if (!PositiveFinite(diameter)) {
    throw InputError("tube.diameter", "must be positive and finite");
  }
  if (!PositiveFinite(wall) || wall > diameter / 2) {
    throw InputError("tube.wall", "must be positive and at most half the diameter");
  }
  const double d = diameter, di = diameter - 2 * wall;
  FrameSection3d s;
  s.E = E;
  s.nu = nu;
  s.rho = rho;
  s.A = M_PI * (d * d - di * di) / 4;
  s.Iy = s.Iz = M_PI * (d * d * d * d - di * di * di * di) / 64;
  s.J = s.Ip = s.Iy + s.Iz;
  s.shear_area_y = s.shear_area_z = s.A / 2;
  return s;
}

Matrix12 Frame3dLocalStiffness(const FrameSection3d& s, double length,
                               BeamTheory theory) {
  Check(s, length, theory);
  const double l = length;
  double phi_y = 0, phi_z = 0;
  ShearPhis(s, l, theory, &phi_y, &phi_z);
  Matrix12 k = Matrix12::Zero();
  AddBar(kU, s.E * s.A / l, false, &k);
  AddBar(kRx, s.ShearModulus() * s.J / l, false, &k);
  AddBendingStiffness(kV, kRz, +1, s.E * s.Iz, phi_y, l, &k);
  AddBendingStiffness(kW, kRy, -1, s.E * s.Iy, phi_z, l, &k);
  Symmetrise(&k);
  return k;
}

Matrix12 Frame3dLocalConsistentMass(const FrameSection3d& s, double length,
                                    BeamTheory theory) {
  Check(s, length, theory);
  const double l = length, mu = s.rho * s.A;
  double phi_y = 0, phi_z = 0;
  ShearPhis(s, l, theory, &phi_y, &phi_z);
  Matrix12 m = Matrix12::Zero();
  AddBar(kU, mu * l / 6, true, &m);
  AddBar(kRx, s.rho * s.PolarInertia() * l / 6, true, &m);
  AddBendingMass(kV, kRz, +1, mu, phi_y, l, &m);
  AddBendingMass(kW, kRy, -1, mu, phi_z, l, &m);
  Symmetrise(&m);
  return m;
}

Matrix12 Frame3dLocalTransverseMass(double mass_per_length, double length) {
  if (!PositiveFinite(mass_per_length)) {
    throw InputError("transverse mass", "mass per length must be positive and finite");
  }
  if (!PositiveFinite(length)) {
    throw InputError("frame element", "length must be positive and finite");
  }
  Matrix12 m = Matrix12::Zero();
  AddBendingMass(kV, kRz, +1, mass_per_length, 0, length, &m);
  AddBendingMass(kW, kRy, -1, mass_per_length, 0, length, &m);
  Symmetrise(&m);
  return m;
}

Matrix12 Frame3dTransformation(const Eigen::Vector3d& end1, const Eigen::Vector3d& end2,
                               const Eigen::Vector3d& reference) {
  const Eigen::Vector3d d = end2 - end1;
  const double length = d.norm();
  if (!end1.allFinite() || !end2.allFinite() || !PositiveFinite(length)) {
    throw InputError("frame element", "ends coincide or are not finite");
  }
  const Eigen::Vector3d x = d / length;
  const double ref_norm = reference.norm();
  if (!reference.allFinite() || !(ref_norm > 0)) {
    throw InputError("frame element", "reference vector is zero or not finite");
  }
  Eigen::Vector3d y = reference - reference.dot(x) * x;
  if (!(y.norm() > 1e-9 * ref_norm)) {
    throw InputError("frame element",
                     "reference vector is parallel to the member: it cannot set local y");
  }
  y.normalize();
  const Eigen::Vector3d z = x.cross(y);
  Eigen::Matrix3d r;
  r.row(0) = x.transpose();
  r.row(1) = y.transpose();
  r.row(2) = z.transpose();
  Matrix12 t = Matrix12::Zero();
  for (int b = 0; b < 4; ++b) t.block<3, 3>(3 * b, 3 * b) = r;
  return t;
}

Matrix12 Frame3dStiffness(const FrameSection3d& s, const Eigen::Vector3d& end1,
                          const Eigen::Vector3d& end2, const Eigen::Vector3d& reference,
                          BeamTheory theory) {
  const Matrix12 t = Frame3dTransformation(end1, end2, reference);
  return Rotate(t, Frame3dLocalStiffness(s, (end2 - end1).norm(), theory));
}

Matrix12 Frame3dConsistentMass(const FrameSection3d& s, const Eigen::Vector3d& end1,
                               const Eigen::Vector3d& end2,
                               const Eigen::Vector3d& reference, BeamTheory theory) {
  const Matrix12 t = Frame3dTransformation(end1, end2, reference);
  return Rotate(t, Frame3dLocalConsistentMass(s, (end2 - end1).norm(), theory));
}

Matrix12 Frame3dTransverseMass(double mass_per_length, const Eigen::Vector3d& end1,
                               const Eigen::Vector3d& end2,
                               const Eigen::Vector3d& reference) {
  const Matrix12 t = Frame3dTransformation(end1, end2, reference);
  return Rotate(t, Frame3dLocalTransverseMass(mass_per_length, (end2 - end1).norm()));
}

}  // namespace femup
