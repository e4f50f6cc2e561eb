// Strip-theory added mass (core/include/femup/core/fe/strip_theory.h): the rectangle
// coefficient against DNV-RP-C205 Table A-1, the strip mass per length against
// the displaced fluid of a circle, and the wet added-mass matrix against the
// element transverse mass (fe.h) and closed-form integrals of cubic fields.
#include "femup/core/fe/strip_theory.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "beam_dofs.h"
#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/fe.h"
#include "paper_beam.h"

namespace femup {
namespace {

using fixtures::PaperSection;

const double kPi = std::acos(-1.0);
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

using testing::ExpectInputError;

// ---------------------------------------------------------------------------
// Coefficients.

// DNV-RP-C205 (2010) Table A-1, rectangle, finite a/b.
struct TableRow {
  double a_over_b, ca;
};
const TableRow kTable[] = {{10, 1.14},  {5, 1.21},   {2, 1.36},  {1, 1.51},
                           {0.5, 1.70}, {0.2, 1.98}, {0.1, 2.23}};

TEST(RectangleAddedMassCoefficient, TabulatedValues) {
  for (const TableRow& row : kTable) {
    // a/b = width_normal / depth_along; try two absolute sizes.
    EXPECT_NEAR(RectangleAddedMassCoefficient(row.a_over_b, 1.0), row.ca, 1e-12)
        << "a/b = " << row.a_over_b;
    EXPECT_NEAR(RectangleAddedMassCoefficient(0.03 * row.a_over_b, 0.03), row.ca, 1e-12)
        << "a/b = " << row.a_over_b;
  }
  // a/b = inf: the flat plate normal to the motion.
  EXPECT_EQ(RectangleAddedMassCoefficient(0.05, 0.0), 1.0);
  EXPECT_NEAR(RectangleAddedMassCoefficient(1.0, 1e-12), 1.0, 1e-11);
}

TEST(RectangleAddedMassCoefficient, InterpolatesInLogRatioAndInInverseRatioAboveTen) {
  // Geometric midpoints of table intervals get the arithmetic mean of C_A.
  for (int i = 0; i + 1 < static_cast<int>(std::size(kTable)); ++i) {
    const double mid = std::sqrt(kTable[i].a_over_b * kTable[i + 1].a_over_b);
    EXPECT_NEAR(RectangleAddedMassCoefficient(mid, 1.0),
                0.5 * (kTable[i].ca + kTable[i + 1].ca), 1e-12)
        << "a/b = " << mid;
  }
  // a/b = 20 is b/a = 0.05, half way between b/a = 0.1 (1.14) and 0 (1.00).
  EXPECT_NEAR(RectangleAddedMassCoefficient(20.0, 1.0), 1.07, 1e-12);
  EXPECT_NEAR(RectangleAddedMassCoefficient(40.0, 1.0), 1.035, 1e-12);
}

TEST(RectangleAddedMassCoefficient, FallsMonotonicallyAndContinuously) {
  double previous = RectangleAddedMassCoefficient(0.1, 1.0);
  const int steps = 20000;
  for (int i = 1; i <= steps; ++i) {
    // a/b from 0.1 to 1e4, equally spaced in log.
    const double a_over_b = 0.1 * std::pow(1e5, static_cast<double>(i) / steps);
    const double ca = RectangleAddedMassCoefficient(a_over_b, 1.0);
    EXPECT_LT(ca, previous) << "a/b = " << a_over_b;
    EXPECT_LT(previous - ca, 2e-3) << "jump at a/b = " << a_over_b;
    EXPECT_GT(ca, 1.0);
    EXPECT_LE(ca, 2.23);
    previous = ca;
  }
}

TEST(RectangleAddedMassCoefficient, OutsideTheTableOrBadSizesThrow) {
  ExpectInputError([] { RectangleAddedMassCoefficient(0.099, 1.0); },
                   {"0.099", "0.1, inf"});
  ExpectInputError([] { RectangleAddedMassCoefficient(0.0, 1.0); },
                   {"width_normal", "0"});
  ExpectInputError([] { RectangleAddedMassCoefficient(-1.0, 1.0); },
                   {"width_normal", "-1"});
  ExpectInputError([] { RectangleAddedMassCoefficient(kNaN, 1.0); }, {"width_normal"});
  ExpectInputError([] { RectangleAddedMassCoefficient(kInf, 1.0); }, {"width_normal"});
  ExpectInputError([] { RectangleAddedMassCoefficient(1.0, -0.5); },
                   {"depth_along", "-0.5"});
  ExpectInputError([] { RectangleAddedMassCoefficient(1.0, kInf); }, {"depth_along"});
  ExpectInputError([] { RectangleAddedMassCoefficient(1.0, kNaN); }, {"depth_along"});
}

TEST(StripAddedMass, CircleCarriesItsDisplacedFluid) {
  EXPECT_EQ(CircleAddedMassCoefficient(), 1.0);
  // A 0.1 m diameter cylinder in sea water: rho pi d^2 / 4 per metre.
  const double d = 0.1, rho = 1025;
  EXPECT_NEAR(StripAddedMassPerLength(rho, d, CircleAddedMassCoefficient()),
              rho * kPi * d * d / 4, 1e-12);
  EXPECT_NEAR(StripAddedMassPerLength(rho, d, 2.0), 2 * rho * kPi * d * d / 4, 1e-12);
}

TEST(StripAddedMass, SteelBarInFreshWater) {
  // 25.8 mm normal to the motion, 34.1 mm along it: a/b = 0.7566, between the
  // table's 0.5 (1.70) and 1 (1.51), a fraction log2(a/b / 0.5) of the way.
  const double width = 0.0258, depth = 0.0341;
  const double ca = RectangleAddedMassCoefficient(width, depth);
  const double t = std::log2(width / depth / 0.5);
  EXPECT_NEAR(ca, 1.70 + t * (1.51 - 1.70), 1e-12);
  EXPECT_GT(ca, 1.58);
  EXPECT_LT(ca, 1.59);
  const double ma = StripAddedMassPerLength(1000, width, ca);
  EXPECT_NEAR(ma, ca * 1000 * kPi * 0.0129 * 0.0129, 1e-12);
  // About 12 % of the bar's own mass per length (7850 * 8.8e-4 kg/m).
  const double ratio = ma / (7850 * 8.8e-4);
  EXPECT_GT(ratio, 0.11);
  EXPECT_LT(ratio, 0.13);
}

TEST(StripAddedMass, BadInputsNameTheField) {
  ExpectInputError([] { StripAddedMassPerLength(0, 0.1, 1); }, {"fluid_density", "0"});
  ExpectInputError([] { StripAddedMassPerLength(1000, -0.1, 1); },
                   {"width_normal", "-0.1"});
  ExpectInputError([] { StripAddedMassPerLength(1000, 0.1, kNaN); }, {"coefficient"});
  ExpectInputError([] { StripAddedMassPerLength(kInf, 0.1, 1); }, {"fluid_density"});
}

// ---------------------------------------------------------------------------
// Wet added-mass matrix of a cantilever.

// Non-uniform mesh of 5 elements, 0.9 m.
const std::vector<double>& kHeights = fixtures::kNonUniformHeights;

Structure Cantilever(const std::vector<double>& heights, bool free_base) {
  return BuildCantilever(fixtures::PaperCantilever(heights, free_base));
}

using fixtures::Dof;

// Frame2dTransverseMass of each element in `elements` (0-based), scattered into
// the global DOFs found by label.
Eigen::MatrixXd ScatteredTransverseMass(const Structure& s,
                                        const std::vector<double>& heights,
                                        const std::vector<int>& elements, double mpl) {
  const int n = static_cast<int>(s.dof_labels.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  static const char* kNames[3] = {"ux", "uy", "rz"};
  for (int e : elements) {
    const Matrix6 me = Frame2dTransverseMass(mpl, 0, heights[e], 0, heights[e + 1]);
    int dof[6];
    for (int i = 0; i < 6; ++i) {
      dof[i] = Dof(s, "n" + std::to_string(e + i / 3) + ":" + kNames[i % 3]);
    }
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) {
        if (dof[i] >= 0 && dof[j] >= 0) m(dof[i], dof[j]) += me(i, j);
      }
    }
  }
  return m;
}

using fixtures::MonomialField;

// Closed form of the integral of z^k m(z) over [0, top], with m(z) the added
// mass per length of the header (mpl below depth - fade, linear to 0 at depth).
double Moment(int k, double mpl, double depth, double fade, double top) {
  const double zf = std::max(0.0, depth - fade);
  const double a = std::min(top, zf);
  double result = mpl * std::pow(a, k + 1) / (k + 1);
  if (fade > 0) {
    const double lo = a, hi = std::min(depth, top);
    if (hi > lo) {
      result += mpl / fade *
                (depth * (std::pow(hi, k + 1) - std::pow(lo, k + 1)) / (k + 1) -
                 (std::pow(hi, k + 2) - std::pow(lo, k + 2)) / (k + 2));
    }
  }
  return result;
}

double MaxAbs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

TEST(WetTransverseAddedMass, FullyWetEqualsScatteredTransverseMass) {
  const double mpl = 0.83;
  for (bool free_base : {false, true}) {
    const Structure s = Cantilever(kHeights, free_base);
    const Eigen::MatrixXd expected =
        ScatteredTransverseMass(s, kHeights, {0, 1, 2, 3, 4}, mpl);
    for (double depth : {0.9, 1.5}) {  // at the tip, above it
      const Eigen::MatrixXd got = WetTransverseAddedMass(s, mpl, depth);
      ASSERT_EQ(got.rows(), static_cast<int>(s.dof_labels.size()));
      EXPECT_LE(MaxAbs(got - expected), 1e-13 * MaxAbs(expected))
          << "free base " << free_base << ", depth " << depth;
    }
    // The builder's transverse added-mass basis (mass per length rho A),
    // rescaled, is the same matrix.
    CantileverSpec spec = fixtures::PaperCantilever(kHeights);
    spec.added_mass_basis = AddedMassBasis::kTransverse;
    if (free_base) spec.support_transverse = spec.support_rotation = 1e5;
    const Structure t = BuildCantilever(spec);
    Eigen::MatrixXd basis =
        Eigen::MatrixXd::Zero(t.dof_labels.size(), t.dof_labels.size());
    for (const ElementMatrices& el : t.elements)
      basis += Eigen::MatrixXd(el.added_mass_basis);
    basis *= mpl / (spec.section.rho * spec.section.A);
    const Eigen::MatrixXd got = WetTransverseAddedMass(t, mpl, 0.9);
    EXPECT_LE(MaxAbs(got - basis), 1e-12 * MaxAbs(basis));
  }
}

TEST(WetTransverseAddedMass, WaterLineAtANodeKeepsOnlyTheElementsBelow) {
  const double mpl = 1.7;
  const Structure s = Cantilever(kHeights, false);
  const Eigen::MatrixXd expected = ScatteredTransverseMass(s, kHeights, {0, 1, 2}, mpl);
  const Eigen::MatrixXd got = WetTransverseAddedMass(s, mpl, kHeights[3]);
  EXPECT_LE(MaxAbs(got - expected), 1e-13 * MaxAbs(expected));
}

// With one element and a free base the transverse DOFs (ux, rz at both nodes)
// span exactly the cubics, so u_i' Ma u_j for u_i = the field z^i, i = 0..3,
// determines the element's whole matrix: compare with the closed-form moments.
TEST(WetTransverseAddedMass, PartlyWetSingleElementIsExact) {
  const double length = 0.4, mpl = 2.5;
  const std::vector<double> heights = {0.0, length};
  const Structure s = Cantilever(heights, true);
  ASSERT_EQ(s.dof_labels.size(), 6u);
  struct Case {
    double depth, fade;
  };
  // Sharp water line mid-element and near the ends; fade inside the element,
  // reaching below the base, and longer than the element.
  const Case cases[] = {{0.2, 0},    {0.013, 0},   {0.391, 0},  {0.25, 0.1},
                        {0.25, 0.4}, {0.35, 0.35}, {0.1, 0.05}, {0.7, 0.5}};
  std::vector<Eigen::VectorXd> fields;
  for (int k = 0; k < 4; ++k) fields.push_back(MonomialField(s, heights, k));
  for (const Case& c : cases) {
    const Eigen::MatrixXd ma = WetTransverseAddedMass(s, mpl, c.depth, c.fade);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const double expected = Moment(i + j, mpl, c.depth, c.fade, length);
        EXPECT_NEAR(fields[i].dot(ma * fields[j]), expected, 1e-14 + 1e-12 * expected)
            << "depth " << c.depth << ", fade " << c.fade << ", z^" << i << " z^" << j;
      }
    }
    // Axial DOFs carry nothing.
    for (const char* label : {"n0:uy", "n1:uy"}) {
      const int d = Dof(s, label);
      EXPECT_EQ(ma.row(d).cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ(ma.col(d).cwiseAbs().maxCoeff(), 0.0);
    }
  }
}

