// Local modifications along a cantilever (core/include/femup/core/fe/beam_modifications.h
// and CantileverSpec's lists in builders.h), checked against independent
// references: the element stiffness of fe.h, closed-form integrals of polynomial
// fields, exact frequency ratios, rigid-body kinetic energy, the Euler-Bernoulli
// frequency equation of a cantilever with a tip mass, and a finer mesh.
#include "femup/core/fe/beam_modifications.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "beam_dofs.h"
#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/fe.h"
#include "femup/studies/study.h"
#include "paper_beam.h"
#include "scratch_dir.h"

namespace femup {
namespace {

using fixtures::PaperSection;

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

using testing::ExpectInputError;

// Non-uniform mesh of 5 elements, 0.9 m.
const std::vector<double>& kHeights = fixtures::kNonUniformHeights;

CantileverSpec Spec(const std::vector<double>& heights, bool free_base) {
  return fixtures::PaperCantilever(heights, free_base);
}

Structure Cantilever(const std::vector<double>& heights, bool free_base) {
  return BuildCantilever(Spec(heights, free_base));
}

using fixtures::Dof;

double MaxAbs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

using fixtures::MonomialField;

// Unit axial translation uy = 1 on every node that has the DOF.
Eigen::VectorXd AxialTranslation(const Structure& s) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(s.dof_labels.size());
  for (std::size_t i = 0; i < s.dof_labels.size(); ++i) {
    if (s.dof_labels[i].size() > 3 &&
        s.dof_labels[i].compare(s.dof_labels[i].size() - 3, 3, ":uy") == 0) {
      u(i) = 1;
    }
  }
  return u;
}

// Natural frequencies (rad/s, ascending) of K, M split into bending modes
// (transverse ux/rz motion) and axial modes (uy); the two do not couple in a
// straight vertical cantilever.
struct Frequencies {
  std::vector<double> bending, axial;
};
Frequencies Modes(const Structure& s, const SparseMatrix& k, const SparseMatrix& m) {
  const Eigen::MatrixXd kd(k), md(m);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(kd, md);
  EXPECT_EQ(eig.info(), Eigen::Success);
  Frequencies f;
  for (int j = 0; j < eig.eigenvalues().size(); ++j) {
    double transverse = 0, axial = 0;
    for (std::size_t i = 0; i < s.dof_labels.size(); ++i) {
      const double v = std::abs(eig.eigenvectors()(i, j));
      double& part =
          s.dof_labels[i].find(":uy") != std::string::npos ? axial : transverse;
      part = std::max(part, v);
    }
    // Exact decoupling: the other part is round-off.
    EXPECT_LT(std::min(transverse, axial), 1e-8 * std::max(transverse, axial));
    (transverse > axial ? f.bending : f.axial).push_back(std::sqrt(eig.eigenvalues()(j)));
  }
  return f;
}

// Scatters the entries of `ke` (element DOFs [ux1 uy1 rz1 ux2 uy2 rz2] of element
// e) whose row and column are both in `keep` into the global DOFs by label.
Eigen::MatrixXd Scattered(const Structure& s, int e, const Matrix6& ke,
                          const std::vector<int>& keep) {
  static const char* kNames[3] = {"ux", "uy", "rz"};
  const int n = static_cast<int>(s.dof_labels.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  int dof[6];
  for (int i = 0; i < 6; ++i) {
    dof[i] = Dof(s, "n" + std::to_string(e + i / 3) + ":" + kNames[i % 3]);
  }
  for (int i : keep) {
    for (int j : keep) {
      if (dof[i] >= 0 && dof[j] >= 0) m(dof[i], dof[j]) += ke(i, j);
    }
  }
  return m;
}

// ---------------------------------------------------------------------------
// Axial force.

TEST(AxialForceStiffness, IsTheTextbookGeometricStiffnessOnEveryElement) {
  // P / (30 l) [36, 3l, -36, 3l; 3l, 4l^2, -3l, -l^2; -36, -3l, 36, -3l;
  // 3l, -l^2, -3l, 4l^2] on (w1, theta1, w2, theta2) with theta = dw/dz; here
  // rz = -dux/dz, so the rotation rows and columns change sign.
  const double force = -2500;
  for (bool free_base : {false, true}) {
    const Structure s = Cantilever(kHeights, free_base);
    Eigen::MatrixXd expected =
        Eigen::MatrixXd::Zero(s.dof_labels.size(), s.dof_labels.size());
    for (std::size_t e = 0; e + 1 < kHeights.size(); ++e) {
      const double l = kHeights[e + 1] - kHeights[e];
      Eigen::Matrix4d g;
      g << 36, 3 * l, -36, 3 * l, 3 * l, 4 * l * l, -3 * l, -l * l, -36, -3 * l, 36,
          -3 * l, 3 * l, -l * l, -3 * l, 4 * l * l;
      g *= force / (30 * l);
      const Eigen::Vector4d sign(1, -1, 1, -1);
      g = sign.asDiagonal() * g * sign.asDiagonal();
      Matrix6 k6 = Matrix6::Zero();
      const int at[4] = {0, 2, 3, 5};  // ux1, rz1, ux2, rz2 among the element's 6
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) k6(at[i], at[j]) = g(i, j);
      expected += Scattered(s, static_cast<int>(e), k6, {0, 1, 2, 3, 4, 5});
    }
    const Eigen::MatrixXd got(AxialForceStiffness(s, force));
    EXPECT_LT(MaxAbs(got - expected), 1e-9 * MaxAbs(expected)) << free_base;
    EXPECT_EQ(MaxAbs(Eigen::MatrixXd(AxialForceStiffness(s, 0.0))), 0.0);
  }
}

TEST(AxialForceStiffness, CompressionBucklesAUniformCantileverAtEulersLoad) {
  // K x = P G x, G the geometric stiffness of a unit compression: the lowest
  // P is pi^2 E I / (4 L^2).
  const double length = 1.9;
  const BeamSection sec = PaperSection();
  const Structure s = Cantilever(UniformHeights(length, 40), false);
  const Eigen::MatrixXd g = -Eigen::MatrixXd(AxialForceStiffness(s, -1.0));
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
      g, Eigen::MatrixXd(s.stiffness));
  ASSERT_EQ(eig.info(), Eigen::Success);
  const double euler = M_PI * M_PI * sec.E * sec.I / (4 * length * length);
  EXPECT_NEAR(1 / eig.eigenvalues().maxCoeff() / euler, 1.0, 1e-7);
}

