// 2D frame element matrices (core/include/femup/core/fe/fe.h), checked against textbook
// entries, rigid-body kinematics and mass totals computed by hand.
#include "femup/core/fe/fe.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <vector>

#include "femup/core/errors.h"
#include "paper_beam.h"

namespace femup {
namespace {

using fixtures::PaperSection;

using Vector6 = Eigen::Matrix<double, 6, 1>;

// Node coordinates of a few elements in general position (length, angle).
struct Segment {
  double x1, y1, x2, y2;
};
std::vector<Segment> TestSegments() {
  return {{0.0, 0.0, 1.0, 0.0},
          {0.0, 0.0, 0.0, 0.7},
          {0.3, -0.2, 1.1, 0.4},
          {2.0, 1.0, 1.2, 2.5},
          {-1.0, 3.0, -1.6, 2.1}};
}

double Length(const Segment& g) { return std::hypot(g.x2 - g.x1, g.y2 - g.y1); }

// Rigid-body motions in global DOFs [u1 v1 t1 u2 v2 t2]: translation in x,
// translation in y, and a small rotation about the origin (u = -y, v = x, t = 1).
Vector6 TranslationX() { return (Vector6() << 1, 0, 0, 1, 0, 0).finished(); }
Vector6 TranslationY() { return (Vector6() << 0, 1, 0, 0, 1, 0).finished(); }
Vector6 Rotation(const Segment& g) {
  return (Vector6() << -g.y1, g.x1, 1, -g.y2, g.x2, 1).finished();
}

TEST(Frame2dStiffness, AxialElementMatchesTextbookEntries) {
  const BeamSection s = PaperSection();
  const double l = 0.19;
  const Matrix6 k = Frame2dStiffness(s, 0, 0, l, 0);
  const double ea = s.E * s.A / l, ei = s.E * s.I;
  const double tol = 1e-12;
  EXPECT_NEAR(k(0, 0), ea, tol * ea);
  EXPECT_NEAR(k(0, 3), -ea, tol * ea);
  EXPECT_NEAR(k(1, 1), 12 * ei / (l * l * l), tol * ea);
  EXPECT_NEAR(k(1, 2), 6 * ei / (l * l), tol * ea);
  EXPECT_NEAR(k(2, 2), 4 * ei / l, tol * ea);
  EXPECT_NEAR(k(2, 5), 2 * ei / l, tol * ea);
  EXPECT_NEAR(k(4, 5), -6 * ei / (l * l), tol * ea);
  EXPECT_EQ(k(0, 1), 0.0);
  EXPECT_EQ(k(0, 2), 0.0);
}

TEST(Frame2dStiffness, Symmetric) {
  for (const Segment& g : TestSegments()) {
    const Matrix6 k = Frame2dStiffness(PaperSection(), g.x1, g.y1, g.x2, g.y2);
    EXPECT_LE((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-14 * k.cwiseAbs().maxCoeff());
  }
}

TEST(Frame2dStiffness, RigidBodyMotionsAreTheNullSpace) {
  for (const Segment& g : TestSegments()) {
    const Matrix6 k = Frame2dStiffness(PaperSection(), g.x1, g.y1, g.x2, g.y2);
    const double scale = k.cwiseAbs().maxCoeff();
    EXPECT_LE((k * TranslationX()).norm(), 1e-12 * scale);
    EXPECT_LE((k * TranslationY()).norm(), 1e-12 * scale);
    const Vector6 r = Rotation(g);
    EXPECT_LE((k * r).norm(), 1e-12 * scale * r.norm());
    // Exactly three zero eigenvalues, three positive: no other mechanism.
    Eigen::SelfAdjointEigenSolver<Matrix6> es(k);
    const Vector6 ev = es.eigenvalues();
    for (int i = 0; i < 3; ++i) EXPECT_LE(std::abs(ev[i]), 1e-10 * scale) << i;
    for (int i = 3; i < 6; ++i) EXPECT_GT(ev[i], 1e-6 * scale) << i;
  }
}

TEST(Frame2dStiffness, AxialStretchEnergy) {
  // Stretch along the element axis by delta: strain energy EA delta^2 / (2 L).
  const BeamSection s = PaperSection();
  for (const Segment& g : TestSegments()) {
    const double l = Length(g);
    const double c = (g.x2 - g.x1) / l, sn = (g.y2 - g.y1) / l;
    const double delta = 1e-3;
    Vector6 u = Vector6::Zero();
    u[3] = delta * c;
    u[4] = delta * sn;
    const Matrix6 k = Frame2dStiffness(s, g.x1, g.y1, g.x2, g.y2);
    const double energy = 0.5 * u.dot(k * u);
    const double expected = s.E * s.A * delta * delta / (2 * l);
    EXPECT_NEAR(energy, expected, 1e-12 * expected);
  }
}

TEST(Frame2dConsistentMass, TotalTranslationalMassInEachDirection) {
  const BeamSection s = PaperSection();
  for (const Segment& g : TestSegments()) {
    const Matrix6 m = Frame2dConsistentMass(s, g.x1, g.y1, g.x2, g.y2);
    const double total = s.rho * s.A * Length(g);
    EXPECT_NEAR(TranslationX().dot(m * TranslationX()), total, 1e-12 * total);
    EXPECT_NEAR(TranslationY().dot(m * TranslationY()), total, 1e-12 * total);
    // A diagonal translation (1, 1) carries the same mass in both directions.
    const Vector6 diag = TranslationX() + TranslationY();
    EXPECT_NEAR(diag.dot(m * diag), 2 * total, 1e-12 * total);
    // x and y translations are not coupled by the mass.
    EXPECT_NEAR(TranslationX().dot(m * TranslationY()), 0.0, 1e-12 * total);
  }
}

TEST(Frame2dConsistentMass, SymmetricPositiveDefinite) {
  for (const Segment& g : TestSegments()) {
    const Matrix6 m = Frame2dConsistentMass(PaperSection(), g.x1, g.y1, g.x2, g.y2);
    EXPECT_LE((m - m.transpose()).cwiseAbs().maxCoeff(), 1e-14 * m.cwiseAbs().maxCoeff());
    Eigen::SelfAdjointEigenSolver<Matrix6> es(m);
    EXPECT_GT(es.eigenvalues().minCoeff(), 0.0);
  }
}

TEST(Frame2dConsistentMass, AxialElementMatchesTextbookEntries) {
  const BeamSection s = PaperSection();
  const double l = 0.25;
  const Matrix6 m = Frame2dConsistentMass(s, 0, 0, l, 0);
  const double ml = s.rho * s.A * l;
  const double tol = 1e-13 * ml;
  EXPECT_NEAR(m(0, 0), ml / 3, tol);
  EXPECT_NEAR(m(0, 3), ml / 6, tol);
  EXPECT_NEAR(m(1, 1), 156 * ml / 420, tol);
  EXPECT_NEAR(m(1, 2), 22 * l * ml / 420, tol);
  EXPECT_NEAR(m(1, 4), 54 * ml / 420, tol);
  EXPECT_NEAR(m(1, 5), -13 * l * ml / 420, tol);
  EXPECT_NEAR(m(2, 2), 4 * l * l * ml / 420, tol);
  EXPECT_NEAR(m(2, 5), -3 * l * l * ml / 420, tol);
}

TEST(Frame2dTransverseMass, NoAxialInertiaForInclinedElement) {
  const double mass_per_length = 6.9;
  for (const Segment& g : TestSegments()) {
    const double l = Length(g);
    const double c = (g.x2 - g.x1) / l, s = (g.y2 - g.y1) / l;
    const Matrix6 m = Frame2dTransverseMass(mass_per_length, g.x1, g.y1, g.x2, g.y2);
    const double total = mass_per_length * l;
    // Translation along the member axis: no inertia at all (M a = 0).
    const Vector6 axial = (Vector6() << c, s, 0, c, s, 0).finished();
    EXPECT_LE((m * axial).norm(), 1e-12 * total);
    // Translation normal to the member: the full mass.
    const Vector6 normal = (Vector6() << -s, c, 0, -s, c, 0).finished();
    EXPECT_NEAR(normal.dot(m * normal), total, 1e-12 * total);
    // Symmetric.
    EXPECT_LE((m - m.transpose()).cwiseAbs().maxCoeff(), 1e-14 * total);
  }
}

TEST(Frame2dTransverseMass, IsConsistentMassMinusAxialPart) {
  // With mass_per_length = rho A, the consistent mass is the transverse part
  // plus the axial bar mass (rho A L / 6) [2 1; 1 2] along the member axis.
  const BeamSection s = PaperSection();
  const Segment g{0.3, -0.2, 1.1, 0.4};
  const double l = Length(g);
  const double c = (g.x2 - g.x1) / l, sn = (g.y2 - g.y1) / l;
  Eigen::Matrix<double, 2, 6> axial = Eigen::Matrix<double, 2, 6>::Zero();
  axial(0, 0) = c;
  axial(0, 1) = sn;
  axial(1, 3) = c;
  axial(1, 4) = sn;
  Eigen::Matrix2d bar;
  bar << 2, 1, 1, 2;
  bar *= s.rho * s.A * l / 6;
  const Matrix6 expected = Frame2dTransverseMass(s.rho * s.A, g.x1, g.y1, g.x2, g.y2) +
                           axial.transpose() * bar * axial;
  const Matrix6 full = Frame2dConsistentMass(s, g.x1, g.y1, g.x2, g.y2);
  EXPECT_LE((full - expected).cwiseAbs().maxCoeff(), 1e-14 * full.cwiseAbs().maxCoeff());
}

// Sorted eigenvalues of a symmetric 6x6 matrix.
Vector6 Spectrum(const Matrix6& a) {
  return Eigen::SelfAdjointEigenSolver<Matrix6>(a).eigenvalues();
}

TEST(Frame2dElement, RotationInvariance) {
  const BeamSection s = PaperSection();
  const double l = 0.4;
  const Matrix6 kx = Frame2dStiffness(s, 0, 0, l, 0);
  const Matrix6 ky = Frame2dStiffness(s, 0, 0, 0, l);
  const Matrix6 mx = Frame2dConsistentMass(s, 0, 0, l, 0);
  const Matrix6 my = Frame2dConsistentMass(s, 0, 0, 0, l);
  // Same element at 37 degrees, shifted away from the origin.
  const double a = 37.0 * std::acos(-1.0) / 180.0;
  const double x0 = 1.5, y0 = -0.8;
  const Matrix6 ka =
      Frame2dStiffness(s, x0, y0, x0 + l * std::cos(a), y0 + l * std::sin(a));
  const Matrix6 ma =
      Frame2dConsistentMass(s, x0, y0, x0 + l * std::cos(a), y0 + l * std::sin(a));
  const double ks = kx.cwiseAbs().maxCoeff(), ms = mx.cwiseAbs().maxCoeff();
  EXPECT_LE((Spectrum(kx) - Spectrum(ky)).cwiseAbs().maxCoeff(), 1e-12 * ks);
  EXPECT_LE((Spectrum(kx) - Spectrum(ka)).cwiseAbs().maxCoeff(), 1e-12 * ks);
  EXPECT_LE((Spectrum(mx) - Spectrum(my)).cwiseAbs().maxCoeff(), 1e-12 * ms);
  EXPECT_LE((Spectrum(mx) - Spectrum(ma)).cwiseAbs().maxCoeff(), 1e-12 * ms);
  // The generalised eigenvalues (free-element frequencies) agree as well.
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6> ex(kx, mx), ey(ky, my), ea(ka, ma);
  const double top = ex.eigenvalues().maxCoeff();
  EXPECT_LE((ex.eigenvalues() - ey.eigenvalues()).cwiseAbs().maxCoeff(), 1e-10 * top);
  EXPECT_LE((ex.eigenvalues() - ea.eigenvalues()).cwiseAbs().maxCoeff(), 1e-10 * top);
}

TEST(Frame2dElement, ElementAlongYIsElementAlongXRotated) {
  // For the element along +y the local axis is global y and the local
  // transverse direction is global -x: local = R global with
  // R = [0 1 0; -1 0 0; 0 0 1], so K_y = T' K_x T with T = blockdiag(R, R).
  const BeamSection s = PaperSection();
  const double l = 0.3;
  Eigen::Matrix3d r;
  r << 0, 1, 0, -1, 0, 0, 0, 0, 1;
  Matrix6 t = Matrix6::Zero();
  t.block<3, 3>(0, 0) = r;
  t.block<3, 3>(3, 3) = r;
  const Matrix6 kx = Frame2dStiffness(s, 0, 0, l, 0);
  const Matrix6 ky = Frame2dStiffness(s, 0, 0, 0, l);
  EXPECT_LE((t.transpose() * kx * t - ky).cwiseAbs().maxCoeff(),
            1e-12 * kx.cwiseAbs().maxCoeff());
  const Matrix6 mx = Frame2dConsistentMass(s, 0, 0, l, 0);
  const Matrix6 my = Frame2dConsistentMass(s, 0, 0, 0, l);
  EXPECT_LE((t.transpose() * mx * t - my).cwiseAbs().maxCoeff(),
            1e-12 * mx.cwiseAbs().maxCoeff());
}

TEST(Frame2dElement, InvalidSectionsThrow) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<BeamSection> bad;
  for (int field = 0; field < 4; ++field) {
    for (double value : {0.0, -1.0, nan, inf}) {
      BeamSection s = PaperSection();
      double* target[4] = {&s.E, &s.A, &s.I, &s.rho};
      *target[field] = value;
      bad.push_back(s);
    }
  }
  for (const BeamSection& s : bad) {
    EXPECT_THROW(Frame2dStiffness(s, 0, 0, 1, 0), InputError)
        << s.E << " " << s.A << " " << s.I << " " << s.rho;
    EXPECT_THROW(Frame2dConsistentMass(s, 0, 0, 1, 0), InputError)
        << s.E << " " << s.A << " " << s.I << " " << s.rho;
  }
}

TEST(Frame2dElement, DegenerateGeometryAndMassPerLengthThrow) {
  const BeamSection s = PaperSection();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Frame2dStiffness(s, 1, 2, 1, 2), InputError);
  EXPECT_THROW(Frame2dConsistentMass(s, 1, 2, 1, 2), InputError);
  EXPECT_THROW(Frame2dStiffness(s, 0, 0, nan, 1), InputError);
  EXPECT_THROW(Frame2dTransverseMass(1.0, 0, 0, 0, 0), InputError);
  EXPECT_THROW(Frame2dTransverseMass(0.0, 0, 0, 1, 0), InputError);
  EXPECT_THROW(Frame2dTransverseMass(-2.0, 0, 0, 1, 0), InputError);
  EXPECT_THROW(Frame2dTransverseMass(nan, 0, 0, 1, 0), InputError);
}

// The sheared element through frame3d.h, checked against the 2D element (no
// shear) and against the Timoshenko cantilever's tip deflection under a tip
// load normal to it, P L^3 / (3 E I) + P L / (kappa A G), which this element
// reproduces exactly (its shape functions solve the static beam equations).
TEST(Frame2dShear, WithoutShearAreaEqualsTheEulerBernoulliElement) {
  for (const Segment& g : TestSegments()) {
    const Matrix6 k = Frame2dStiffness(PaperSection(), g.x1, g.y1, g.x2, g.y2);
    const Matrix6 m = Frame2dConsistentMass(PaperSection(), g.x1, g.y1, g.x2, g.y2);
    const Matrix6 k3 =
        Frame2dStiffness(PaperSection(), BeamShear{}, g.x1, g.y1, g.x2, g.y2);
    const Matrix6 m3 =
        Frame2dConsistentMass(PaperSection(), BeamShear{}, g.x1, g.y1, g.x2, g.y2);
    EXPECT_LE((k - k3).cwiseAbs().maxCoeff(), 1e-12 * k.cwiseAbs().maxCoeff());
    EXPECT_LE((m - m3).cwiseAbs().maxCoeff(), 1e-12 * m.cwiseAbs().maxCoeff());
  }
}

TEST(Frame2dShear, CantileverTipDeflectionHasTheShearTerm) {
  const BeamSection s{210e9, 0.01, 2e-5, 7850};
  const BeamShear shear{0.45 * s.A, 0.3};
  const double g_mod = s.E / (2 * 1.3), p = 1e4;
  for (const Segment& g : TestSegments()) {
    const double l = Length(g);
    const Matrix6 k = Frame2dStiffness(s, shear, g.x1, g.y1, g.x2, g.y2);
    // End 1 clamped; a load P normal to the member at end 2.
    const Eigen::Vector2d e((g.x2 - g.x1) / l, (g.y2 - g.y1) / l);
    const Eigen::Vector3d f(-e.y() * p, e.x() * p, 0.0);
    const Eigen::Vector3d u = k.bottomRightCorner<3, 3>().ldlt().solve(f);
    const double deflection = u.head<2>().dot(Eigen::Vector2d(-e.y(), e.x()));
    const double expected =
        p * l * l * l / (3 * s.E * s.I) + p * l / (shear.area * g_mod);
    EXPECT_NEAR(deflection, expected, 1e-9 * expected) << l;
    EXPECT_NEAR(u.head<2>().dot(e), 0.0, 1e-9 * expected);  // no axial motion
    // Stiffer without shear: the Euler-Bernoulli element gives the bending term.
    const Matrix6 k0 = Frame2dStiffness(s, g.x1, g.y1, g.x2, g.y2);
    const Eigen::Vector3d u0 = k0.bottomRightCorner<3, 3>().ldlt().solve(f);
    EXPECT_NEAR(u0.head<2>().norm(), p * l * l * l / (3 * s.E * s.I), 1e-9 * expected);
  }
}

// The section's rotary inertia: the kinetic energy of a slope field the cubic
// reproduces, integral of rho I theta^2 along the element: a rigid rotation
// (rho I L theta^2), a quadratic deflection v = x^2 / 2 (slope x: rho I L^3 /
// 3); a rigid translation has none.
TEST(Frame2dRotaryInertiaMass, IsTheSlopesKineticEnergy) {
  const BeamSection s{210e9, 0.01, 2e-5, 7850};
  for (const Segment& g : TestSegments()) {
    const double l = Length(g), dx = g.x2 - g.x1, dy = g.y2 - g.y1;
    const Matrix6 m = Frame2dRotaryInertiaMass(s, g.x1, g.y1, g.x2, g.y2);
    EXPECT_LT((m - m.transpose()).norm(), 1e-12 * m.norm());
    const double theta = 0.3;
    Vector6 u;
    u << 0, 0, theta, -theta * dy, theta * dx, theta;
    EXPECT_NEAR(u.dot(m * u), s.rho * s.I * l * theta * theta, 1e-10 * s.rho * s.I * l);
    // v = x^2 / 2 along the member's normal (-e_y, e_x), slope x.
    const double ex = dx / l, ey = dy / l, v2 = 0.5 * l * l;
    u << 0, 0, 0, -ey * v2, ex * v2, l;
    EXPECT_NEAR(u.dot(m * u), s.rho * s.I * l * l * l / 3,
                1e-10 * s.rho * s.I * l * l * l);
    u << 0.7, -0.2, 0, 0.7, -0.2, 0;
    EXPECT_NEAR(u.dot(m * u), 0.0, 1e-14 * m.norm());
  }
  EXPECT_THROW(Frame2dRotaryInertiaMass(BeamSection{}, 0, 0, 1, 0), InputError);
}

TEST(Frame2dShear, RefusesANegativeShearArea) {
  EXPECT_THROW(Frame2dStiffness(PaperSection(), BeamShear{-1.0, 0.3}, 0, 0, 1, 0),
               InputError);
  EXPECT_THROW(Frame2dConsistentMass(PaperSection(), BeamShear{0.01, 0.7}, 0, 0, 1, 0),
               InputError);
}

}  // namespace
}  // namespace femup