TEST(WetTransverseAddedMass, CubicFieldsOnAMeshMatchClosedFormMoments) {
  const double mpl = 0.9, top = kHeights.back();
  for (bool free_base : {true, false}) {
    const Structure s = Cantilever(kHeights, free_base);
    // A clamped base admits only the fields with ux(0) = ux'(0) = 0.
    const int first = free_base ? 0 : 2;
    for (double depth : {0.05, 0.41, 0.9, 1.2}) {
      for (double fade : {0.0, 0.04, 0.23, 0.6}) {
        const Eigen::MatrixXd ma = WetTransverseAddedMass(s, mpl, depth, fade);
        for (int i = first; i < 4; ++i) {
          for (int j = first; j < 4; ++j) {
            const Eigen::VectorXd ui = MonomialField(s, kHeights, i);
            const Eigen::VectorXd uj = MonomialField(s, kHeights, j);
            const double expected = Moment(i + j, mpl, depth, fade, top);
            EXPECT_NEAR(ui.dot(ma * uj), expected, 1e-14 + 1e-12 * expected)
                << "free base " << free_base << ", depth " << depth << ", fade " << fade
                << ", z^" << i << " z^" << j;
          }
        }
      }
    }
  }
}

// r = 1 on every ux DOF. With a free base r is the rigid translation and
// r' Ma r is the wet mass. With a clamped base ux(0) = 0 and r is the field
// 3 xi^2 - 2 xi^3 over the first element (length L1), whose square integrates
// to 13/35 L1 instead of L1.
TEST(WetTransverseAddedMass, UnitTranslationCarriesTheWetMass) {
  const double mpl = 1.3;
  const double l1 = kHeights[1];
  for (bool free_base : {true, false}) {
    const Structure s = Cantilever(kHeights, free_base);
    Eigen::VectorXd r = Eigen::VectorXd::Zero(s.dof_labels.size());
    for (std::size_t i = 0; i < s.dof_labels.size(); ++i) {
      if (s.dof_labels[i].find(":ux") != std::string::npos) r(i) = 1;
    }
    const double base_loss = free_base ? 0.0 : mpl * l1 * (1 - 13.0 / 35.0);
    // Water lines in the middle of elements 3 and 4 (sharp), and faded.
    for (double depth : {0.41, 0.6}) {
      const Eigen::MatrixXd ma = WetTransverseAddedMass(s, mpl, depth);
      EXPECT_NEAR(r.dot(ma * r), mpl * depth - base_loss, 1e-12);
      const double fade = 0.2;  // from 0.21 / 0.40 up: above the first element
      const Eigen::MatrixXd mf = WetTransverseAddedMass(s, mpl, depth, fade);
      EXPECT_NEAR(r.dot(mf * r), mpl * (depth - fade / 2) - base_loss, 1e-12);
    }
  }
}