TEST(AxialForceStiffness, TensionStiffensAndCompressionSoftensOnlyTheBendingModes) {
  const double length = 1.9;
  const BeamSection sec = PaperSection();
  const double euler = M_PI * M_PI * sec.E * sec.I / (4 * length * length);
  CantileverSpec spec = Spec(UniformHeights(length, 20), false);
  const Structure bare = BuildCantilever(spec);
  const Frequencies f0 = Modes(bare, bare.stiffness, bare.mass);
  for (double ratio : {-0.5, 0.5, 3.0}) {
    spec.axial_force = ratio * euler;
    const Structure s = BuildCantilever(spec);
    const Frequencies f = Modes(s, s.stiffness, s.mass);
    ASSERT_EQ(f.bending.size(), f0.bending.size());
    for (std::size_t k = 0; k < 4; ++k) {
      if (ratio > 0) {
        EXPECT_GT(f.bending[k], f0.bending[k] * (1 + 1e-4)) << ratio << k;
      } else {
        EXPECT_LT(f.bending[k], f0.bending[k] * (1 - 1e-4)) << ratio << k;
      }
    }
    for (std::size_t k = 0; k < f0.axial.size(); ++k)
      EXPECT_NEAR(f.axial[k], f0.axial[k], 1e-9 * f0.axial[k]);
  }
  spec.axial_force = kInf;
  ExpectInputError([&] { BuildCantilever(spec); }, {"model.axial_force"});
  ExpectInputError([&] { AxialForceStiffness(bare, kNaN); }, {"axial_force", "N"});
}

// ---------------------------------------------------------------------------
// Bending stiffness.

TEST(BendingStiffnessOverInterval, WholeElementIsTheBendingPartOfFrame2dStiffness) {
  const BeamSection sec = PaperSection();
  for (bool free_base : {false, true}) {
    const Structure s = Cantilever(kHeights, free_base);
    for (int e = 0; e + 1 < static_cast<int>(kHeights.size()); ++e) {
      const Matrix6 ke = Frame2dStiffness(sec, 0, kHeights[e], 0, kHeights[e + 1]);
      const Eigen::MatrixXd expected = Scattered(s, e, ke, {0, 2, 3, 5});
      const Eigen::MatrixXd got =
          BendingStiffnessOverInterval(s, kHeights[e], kHeights[e + 1], sec.E * sec.I);
      EXPECT_LE(MaxAbs(got - expected), 1e-12 * MaxAbs(expected))
          << "element " << e << ", free base " << free_base;
    }
  }
}

TEST(BendingStiffnessOverInterval, PiecesSumToTheWhole) {
  const Structure s = Cantilever(kHeights, true);
  const double dei = -3.7e3;
  for (double split : {0.41, 0.5, 0.11}) {
    const Eigen::MatrixXd whole = BendingStiffnessOverInterval(s, 0.07, 0.63, dei);
    const Eigen::MatrixXd lower = BendingStiffnessOverInterval(s, 0.07, split, dei);
    const Eigen::MatrixXd upper = BendingStiffnessOverInterval(s, split, 0.63, dei);
    EXPECT_LE(MaxAbs(lower + upper - whole), 1e-12 * MaxAbs(whole)) << split;
    EXPECT_EQ(MaxAbs(whole - whole.transpose()), 0.0);
  }
}

// Quadratic and cubic fields are exact in the Hermite elements, so the energy
// delta_ei * integral of u_i'' u_j'' over any interval is exact too:
// (z^2)'' = 2, (z^3)'' = 6 z.
TEST(BendingStiffnessOverInterval, PolynomialFieldsOnPartialElementsMatchClosedForm) {
  const Structure s = Cantilever(kHeights, true);
  const double dei = 2.5e4;
  const Eigen::VectorXd u2 = MonomialField(s, kHeights, 2);
  const Eigen::VectorXd u3 = MonomialField(s, kHeights, 3);
  struct Interval {
    double z0, z1;
  };
  for (Interval c : {Interval{0.07, 0.63}, Interval{0.2, 0.3}, Interval{0.0, 0.9},
                     Interval{0.5, 0.555}}) {
    const SparseMatrix k = BendingStiffnessOverInterval(s, c.z0, c.z1, dei);
    const double tol = 1e-10 * dei;
    EXPECT_NEAR(u2.dot(k * u2), dei * 4 * (c.z1 - c.z0), tol) << c.z0;
    EXPECT_NEAR(u2.dot(k * u3), dei * 6 * (c.z1 * c.z1 - c.z0 * c.z0), tol) << c.z0;
    EXPECT_NEAR(u3.dot(k * u3), dei * 12 * (std::pow(c.z1, 3) - std::pow(c.z0, 3)), tol)
        << c.z0;
    // Rigid motions and axial motion carry no bending energy.
    const Eigen::VectorXd u1 = MonomialField(s, kHeights, 1);
    EXPECT_NEAR((k * u1).norm(), 0.0, 1e-9 * dei);
    EXPECT_NEAR((k * MonomialField(s, kHeights, 0)).norm(), 0.0, 1e-9 * dei);
    EXPECT_EQ((k * AxialTranslation(s)).norm(), 0.0);
  }
}

TEST(BendingStiffnessOverInterval, WholeLengthFactorScalesBendingFrequencies) {
  const double length = 1.9;
  const CantileverSpec base = Spec(UniformHeights(length, 10), false);
  const Structure s0 = BuildCantilever(base);
  const Frequencies f0 = Modes(s0, s0.stiffness, s0.mass);
  ASSERT_EQ(f0.bending.size(), 20u);
  ASSERT_EQ(f0.axial.size(), 10u);
  for (double factor : {0.3, -0.4}) {
    CantileverSpec spec = base;
    spec.stiffness_changes.push_back({0.0, length, factor});
    const Structure s = BuildCantilever(spec);
    const Frequencies f = Modes(s, s.stiffness, s.mass);
    ASSERT_EQ(f.bending.size(), f0.bending.size());
    ASSERT_EQ(f.axial.size(), f0.axial.size());
    for (std::size_t i = 0; i < f0.bending.size(); ++i) {
      EXPECT_NEAR(f.bending[i] / f0.bending[i], std::sqrt(1 + factor), 1e-8)
          << "bending mode " << i + 1;
    }
    for (std::size_t i = 0; i < f0.axial.size(); ++i) {
      EXPECT_NEAR(f.axial[i] / f0.axial[i], 1.0, 1e-8) << "axial mode " << i + 1;
    }
    // The elements keep their own matrices.
    for (std::size_t e = 0; e < s.elements.size(); ++e) {
      EXPECT_EQ(
          MaxAbs(Eigen::MatrixXd(s.elements[e].stiffness - s0.elements[e].stiffness)),
          0.0);
    }
  }
}