TEST(WetTransverseAddedMass, SymmetricAndPositiveSemiDefinite) {
  for (bool free_base : {true, false}) {
    const Structure s = Cantilever(kHeights, free_base);
    for (double depth : {0.07, 0.44, 2.0}) {
      const Eigen::MatrixXd ma = WetTransverseAddedMass(s, 0.7, depth, 0.1);
      EXPECT_EQ(MaxAbs(ma - ma.transpose()), 0.0);
      const Eigen::VectorXd ev =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(ma).eigenvalues();
      EXPECT_GE(ev.minCoeff(), -1e-14 * ev.maxCoeff());
      EXPECT_GT(ev.maxCoeff(), 0.0);
    }
  }
}

TEST(WetTransverseAddedMass, DryCantileverHasNone) {
  const Structure s = Cantilever(kHeights, true);
  const SparseMatrix ma = WetTransverseAddedMass(s, 1.0, 0.0, 0.3);
  EXPECT_EQ(ma.rows(), static_cast<int>(s.dof_labels.size()));
  EXPECT_EQ(ma.cols(), static_cast<int>(s.dof_labels.size()));
  EXPECT_EQ(ma.nonZeros(), 0);
}

TEST(WetTransverseAddedMass, BadInputsThrow) {
  const Structure s = Cantilever(kHeights, false);
  ExpectInputError([&] { WetTransverseAddedMass(s, 1.0, -0.2); },
                   {"water_depth", "-0.2"});
  ExpectInputError([&] { WetTransverseAddedMass(s, 1.0, kNaN); }, {"water_depth"});
  ExpectInputError([&] { WetTransverseAddedMass(s, 1.0, 0.5, -1); },
                   {"fade_length", "-1"});
  ExpectInputError([&] { WetTransverseAddedMass(s, 1.0, 0.5, kInf); }, {"fade_length"});
  ExpectInputError([&] { WetTransverseAddedMass(s, 0.0, 0.5); },
                   {"mass_per_length", "0"});

  // A spring-mass chain has x0/x1 but no cantilever DOFs.
  ChainSpec chain;
  chain.masses = {1.0, 1.0};
  chain.springs = {1.0, 1.0};
  ExpectInputError([&] { WetTransverseAddedMass(BuildSpringMassChain(chain), 1.0, 0.5); },
                   {"not a vertical cantilever", "x1"});

  // Elements without positions (as from a matrix import).
  Structure no_positions = s;
  for (ElementMatrices& el : no_positions.elements) el.x0 = el.x1 = 0;
  ExpectInputError([&] { WetTransverseAddedMass(no_positions, 1.0, 0.5); },
                   {"structure.elements[1]", "not a vertical cantilever"});

  // Positions that do not match the node heights.
  Structure moved = s;
  moved.elements[2].x1 += 0.01;
  ExpectInputError([&] { WetTransverseAddedMass(moved, 1.0, 0.5); },
                   {"not a vertical cantilever"});

  Structure relabelled = s;
  relabelled.dof_labels[4] = "n2:uz";
  ExpectInputError([&] { WetTransverseAddedMass(relabelled, 1.0, 0.5); },
                   {"structure.dof_labels[5]", "n2:uz"});

  Structure no_positions_at_all = s;
  no_positions_at_all.dof_positions.clear();
  ExpectInputError([&] { WetTransverseAddedMass(no_positions_at_all, 1.0, 0.5); },
                   {"structure.dof_positions"});
}

}  // namespace
}  // namespace femup