// ---------------------------------------------------------------------------
// Transverse mass.

TEST(TransverseMassOverInterval, RhoAOverTheWholeLengthLowersBendingBySqrt2) {
  const double length = 1.9;
  const BeamSection sec = PaperSection();
  const CantileverSpec base = Spec(UniformHeights(length, 10), false);
  const Structure s0 = BuildCantilever(base);
  const Frequencies f0 = Modes(s0, s0.stiffness, s0.mass);
  CantileverSpec spec = base;
  spec.distributed_masses.push_back({0.0, length, sec.rho * sec.A, 0.0});
  const Structure s = BuildCantilever(spec);
  const Frequencies f = Modes(s, s.stiffness, s.mass);
  ASSERT_EQ(f.bending.size(), f0.bending.size());
  ASSERT_EQ(f.axial.size(), f0.axial.size());
  for (std::size_t i = 0; i < f0.bending.size(); ++i) {
    EXPECT_NEAR(f.bending[i] / f0.bending[i], 1 / std::sqrt(2.0), 1e-8)
        << "bending mode " << i + 1;
  }
  for (std::size_t i = 0; i < f0.axial.size(); ++i) {
    EXPECT_NEAR(f.axial[i] / f0.axial[i], 1.0, 1e-8) << "axial mode " << i + 1;
  }
}

// Closed form of the integral of z^k m(z) over [z0, min(z1, top)], m the mass per
// length of the header (full below z1 - fade, linear to 0 at z1).
double Moment(int k, double mpl, double z0, double z1, double fade, double top) {
  const auto power = [k](double z, int extra) {
    return std::pow(z, k + 1 + extra) / (k + 1 + extra);
  };
  const double hi = std::min(z1, top);
  const double a = std::min(hi, std::max(z0, z1 - fade));  // start of the fade
  double result = mpl * (power(a, 0) - power(z0, 0));
  if (fade > 0 && hi > a) {
    result +=
        mpl / fade * (z1 * (power(hi, 0) - power(a, 0)) - (power(hi, 1) - power(a, 1)));
  }
  return result;
}

TEST(TransverseMassOverInterval, RigidTranslationCarriesTheIntervalMass) {
  const Structure s = Cantilever(kHeights, true);
  const double mpl = 1.3;
  const Eigen::VectorXd ux = MonomialField(s, kHeights, 0);
  const Eigen::VectorXd uy = AxialTranslation(s);
  struct Case {
    double z0, z1, fade, expected_over_mpl;
  };
  const Case cases[] = {
      {0.07, 0.63, 0.0, 0.56},
      {0.33, 0.34, 0.0, 0.01},
      {0.0, 0.9, 0.0, 0.9},
      {0.07, 0.63, 0.1, 0.56 - 0.05},
      {0.2, 0.3, 0.4, 0.1 * 0.1 / 2 / 0.4},  // fade longer than the interval
      {0.5, 1.5, 0.0, 0.4},                  // clipped at the tip
      {0.5, 1.5, 0.8, 0.2 + (1.5 * 0.2 - (0.81 - 0.49) / 2) / 0.8},
  };
  for (const Case& c : cases) {
    const SparseMatrix m = TransverseMassOverInterval(s, c.z0, c.z1, mpl, c.fade);
    EXPECT_NEAR(ux.dot(m * ux), mpl * c.expected_over_mpl, 1e-13)
        << c.z0 << " " << c.z1 << " " << c.fade;
    EXPECT_EQ((m * uy).norm(), 0.0);  // transverse only
    const Eigen::MatrixXd dense(m);
    EXPECT_EQ(MaxAbs(dense - dense.transpose()), 0.0);
  }
}

TEST(TransverseMassOverInterval, CubicFieldsMatchClosedFormMoments) {
  const double mpl = 0.9, top = kHeights.back();
  for (bool free_base : {true, false}) {
    const Structure s = Cantilever(kHeights, free_base);
    const int first = free_base ? 0 : 2;  // clamped: only fields with u(0) = u'(0) = 0
    struct Case {
      double z0, z1, fade;
    };
    for (Case c : {Case{0.07, 0.63, 0.0}, Case{0.07, 0.63, 0.2}, Case{0.4, 0.45, 0.3},
                   Case{0.6, 2.0, 1.2}}) {
      const SparseMatrix m = TransverseMassOverInterval(s, c.z0, c.z1, mpl, c.fade);
      for (int i = first; i < 4; ++i) {
        for (int j = first; j < 4; ++j) {
          const Eigen::VectorXd ui = MonomialField(s, kHeights, i);
          const Eigen::VectorXd uj = MonomialField(s, kHeights, j);
          EXPECT_NEAR(ui.dot(m * uj), Moment(i + j, mpl, c.z0, c.z1, c.fade, top), 1e-12)
              << "z^" << i << " z^" << j << " on [" << c.z0 << ", " << c.z1 << "] fade "
              << c.fade;
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Point mass.

TEST(PointMassAt, AtANodeEqualsALumpedMass) {
  const double mass = 0.37, inertia = 2.1e-3;
  for (bool free_base : {true, false}) {
    const CantileverSpec spec = Spec(kHeights, free_base);
    const Structure s = BuildCantilever(spec);
    const int n = static_cast<int>(s.dof_labels.size());
    for (int node = 0; node < static_cast<int>(kHeights.size()); ++node) {
      // A lumped mass: `mass` on the node's ux and uy, `inertia` on its rz.
      Eigen::MatrixXd lumped = Eigen::MatrixXd::Zero(n, n);
      const std::string prefix = "n" + std::to_string(node) + ":";
      for (const char* name : {"ux", "uy", "rz"}) {
        const int d = Dof(s, prefix + name);
        if (d >= 0) lumped(d, d) = std::string(name) == "rz" ? inertia : mass;
      }
      const Eigen::MatrixXd got = PointMassAt(s, kHeights[node], mass, inertia);
      EXPECT_EQ(MaxAbs(got - lumped), 0.0)
          << "node " << node << ", free base " << free_base;
      // The same as CantileverSpec::lumped_masses and ::point_masses.
      CantileverSpec with_lumped = spec, with_point = spec;
      with_lumped.lumped_masses.push_back({node, mass, inertia});
      with_point.point_masses.push_back({kHeights[node], mass, inertia});
      const Eigen::MatrixXd ml(BuildCantilever(with_lumped).mass);
      const Eigen::MatrixXd mp(BuildCantilever(with_point).mass);
      EXPECT_LE(MaxAbs(ml - Eigen::MatrixXd(s.mass) - lumped), 1e-15 * MaxAbs(ml));
      EXPECT_LE(MaxAbs(mp - ml), 1e-15 * MaxAbs(ml))
          << "node " << node << ", free base " << free_base;
    }
  }
}

TEST(PointMassAt, BetweenNodesRigidMotionsCarryTheMassExactly) {
  const Structure s = Cantilever(kHeights, true);
  const double mass = 0.8, inertia = 3e-3;
  for (double z : {0.41, 0.05, 0.899, 0.15}) {
    const SparseMatrix m = PointMassAt(s, z, mass, inertia);
    const Eigen::VectorXd ux = MonomialField(s, kHeights, 0);
    const Eigen::VectorXd uy = AxialTranslation(s);
    // Rigid rotation by 1 rad about the base: ux = -z, rz = 1.
    const Eigen::VectorXd rot = -MonomialField(s, kHeights, 1);
    EXPECT_NEAR(ux.dot(m * ux), mass, 1e-14) << z;
    EXPECT_NEAR(uy.dot(m * uy), mass, 1e-14) << z;
    EXPECT_NEAR(ux.dot(m * uy), 0.0, 1e-15) << z;
    EXPECT_NEAR(rot.dot(m * rot), mass * z * z + inertia, 1e-14) << z;
    EXPECT_NEAR(ux.dot(m * rot), -mass * z, 1e-14) << z;
    const Eigen::MatrixXd dense(m);
    EXPECT_EQ(MaxAbs(dense - dense.transpose()), 0.0);
  }
}

// Lowest root of the Euler-Bernoulli frequency equation of a clamped-free beam
// with a tip mass ratio r = m / (rho A L) (no rotary inertia), in x = beta L:
//   1 + cos x cosh x + r x (cos x sinh x - sin x cosh x) = 0.
double TipMassRoot(double r) {
  const auto g = [r](double x) {
    return 1 + std::cos(x) * std::cosh(x) +
           r * x * (std::cos(x) * std::sinh(x) - std::sin(x) * std::cosh(x));
  };
  double lo = 1e-3, hi = lo;
  while (g(hi) > 0) {
    lo = hi;
    hi += 1e-3;
    if (hi > 3) {
      ADD_FAILURE() << "no root below 3 for r = " << r;
      return kNaN;
    }
  }
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(PointMassAt, TipMassMatchesEulerBernoulli) {
  const double length = 1.9;
  const BeamSection sec = PaperSection();
  const double rho_a = sec.rho * sec.A;
  EXPECT_NEAR(TipMassRoot(0), 1.8751040687, 1e-9);  // the bare cantilever
  for (double r : {0.2, 1.0, 5.0}) {
    CantileverSpec spec = Spec(UniformHeights(length, 40), false);
    spec.point_masses.push_back({length, r * rho_a * length, 0.0});
    const Structure s = BuildCantilever(spec);
    const Frequencies f = Modes(s, s.stiffness, s.mass);
    const double x = TipMassRoot(r);
    const double exact = x * x * std::sqrt(sec.E * sec.I / (rho_a * std::pow(length, 4)));
    EXPECT_NEAR(f.bending[0] / exact, 1.0, 1e-4) << "r = " << r;
    // The same matrix from PointMassAt on the bare structure.
    const Structure bare = Cantilever(UniformHeights(length, 40), false);
    const SparseMatrix m = bare.mass + PointMassAt(bare, length, r * rho_a * length, 0.0);
    EXPECT_NEAR(Modes(bare, bare.stiffness, m).bending[0] / exact, 1.0, 1e-4);
  }
}

TEST(PointMassAt, BetweenNodesAgreesWithANodeOfAFinerMesh) {
  const double length = 1.9;
  const BeamSection sec = PaperSection();
  const double mass = 0.5 * sec.rho * sec.A * length, inertia = 2e-3;
  for (int node40 : {13, 27, 39}) {  // odd: mid-element in the 20-element mesh
    const double z = length * node40 / 40;
    CantileverSpec coarse = Spec(UniformHeights(length, 20), false);
    coarse.point_masses.push_back({z, mass, inertia});
    CantileverSpec fine = Spec(UniformHeights(length, 40), false);
    fine.lumped_masses.push_back({node40, mass, inertia});
    const Structure sc = BuildCantilever(coarse);
    const Structure sf = BuildCantilever(fine);
    const Frequencies fc = Modes(sc, sc.stiffness, sc.mass);
    const Frequencies ff = Modes(sf, sf.stiffness, sf.mass);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(fc.bending[i] / ff.bending[i], 1.0, 1e-4)
          << "mode " << i + 1 << ", z = " << z;
    }
  }
}

// ---------------------------------------------------------------------------
// Bad input.

TEST(BeamModifications, BadInputsNameTheField) {
  const Structure s = Cantilever(kHeights, false);
  ExpectInputError([&] { TransverseMassOverInterval(s, -0.1, 0.5, 1.0); },
                   {"z0", "-0.1"});
  ExpectInputError([&] { TransverseMassOverInterval(s, kNaN, 0.5, 1.0); }, {"z0"});
  ExpectInputError([&] { TransverseMassOverInterval(s, 0.9, 1.5, 1.0); }, {"z0", "0.9"});
  ExpectInputError([&] { TransverseMassOverInterval(s, 0.5, 0.5, 1.0); },
                   {"z1", "0.5", "above"});
  ExpectInputError([&] { TransverseMassOverInterval(s, 0.1, kInf, 1.0); }, {"z1"});
  ExpectInputError([&] { TransverseMassOverInterval(s, 0.1, 0.5, -1.0); },
                   {"mass_per_length", "-1"});
  ExpectInputError([&] { TransverseMassOverInterval(s, 0.1, 0.5, 1.0, -0.2); },
                   {"fade_length", "-0.2"});
  ExpectInputError([&] { TransverseMassOverInterval(s, 0.1, 0.5, 1.0, kNaN); },
                   {"fade_length"});

  ExpectInputError([&] { BendingStiffnessOverInterval(s, 0.1, 1.0, 1.0); },
                   {"z1", "1", "0.9"});
  ExpectInputError([&] { BendingStiffnessOverInterval(s, 0.3, 0.2, 1.0); },
                   {"z1", "0.2"});
  ExpectInputError([&] { BendingStiffnessOverInterval(s, -1.0, 0.2, 1.0); },
                   {"z0", "-1"});
  ExpectInputError([&] { BendingStiffnessOverInterval(s, 0.1, 0.2, kInf); },
                   {"delta_ei"});

  ExpectInputError([&] { PointMassAt(s, 1.2, 1.0, 0.0); }, {"z", "1.2", "0.9"});
  ExpectInputError([&] { PointMassAt(s, -0.1, 1.0, 0.0); }, {"z", "-0.1"});
  ExpectInputError([&] { PointMassAt(s, kNaN, 1.0, 0.0); }, {"z"});
  ExpectInputError([&] { PointMassAt(s, 0.5, -2.0, 0.0); }, {"mass", "-2"});
  ExpectInputError([&] { PointMassAt(s, 0.5, 1.0, kNaN); }, {"rotary_inertia"});

  // Not a cantilever: a spring-mass chain.
  ChainSpec chain;
  chain.masses = {1, 1};
  chain.springs = {10, 10};
  const Structure c = BuildSpringMassChain(chain);
  ExpectInputError([&] { TransverseMassOverInterval(c, 0.1, 0.5, 1.0); },
                   {"not a vertical cantilever"});
  ExpectInputError([&] { BendingStiffnessOverInterval(c, 0.1, 0.5, 1.0); },
                   {"not a vertical cantilever"});
  ExpectInputError([&] { PointMassAt(c, 0.5, 1.0, 0.0); }, {"not a vertical cantilever"});
}

TEST(BeamModifications, BadSpecEntriesAreNamed) {
  const CantileverSpec base = Spec(kHeights, false);
  const auto build = [](const CantileverSpec& spec) {
    return [spec] { BuildCantilever(spec); };
  };
  CantileverSpec spec = base;
  spec.distributed_masses = {{0.1, 0.5, 1.0, 0.0}, {0.2, 1.1, 1.0, 0.0}};
  ExpectInputError(build(spec), {"model.distributed_masses[2]", "1.1", "0.9"});
  spec.distributed_masses = {{0.1, 0.5, -1.0, 0.0}};
  ExpectInputError(build(spec), {"model.distributed_masses[1]", "mass_per_length", "-1"});
  spec.distributed_masses = {{0.1, 0.5, 1.0, -0.3}};
  ExpectInputError(build(spec), {"model.distributed_masses[1]", "fade", "-0.3"});

  spec = base;
  spec.stiffness_changes = {{0.1, 0.5, 0.2}, {0.1, 0.5, -1.0}};
  ExpectInputError(build(spec), {"model.stiffness_changes[2]", "factor = -1", "> -1"});
  spec.stiffness_changes = {{0.5, 0.3, 0.2}};
  ExpectInputError(build(spec), {"model.stiffness_changes[1]", "0.3"});
  spec.stiffness_changes = {{0.1, 0.5, kNaN}};
  ExpectInputError(build(spec), {"model.stiffness_changes[1]", "factor"});
  spec.stiffness_changes = {{0.1, 0.5, -0.6}, {0.4, 0.8, -0.6}};  // -1.2 on [0.4, 0.5]
  ExpectInputError(build(spec), {"model.stiffness_changes", "0.4", "-1.2"});

  spec = base;
  spec.point_masses = {{0.3, 1.0, 0.0}, {2.0, 1.0, 0.0}};
  ExpectInputError(build(spec), {"model.point_masses[2]", "height", "2", "0.9"});
  spec.point_masses = {{0.3, -1.0, 0.0}};
  ExpectInputError(build(spec), {"model.point_masses[1]", "mass", "-1"});
  spec.point_masses = {{0.3, 1.0, -1e-3}};
  ExpectInputError(build(spec), {"model.point_masses[1]", "rotary_inertia", "-0.001"});
}

// ---------------------------------------------------------------------------
// The study file's keys.

const char kStudy[] = R"(
model:
  type: cantilever
  node_heights: [0, 0.15, 0.32, 0.5, 0.71, 0.9]
  section: {E: 206e9, A: 8.8e-4, I: 8.53e-8, rho: 7850}
  distributed_masses: [{from: 0.1, to: 0.6, mass_per_length: 2.5, fade: 0.1},
                       {from: 0.7, to: 0.9, mass_per_length: 1.0}]
  stiffness_changes: [{from: 0.2, to: 0.41, factor: -0.3}]
  point_masses: [{height: 0.8, mass: 0.4, rotary_inertia: 1e-3}, {height: 0.32, mass: 0.1}]
  axial_force: -1200
parameters: {mass: none, stiffness: single, added_mass: none}
measurements:
  - {state: air, frequencies_hz: [20]}
)";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return pos == std::string::npos ? text : text.replace(pos, from.size(), to);
}

TEST(BeamModifications, StudyFileKeysAreRead) {
  const testing::ScratchDir dir;
  const std::string path = dir.File("beam.yaml");
  std::ofstream(path) << kStudy;
  const Study study = LoadStudy(path);

  CantileverSpec spec = Spec(kHeights, false);
  spec.distributed_masses = {{0.1, 0.6, 2.5, 0.1}, {0.7, 0.9, 1.0, 0.0}};
  spec.stiffness_changes = {{0.2, 0.41, -0.3}};
  spec.point_masses = {{0.8, 0.4, 1e-3}, {0.32, 0.1, 0.0}};
  spec.axial_force = -1200;
  const Structure expected = BuildCantilever(spec);
  const Structure bare = Cantilever(kHeights, false);
  const Eigen::MatrixXd km(study.structure.stiffness), mm(study.structure.mass);
  EXPECT_EQ(MaxAbs(km - Eigen::MatrixXd(expected.stiffness)), 0.0);
  EXPECT_EQ(MaxAbs(mm - Eigen::MatrixXd(expected.mass)), 0.0);
  // And they did change the model.
  EXPECT_GT(MaxAbs(km - Eigen::MatrixXd(bare.stiffness)), 0.0);
  EXPECT_GT(MaxAbs(mm - Eigen::MatrixXd(bare.mass)), 0.0);
}

TEST(BeamModifications, StudyFileBadValuesAreNamed) {
  const testing::ScratchDir dir;
  struct Case {
    std::string from, to;
    std::vector<std::string> needles;
  };
  const Case cases[] = {
      {"mass_per_length: 2.5",
       "mass_per_length: -2.5",
       {"model.distributed_masses[1].mass_per_length", "-2.5"}},
      {"{from: 0.7, to: 0.9,",
       "{from: 0.7, to: 0.6,",
       {"model.distributed_masses[2].to", "above"}},
      {"fade: 0.1", "fade: abc", {"model.distributed_masses[1].fade", "abc"}},
      {"fade: 0.1", "fades: 0.1", {"model.distributed_masses[1].fades", "unknown key"}},
      {"factor: -0.3", "factor: -2", {"model.stiffness_changes[1].factor", "-2"}},
      {"to: 0.41", "to: 3", {"model.stiffness_changes[1]", "3", "0.9"}},
      {"{height: 0.8", "{height: 1.8", {"model.point_masses[1]", "height", "1.8"}},
      {"mass: 0.1}", "mass: -0.1}", {"model.point_masses[2].mass", "-0.1"}},
      {"rotary_inertia: 1e-3", "inertia: 1e-3", {"model.point_masses[1].inertia"}},
      {"stiffness_changes:", "stiffness_change:", {"stiffness_change", "unknown key"}},
      {"axial_force: -1200", "axial_force: heavy", {"model.axial_force", "heavy"}},
  };
  int k = 0;
  for (const Case& c : cases) {
    const std::string path = dir.File("bad" + std::to_string(++k) + ".yaml");
    std::ofstream(path) << Replace(kStudy, c.from, c.to);
    try {
      LoadStudy(path);
      ADD_FAILURE() << c.to << ": no error";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(path), std::string::npos) << msg;
      for (const std::string& n : c.needles) {
        EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
      }
    }
  }
}

}  // namespace
}  // namespace femup
