// Effects as changes of the model (model_effects.h), checked against closed
// forms and other formulations: a two-mass chain's eigenvalues from the
// quadratic formula, the continuous Euler-Bernoulli cantilever with a tip mass
// (its transcendental frequency equation), the exact interval integral of
// beam_modifications.h, the cantilever builder's own elastic base, and every
// derivative against central differences.
#include "femup/problems/model_effects.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>

#include "femup/core/errors.h"
#include "femup/core/fe/beam_modifications.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/linalg/modal.h"
#include "paper_beam.h"
#include "structure_specs.h"
#include "vector_of.h"

namespace femup {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::VectorXd Theta(std::initializer_list<double> v) { return fixtures::VectorOf(v); }

Eigen::VectorXd Eigenvalues(const SparseMatrix& k, const SparseMatrix& m) {
  return SolveModes(k, m).eigenvalues;
}

// One instance of `kind` (the first, or the one whose region is `region`).
std::unique_ptr<ModelEffect> One(const std::string& kind, const Structure& s,
                                 const std::string& region = "",
                                 const ModelEffectOptions& options = {}) {
  auto all = CreateModelEffects(kind, s, options);
  for (auto& e : all) {
    if (region.empty() || e->region().name == region) return std::move(e);
  }
  ADD_FAILURE() << "no instance of " << kind << " at " << region;
  return nullptr;
}

Structure TwoMassChain() {
  return BuildSpringMassChain({{2.0, 1.0}, {300.0, 100.0}, {}});
}

// Eigenvalues of diag(m1, m2)^-1 [[k1 + k2, -k2], [-k2, k2]], by the quadratic
// formula.
std::pair<double, double> TwoMassEigenvalues(double m1, double m2, double k1, double k2) {
  const double a = m1 * m2, b = -(m1 * k2 + m2 * (k1 + k2)), c = k1 * k2;
  const double root = std::sqrt(b * b - 4 * a * c);
  return {(-b - root) / (2 * a), (-b + root) / (2 * a)};
}

TEST(ModelEffects, StiffnessLossOfAStoreyMatchesTheQuadraticFormula) {
  const Structure s = TwoMassChain();
  auto loss = One("stiffness_loss", s, "element 2");
  ASSERT_TRUE(loss);
  SparseMatrix k, m;
  ApplyModelEffects(s, {loss.get()}, {Theta({std::log(0.25)})}, Immersion::kDry, &k, &m);
  const auto [l1, l2] = TwoMassEigenvalues(2.0, 1.0, 300.0, 75.0);
  const Eigen::VectorXd lambda = Eigenvalues(k, m);
  EXPECT_NEAR(lambda[0], l1, 1e-10 * l2);
  EXPECT_NEAR(lambda[1], l2, 1e-10 * l2);
  EXPECT_NEAR(loss->Magnitudes(Theta({std::log(0.25)}))[0].value, 0.25, 1e-15);
}

TEST(ModelEffects, SupportFlexibilityOfAChainSoftensTheGroundSpring) {
  const Structure s = TwoMassChain();
  auto support = One("support_flexibility", s);
  ASSERT_TRUE(support);
  SparseMatrix k, m;
  const double c = 0.5;  // k1 -> 300 / 1.5 = 200
  ApplyModelEffects(s, {support.get()}, {Theta({std::log(c)})}, Immersion::kDry, &k, &m);
  const auto [l1, l2] = TwoMassEigenvalues(2.0, 1.0, 200.0, 100.0);
  const Eigen::VectorXd lambda = Eigenvalues(k, m);
  EXPECT_NEAR(lambda[0], l1, 1e-10 * l2);
  EXPECT_NEAR(lambda[1], l2, 1e-10 * l2);
}

TEST(ModelEffects, MaterialScalingScalesEveryEigenvalue) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 12));
  const Structure s = BuildCantilever(spec);
  auto e = One("material_scaling", s);
  ASSERT_TRUE(e);
  SparseMatrix k, m;
  ApplyModelEffects(s, {e.get()}, {Theta({std::log(0.9)})}, Immersion::kDry, &k, &m);
  const Eigen::VectorXd before = Eigenvalues(s.stiffness, s.mass);
  const Eigen::VectorXd after = Eigenvalues(k, m);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(after[i] / before[i], 0.9, 1e-9) << i;
}

// The root of f in [lo, hi] (a sign change), by 200 bisections.
template <typename F>
double Bisect(F f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(lo) * f(mid) <= 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// The continuous Euler-Bernoulli cantilever with a tip mass mu rho A L and a
// rotary inertia j rho A L^3 at the tip: the roots in b = beta L of
//   1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b)
//     - j b^3 (cosh b sin b + sinh b cos b) + mu j b^4 (1 - cos b cosh b) = 0
// (the free end's shear balancing the mass's inertia, its moment the rotary
// inertia's; checked against a 200-element numpy beam to 1e-6 when written).
double TipMassRoot(double mu, double lo, double hi, double j = 0) {
  auto f = [mu, j](double b) {
    const double c = std::cos(b), s = std::sin(b), ch = std::cosh(b), sh = std::sinh(b);
    return 1 + c * ch + mu * b * (c * sh - s * ch) - j * b * b * b * (ch * s + sh * c) +
           mu * j * b * b * b * b * (1 - c * ch);
  };
  return Bisect(f, lo, hi);
}

// Expects the lowest eigenvalues of (k, m), in order, to be those of the
// continuous beam of `section`, `length` long, whose roots in beta L are `roots`
// (relative 2e-4).
void ExpectContinuousBeamEigenvalues(const SparseMatrix& k, const SparseMatrix& m,
                                     const BeamSection& section, double length,
                                     const std::vector<double>& roots) {
  const Eigen::VectorXd lambda = Eigenvalues(k, m);
  const double ei = section.E * section.I, rho_a = section.rho * section.A;
  for (std::size_t i = 0; i < roots.size(); ++i) {
    const double exact = std::pow(roots[i] / length, 4) * ei / rho_a;
    EXPECT_NEAR(lambda[i] / exact, 1.0, 2e-4) << "mode " << i + 1;
  }
}

ModelEffectOptions TranslationsOnly() {
  ModelEffectOptions o;
  o.rotary_inertia = false;
  return o;
}

TEST(ModelEffects, AttachedMassAtTheTipMatchesTheContinuousBeam) {
  const double length = 1.9;
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(length, 40));
  const Structure s = BuildCantilever(spec);
  auto tip = One("attached_mass", s, "node n40", TranslationsOnly());
  ASSERT_TRUE(tip);
  const double rho_a = spec.section.rho * spec.section.A;
  const double mu = 0.3;
  // theta such that the mass is mu rho A L.
  const double ratio = mu * rho_a * length / ReferenceMass(s);
  const Eigen::VectorXd theta = Theta({std::log(ratio)});
  EXPECT_NEAR(tip->Magnitudes(theta)[0].value, mu * rho_a * length, 1e-12);
  SparseMatrix k, m;
  ApplyModelEffects(s, {tip.get()}, {theta}, Immersion::kDry, &k, &m);
  // The two lowest modes are bending (the axial ones are far higher).
  ExpectContinuousBeamEigenvalues(k, m, spec.section, length,
                                  {TipMassRoot(mu, 0.5, 1.8), TipMassRoot(mu, 3.0, 4.7)});
}

// With its rotary inertia (fitted by default where the model has rotations):
// a tip mass 0.3 rho A L of radius of gyration r, j = mu r^2 / L^2 = 0.02, whose
// inertia lowers the second mode by a fifth (beta L 4.19 -> 3.35).
TEST(ModelEffects, AttachedMassWithRotaryInertiaAtTheTipMatchesTheContinuousBeam) {
  const double length = 1.9;
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(length, 40));
  const Structure s = BuildCantilever(spec);
  EXPECT_NEAR(ReferenceLength(s), length, 1e-12);
  auto tip = One("attached_mass", s, "node n40");
  ASSERT_TRUE(tip);
  ASSERT_EQ(tip->Parameters().size(), 2u);
  EXPECT_EQ(tip->Parameters()[1].quantity, "radius_of_gyration_m");
  const double rho_a = spec.section.rho * spec.section.A;
  const double mu = 0.3, j = 0.02;
  const double r = length * std::sqrt(j / mu);
  const Eigen::VectorXd theta =
      Theta({std::log(mu * rho_a * length / ReferenceMass(s)), std::log(r / length)});
  const std::vector<EffectMagnitude> size = tip->Magnitudes(theta);
  ASSERT_EQ(size.size(), 4u);
  EXPECT_NEAR(size[2].value, r, 1e-12);
  EXPECT_NEAR(size[3].value / (j * rho_a * std::pow(length, 3)), 1.0, 1e-12);
  SparseMatrix k, m;
  ApplyModelEffects(s, {tip.get()}, {theta}, Immersion::kDry, &k, &m);
  const double b1 = TipMassRoot(mu, 0.5, 1.8, j), b2 = TipMassRoot(mu, 2.5, 4.0, j);
  EXPECT_NEAR(b2, 3.3498, 1e-3);  // the numpy beam's 3.34985
  ExpectContinuousBeamEigenvalues(k, m, spec.section, length, {b1, b2});
}

// The continuous Euler-Bernoulli cantilever with a point mass mu rho A L at
// x = a L (0 < a < 1): two spans, w = c1 cos + c2 sin + c3 cosh + c4 sinh of
// b x / L each, clamped at 0, free at L, w, w' continuous at a, the shear
// jumping by the mass's inertia: w2''' - w1''' = mu b w(a) (in units of
// b^3 / L^3), and the moment by its rotary inertia j rho A L^3:
// w2'' - w1'' = -j b^3 w'(a) (units b^2 / L^2). The roots of the 8 x 8
// determinant in b = beta L.
double PointMassDeterminant(double mu, double a, double b, double j = 0) {
  auto f = [](int k, double t) {
    const double c = std::cos(t), s = std::sin(t), ch = std::cosh(t), sh = std::sinh(t);
    switch (k) {
      case 0:
        return Eigen::RowVector4d(c, s, ch, sh);
      case 1:
        return Eigen::RowVector4d(-s, c, sh, ch);
      case 2:
        return Eigen::RowVector4d(-c, -s, ch, sh);
      default:
        return Eigen::RowVector4d(s, -c, sh, ch);
    }
  };
  Eigen::Matrix<double, 8, 8> d = Eigen::Matrix<double, 8, 8>::Zero();
  d.block<1, 4>(0, 0) = f(0, 0);            // w(0) = 0
  d.block<1, 4>(1, 0) = f(1, 0);            // w'(0) = 0
  d.block<1, 4>(2, 4) = f(2, b * (1 - a));  // w''(L) = 0
  d.block<1, 4>(3, 4) = f(3, b * (1 - a));  // w'''(L) = 0
  for (int k = 0; k < 3; ++k) {             // continuity at a
    d.block<1, 4>(4 + k, 0) = f(k, b * a);
    d.block<1, 4>(4 + k, 4) = -f(k, 0);
  }
  d.block<1, 4>(6, 0) = f(2, b * a) - j * b * b * b * f(1, b * a);  // the moment jump
  d.block<1, 4>(7, 0) = -f(3, b * a) - mu * b * f(0, b * a);        // the shear jump
  d.block<1, 4>(7, 4) = f(3, 0);
  return d.determinant();
}

double PointMassRoot(double mu, double a, double lo, double hi, double j = 0) {
  return Bisect([mu, a, j](double b) { return PointMassDeterminant(mu, a, b, j); }, lo,
                hi);
}

// A point mass between two nodes (the segment instance, its position fitted):
// 0.3 rho A L at 0.37 L, between nodes 14 and 15 of 40 (xi = 0.8), against the
// continuous beam's two lowest frequencies; and dM/dxi against differences.
TEST(ModelEffects, AttachedMassBetweenNodesMatchesTheContinuousBeam) {
  const double length = 1.9;
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(length, 40));
  const Structure s = BuildCantilever(spec);
  auto mass = One("attached_mass", s, "n14-n15", TranslationsOnly());
  ASSERT_TRUE(mass);
  ASSERT_EQ(mass->Parameters().size(), 2u);
  const double rho_a = spec.section.rho * spec.section.A;
  const double mu = 0.3, a = 0.37;
  const Eigen::VectorXd theta =
      Theta({std::log(mu * rho_a * length / ReferenceMass(s)), 0.8});
  EXPECT_NEAR(mass->Location(theta).x, a * length, 1e-12);
  EXPECT_NEAR(mass->Magnitudes(theta)[0].value, mu * rho_a * length, 1e-12);
  SparseMatrix k, m;
  ApplyModelEffects(s, {mass.get()}, {theta}, Immersion::kDry, &k, &m);
  // Without the mass, the cantilever's own root (1.8751); the mass lowers them.
  EXPECT_NEAR(PointMassRoot(0.0, a, 1.0, 2.5), 1.8751040687, 1e-8);
  ExpectContinuousBeamEigenvalues(
      k, m, spec.section, length,
      {PointMassRoot(mu, a, 1.0, 1.87), PointMassRoot(mu, a, 3.0, 4.69)});
  const double h = 1e-6;
  const SparseMatrix dm = mass->Derivative(theta, 1, Immersion::kDry).mass;
  const SparseMatrix plus = mass->Change(Theta({theta[0], theta[1] + h}), {}).mass;
  const SparseMatrix minus = mass->Change(Theta({theta[0], theta[1] - h}), {}).mass;
  const Eigen::MatrixXd fd = Eigen::MatrixXd(plus - minus) / (2 * h);
  EXPECT_LT((Eigen::MatrixXd(dm) - fd).cwiseAbs().maxCoeff(),
            1e-6 * fd.cwiseAbs().maxCoeff());
}

// The same mass with a rotary inertia j rho A L^3, j = 0.02, between the nodes:
// the rotation it follows is the element's slope there (the cubic's
// derivative), against the continuous beam with the moment jump; and every
// derivative (mass, position, radius) against differences. A cubic element
// cannot bend with the moment's jump inside it (a node at the mass could), so
// between nodes the rotary inertia converges with the mesh at about first
// order: on 40, 80, 160 and 320 elements mode 2's eigenvalue is 1.2e-3,
// 4.9e-4, 3.1e-4 and 1.2e-4 above the continuous beam's, mode 3's 2.9e-2,
// 1.2e-2, 7.1e-3 and 2.9e-3 (a translation alone: below 2e-4 on 40, the test
// above; the same mass on a node: 2e-9 on 100).
TEST(ModelEffects, AttachedMassWithRotaryInertiaBetweenNodesMatchesTheContinuousBeam) {
  const double length = 1.9, mu = 0.3, a = 0.37, j = 0.02;
  const std::vector<double> roots = {PointMassRoot(mu, a, 1.0, 2.0, j),
                                     PointMassRoot(mu, a, 3.0, 4.6, j),
                                     PointMassRoot(mu, a, 4.7, 6.0, j)};
  // The numpy beam (400 elements, the mass on its node at 0.37): beta L 1.82031,
  // 4.15463 and 5.58348.
  EXPECT_NEAR(roots[0], 1.82031, 1e-4);
  EXPECT_NEAR(roots[1], 4.15463, 1e-4);
  EXPECT_NEAR(roots[2], 5.58348, 1e-4);
  double previous = 1;
  for (int elements : {40, 160, 320}) {
    SCOPED_TRACE(elements);
    CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(length, elements));
    const Structure s = BuildCantilever(spec);
    const int e = static_cast<int>(a * elements);  // the mass between nodes e, e + 1
    auto mass =
        One("attached_mass", s, "n" + std::to_string(e) + "-n" + std::to_string(e + 1));
    ASSERT_TRUE(mass);
    ASSERT_EQ(mass->Parameters().size(), 3u);
    const double rho_a = spec.section.rho * spec.section.A;
    const Eigen::VectorXd theta =
        Theta({std::log(mu * rho_a * length / ReferenceMass(s)), a * elements - e,
               std::log(std::sqrt(j / mu))});  // r / L, L the structure's extent
    EXPECT_NEAR(mass->Location(theta).x, a * length, 1e-12);
    SparseMatrix k, m;
    ApplyModelEffects(s, {mass.get()}, {theta}, Immersion::kDry, &k, &m);
    const Eigen::VectorXd lambda = Eigenvalues(k, m);
    const double ei = spec.section.E * spec.section.I;
    std::vector<double> excess;
    for (int i = 0; i < 3; ++i)
      excess.push_back(lambda[i] / (std::pow(roots[i] / length, 4) * ei / rho_a) - 1);
    EXPECT_GE(excess[1], 0);  // the element is stiffer than the beam
    EXPECT_LT(excess[0], 5e-5);
    EXPECT_LT(excess[1], elements == 40 ? 1.5e-3 : 4e-4);
    EXPECT_LT(excess[2], elements == 40 ? 3.5e-2 : 1e-2);
    EXPECT_LT(excess[2], previous);
    previous = excess[2];
  }
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(length, 40));
  const Structure s = BuildCantilever(spec);
  auto mass = One("attached_mass", s, "n14-n15");
  ASSERT_TRUE(mass);
  const double rho_a = spec.section.rho * spec.section.A;
  const Eigen::VectorXd theta = Theta({std::log(mu * rho_a * length / ReferenceMass(s)),
                                       0.8, std::log(std::sqrt(j / mu))});
  for (int i = 0; i < 3; ++i) {
    const double h = 1e-6;
    Eigen::VectorXd up = theta, down = theta;
    up[i] += h;
    down[i] -= h;
    const SparseMatrix dm = mass->Derivative(theta, i, Immersion::kDry).mass;
    const Eigen::MatrixXd fd =
        Eigen::MatrixXd(mass->Change(up, {}).mass - mass->Change(down, {}).mass) /
        (2 * h);
    EXPECT_LT((Eigen::MatrixXd(dm) - fd).cwiseAbs().maxCoeff(),
              1e-6 * fd.cwiseAbs().maxCoeff())
        << "parameter " << i;
  }
}

// Without rotations (a chain) or without node coordinates there is no rotary
// inertia to fit: the masses keep their one parameter.
TEST(ModelEffects, NoRotaryInertiaWithoutRotations) {
  const Structure chain = TwoMassChain();
  EXPECT_EQ(ReferenceLength(chain), 0.0);
  for (const auto& e : CreateModelEffects("attached_mass", chain))
    EXPECT_EQ(e->Parameters().size(), 1u) << e->region().name;
}

TEST(ModelEffects, AddedMassOverTheWholeBeamScalesBendingModes) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 10));
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  const Structure s = BuildCantilever(spec);
  auto water = One("added_mass", s);
  ASSERT_TRUE(water);
  ASSERT_EQ(water->Parameters().size(), 2u);  // ratio and level
  SparseMatrix k, m;
  const double r = 0.8;
  ApplyModelEffects(s, {water.get()}, {Theta({std::log(r), 2.0})}, Immersion::kWet, &k,
                    &m);
  const Eigen::VectorXd before = Eigenvalues(s.stiffness, s.mass);
  const Eigen::VectorXd after = Eigenvalues(k, m);
  // Transverse-only mass on bending modes: (1 + r) times their mass.
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(after[i] * (1 + r) / before[i], 1.0, 1e-9) << i;
}

TEST(ModelEffects, AddedMassBelowALevelAtANodeIsTheExactIntervalIntegral) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 10));
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  const Structure s = BuildCantilever(spec);
  auto water = One("added_mass", s);
  ASSERT_TRUE(water);
  const double r = 0.5, level = 1.2;  // a node
  const ModelChange c = water->Change(Theta({std::log(r), level}), Immersion::kWet);
  const double rho_a = spec.section.rho * spec.section.A;
  const SparseMatrix exact = TransverseMassOverInterval(s, 0.0, level, r * rho_a);
  EXPECT_LT((Eigen::MatrixXd(c.mass) - Eigen::MatrixXd(exact)).cwiseAbs().maxCoeff(),
            1e-12 * Eigen::MatrixXd(exact).cwiseAbs().maxCoeff());
}

// A water level exactly at a node (every start of the fit is one on a uniform
// mesh) has a kink there; its derivative is the mean of the two sides', which is
// what central differences give, and not zero: with zero the fit never moved the
// level from its start.
TEST(ModelEffects, AddedMassLevelAtANodeHasTheCentralDifferenceDerivative) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 20));
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  const Structure s = BuildCantilever(spec);
  auto water = One("added_mass", s);
  ASSERT_TRUE(water);
  std::vector<double> levels;
  for (const Eigen::VectorXd& start : water->Starts()) levels.push_back(start[1]);
  levels.push_back(1.5);  // 15 elements of 0.1 m
  levels.push_back(2.0);  // the top
  for (const double level : levels) {
    const Eigen::VectorXd theta = Theta({std::log(0.3), level});
    const double h = 1e-7;
    const Eigen::MatrixXd fd =
        (Eigen::MatrixXd(
             water->Change(Theta({std::log(0.3), level + h}), Immersion::kWet).mass) -
         Eigen::MatrixXd(
             water->Change(Theta({std::log(0.3), level - h}), Immersion::kWet).mass)) /
        (2 * h);
    const Eigen::MatrixXd d =
        Eigen::MatrixXd(water->Derivative(theta, 1, Immersion::kWet).mass);
    ASSERT_GT(fd.cwiseAbs().maxCoeff(), 0.0) << level;
    EXPECT_LT((d - fd).cwiseAbs().maxCoeff(), 1e-6 * fd.cwiseAbs().maxCoeff()) << level;
  }
}

TEST(ModelEffects, AddedMassActsInWetStatesOnlyWhenAsked) {
  const Structure s =
      BuildSpringMassChain({{50, 50, 50}, {2e7, 2e7, 2e7}, {true, true, false}});
  auto water = One("added_mass", s, "", ModelEffectOptions{true});
  ASSERT_TRUE(water);
  EXPECT_EQ(water->region().elements, (std::vector<int>{0, 1}));
  const Eigen::VectorXd theta = Theta({std::log(0.2)});
  EXPECT_EQ(water->Change(theta, Immersion::kDry).mass.size(), 0);
  const SparseMatrix wet = water->Change(theta, Immersion::kWet).mass;
  EXPECT_NEAR(wet.coeff(0, 0), 10.0, 1e-12);
  EXPECT_NEAR(wet.coeff(1, 1), 10.0, 1e-12);
  EXPECT_EQ(wet.coeff(2, 2), 0.0);
  auto always = One("added_mass", s);
  EXPECT_NEAR(always->Change(theta, Immersion::kDry).mass.coeff(0, 0), 10.0, 1e-12);
}

TEST(ModelEffects, ElasticBaseMatchesTheBuilderWithTheSoftenedSpring) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 8));
  spec.support_rotation = 4e5;
  spec.support_transverse = 5e7;
  const Structure s = BuildCantilever(spec);
  ASSERT_EQ(s.supports.size(), 2u);
  auto support = One("support_flexibility", s);
  ASSERT_TRUE(support);
  // A rotation and a translation: a compliance ratio each.
  const auto params = support->Parameters();
  ASSERT_EQ(params.size(), 2u);
  EXPECT_EQ(params[0].quantity, "translation_compliance_ratio");
  EXPECT_EQ(params[1].quantity, "rotation_compliance_ratio");
  const double ct = 3.0, cr = 0.5;
  SparseMatrix k, m;
  ApplyModelEffects(s, {support.get()}, {Theta({std::log(ct), std::log(cr)})},
                    Immersion::kDry, &k, &m);
  CantileverSpec softer = spec;
  softer.support_rotation /= 1 + cr;
  softer.support_transverse /= 1 + ct;
  const Structure reference = BuildCantilever(softer);
  EXPECT_LT(
      (Eigen::MatrixXd(k) - Eigen::MatrixXd(reference.stiffness)).cwiseAbs().maxCoeff(),
      1e-12 * Eigen::MatrixXd(reference.stiffness).cwiseAbs().maxCoeff());
}

// The continuous Euler-Bernoulli beam on a translational spring k_t and a
// rotational spring k_r at x = 0, free at x = L: the roots in b = beta L of
// the determinant of its four end conditions on w = A cos + B sin + C cosh +
// D sinh (bx), from the energy's boundary terms (EI w''(0) = k_r w'(0),
// EI w'''(0) = -k_t w(0); free end w''(L) = w'''(L) = 0), with T = k_t L^3 / EI
// and R = k_r L / EI. T = R = inf is the clamped cantilever (1.8751, 4.6941).
std::vector<double> SprungBaseRoots(double t, double r, int count) {
  auto f = [t, r](double b) {
    const double c = std::cos(b), s = std::sin(b), ch = std::cosh(b), sh = std::sinh(b);
    Eigen::Matrix4d a;
    a << t, -b * b * b, t, b * b * b,  // shear against the translational spring
        -b, -r, b, -r,                 // moment against the rotational spring
        -c, -s, ch, sh,                // no moment at the tip
        s, -c, sh, ch;                 // no shear at the tip
    return a.determinant();
  };
  std::vector<double> roots;
  for (double b = 0.05; roots.size() < static_cast<std::size_t>(count); b += 0.01) {
    if (f(b) * f(b + 0.01) <= 0) roots.push_back(Bisect(f, b, b + 0.01));
  }
  return roots;
}

// A clamped cantilever's base released by support flexibility (the base a
// rigid support of the builder's, condensed out): the continuous beam on
// springs k_t = 3 EI / (L^3 c_t) and k_r = EI / (L c_r), so T = 3 / c_t and
// R = 1 / c_r.
TEST(ModelEffects, ClampedCantileverBaseReleasedMatchesTheBeamOnSprings) {
  const double length = 2.0;
  const int elements = 40;
  const CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(length, elements));
  const Structure s = BuildCantilever(spec);
  ASSERT_EQ(s.rigid_supports.size(), 1u);
  EXPECT_EQ(s.rigid_supports[0].directions, (std::vector<std::string>{"ux", "rz"}));
  auto base = One("support_flexibility", s);
  ASSERT_TRUE(base);
  ASSERT_EQ(base->Parameters().size(), 2u);
  EXPECT_EQ(base->Parameters()[0].quantity, "translation_compliance_ratio");
  // The cantilever's own pipeline's range, [1e-6, 10] of the beam's stiffness.
  EXPECT_NEAR(base->Parameters()[1].lower, std::log(1e-6), 1e-12);
  EXPECT_NEAR(base->Parameters()[1].upper, std::log(10.0), 1e-12);
  const double to_t = 3, to_r = 1;
  const double rigid = 1e-12;  // a compliance ratio that leaves a direction clamped
  for (const auto& [t, r] :
       std::vector<std::pair<double, double>>{{1e30, 2.0}, {50.0, 10.0}, {20.0, 1e30}}) {
    SCOPED_TRACE("T " + std::to_string(t) + ", R " + std::to_string(r));
    const double ct = t > 1e20 ? rigid : to_t / t, cr = r > 1e20 ? rigid : to_r / r;
    SparseMatrix k, m;
    ApplyModelEffects(s, {base.get()}, {Theta({std::log(ct), std::log(cr)})},
                      Immersion::kDry, &k, &m);
    ExpectContinuousBeamEigenvalues(
        k, m, spec.section, length,
        SprungBaseRoots(std::min(t, 1e12), std::min(r, 1e12), 3));
  }
}

// The clamped-free Euler-Bernoulli beam-column under a dead axial compression P
// (tension: P < 0), EI w'''' + P w'' = m w^2 w: with a^2 and g^2 =
// (sqrt(P^2 + 4 EI m w^2) -+ P) / (2 EI), w = A cosh ax + B sinh ax + C cos gx
// + D sin gx, clamped at x = 0, and at the free end no moment and no transverse
// force (EI w''' + P w' = 0). The determinant of the four conditions at w.
double BeamColumnDeterminant(double ei, double m, double length, double p, double w) {
  const double root = std::sqrt(p * p + 4 * ei * m * w * w);
  const double a = std::sqrt((root - p) / (2 * ei)), g = std::sqrt((root + p) / (2 * ei));
  const double ch = std::cosh(a * length), sh = std::sinh(a * length);
  const double c = std::cos(g * length), s = std::sin(g * length);
  Eigen::Matrix4d d;
  d << 1, 0, 1, 0,  //
      0, a, 0, g,   //
      a * a * ch, a * a * sh, -g * g * c, -g * g * s, ei * a * a * a * sh + p * a * sh,
      ei * a * a * a * ch + p * a * ch, ei * g * g * g * s - p * g * s,
      -ei * g * g * g * c + p * g * c;
  return d.determinant();
}

// axial_load on a clamped cantilever: its buckling load is Euler's
// pi^2 EI / (4 L^2), and under 0.5 of it in compression and 3 times it in
// tension the two lowest eigenvalues are the beam-column's.
TEST(ModelEffects, AxialLoadMatchesTheBeamColumn) {
  const double length = 2.0;
  const CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(length, 20));
  const Structure s = BuildCantilever(spec);
  auto axial = One("axial_load", s);
  ASSERT_TRUE(axial);
  const double ei = spec.section.E * spec.section.I,
               m = spec.section.rho * spec.section.A;
  const double euler = kPi * kPi * ei / (4 * length * length);
  EXPECT_NEAR(axial->Magnitudes(Theta({0.0}))[2].value / euler, 1.0, 1e-6);
  for (const double ratio : {-0.5, 3.0}) {
    SCOPED_TRACE("force ratio " + std::to_string(ratio));
    SparseMatrix k, mm;
    ApplyModelEffects(s, {axial.get()}, {Theta({ratio})}, Immersion::kDry, &k, &mm);
    EXPECT_NEAR(axial->Magnitudes(Theta({ratio}))[0].value, ratio * euler, 1e-6 * euler);
    const Eigen::VectorXd lambda = Eigenvalues(k, mm);
    const double p = -ratio * euler;  // compression positive
    for (int i = 0; i < 2; ++i) {
      const double w = std::sqrt(lambda[i]);
      const double exact =
          Bisect([&](double x) { return BeamColumnDeterminant(ei, m, length, p, x); },
                 0.97 * w, 1.03 * w);
      EXPECT_NEAR(w / exact, 1.0, 2e-4) << "mode " << i + 1;
    }
  }
  // Not tried unless named; a chain has no geometric stiffness.
  for (const FamilyApplicability& a : ApplicableModelEffects(s))
    EXPECT_EQ(a.by_default, a.kind != "axial_load") << a.kind;
  const Structure chain = BuildSpringMassChain({{1, 1}, {10, 10}, {}});
  for (const FamilyApplicability& a : ApplicableModelEffects(chain)) {
    if (a.kind == "axial_load") {
      EXPECT_NE(a.why_not.find("geometric stiffness"), std::string::npos) << a.why_not;
    }
  }
}

// Every family's derivative against central differences of its change.
// The index of a DOF by its label.
int DofOf(const Structure& s, const std::string& label) {
  const auto it = std::find(s.dof_labels.begin(), s.dof_labels.end(), label);
  EXPECT_NE(it, s.dof_labels.end()) << label;
  return static_cast<int>(it - s.dof_labels.begin());
}

TEST(ModelEffects, ConnectionsAreTheBeamsEnds) {
  const Structure s = BuildPlaneFrameStructure(fixtures::PlaneFrame(2, 2, 2));
  ASSERT_EQ(s.connections.size(), 4u);  // two beams a storey, no columns
  std::vector<std::string> regions;
  for (const auto& e : CreateModelEffects("stiffness_loss", s)) {
    if (e->region().name.rfind("connections of ", 0) == 0)
      regions.push_back(e->region().name);
  }
  EXPECT_EQ(regions, (std::vector<std::string>{
                         "connections of s1:beam1", "connections of s1:beam2",
                         "connections of s2:beam1", "connections of s2:beam2"}));
  for (const MemberConnections& c : s.connections) {
    EXPECT_EQ(s.elements[static_cast<std::size_t>(c.element)].label, c.label);
    ASSERT_EQ(c.ends.size(), 2u);  // the first and the last of its two elements
    EXPECT_EQ(c.ends[0].rotations, std::vector<int>{2});
    EXPECT_EQ(c.ends[1].rotations, std::vector<int>{5});
  }
}

// A beam of one element with both end connections semi-rigid: its end
// rotational stiffnesses against the semi-rigid beam's closed form (Monforton
// and Wu 1963), fixity factor r = 1 / (1 + 3 EI / (k L)) at each end:
// k_11 = (4 EI / L) 3 r / (4 - r^2), k_12 = (2 EI / L) 3 r^2 / (4 - r^2).
TEST(ModelEffects, ConnectionLossMatchesTheSemiRigidBeamsClosedForm) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(1, 1, 1, 3.0, 5.0);
  const Structure s = BuildPlaneFrameStructure(spec);
  const auto e = One("stiffness_loss", s, "connections of s1:beam1");
  ASSERT_TRUE(e);
  ASSERT_EQ(s.connections.size(), 1u);
  ASSERT_EQ(s.connections[0].ends.size(), 1u);
  EXPECT_EQ(s.connections[0].ends[0].rotations, (std::vector<int>{2, 5}));
  const int a = DofOf(s, "n1:rz"), b = DofOf(s, "n2:rz");
  const double ei = spec.beam.E * spec.beam.I, l = spec.bay_width;
  const Eigen::MatrixXd beam(s.elements[2].stiffness);
  for (double loss : {0.01, 0.2, 0.5, 0.9}) {
    const Eigen::MatrixXd k =
        beam +
        Eigen::MatrixXd(e->Change(Theta({std::log(loss)}), Immersion::kDry).stiffness);
    const double spring = 4 * ei / l * (1 - loss) / loss;
    const double r = 1 / (1 + 3 * ei / (spring * l));
    EXPECT_NEAR(k(a, a) / (4 * ei / l * 3 * r / (4 - r * r)), 1.0, 1e-10) << loss;
    EXPECT_NEAR(k(a, b) / (2 * ei / l * 3 * r * r / (4 - r * r)), 1.0, 1e-10) << loss;
    EXPECT_NEAR(k(b, b), k(a, a), 1e-9 * k(a, a)) << loss;
  }
}

// A portal whose beam is rigid and whose columns are nearly massless sways
// against each column's stiffness with a rotational spring k at its top to the
// beam, which does not rotate (slope-deflection): 12 EI / h^3 - 36 (EI)^2 /
// (h^4 (4 EI / h + k)); 12 EI / h^3 rigid, 3 EI / h^3 pinned.
TEST(ModelEffects, ConnectionLossOfAPortalsRigidBeamMatchesSlopeDeflection) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(1, 1, 4, 3.0, 5.0);
  spec.column = {210e9, 1.0, 8e-5, 1e-5};
  spec.beam = {210e9, 0.05, 8e-1, 2e4};
  const Structure s = BuildPlaneFrameStructure(spec);
  const auto e = One("stiffness_loss", s, "connections of s1:beam1");
  ASSERT_TRUE(e);
  const double ei = spec.column.E * spec.column.I, h = spec.storey_height;
  const double beam_mass = spec.beam.rho * spec.beam.A * spec.bay_width;
  // The beam's end element's own rotational stiffness, 4 EI_b / (L / 4).
  const double k_rr = 4 * spec.beam.E * spec.beam.I / (spec.bay_width / 4);
  for (double ratio : {0.1, 1.0, 10.0}) {  // k over the column's 4 EI / h
    const double spring = ratio * 4 * ei / h;
    const double loss = k_rr / (k_rr + spring);  // k = k_rr (1 - loss) / loss
    const ModelChange c = e->Change(Theta({std::log(loss)}), Immersion::kDry);
    const Eigen::VectorXd lambda =
        Eigenvalues(s.stiffness + c.stiffness, s.mass + c.mass);
    const double column = 12 * ei / std::pow(h, 3) -
                          36 * ei * ei / (std::pow(h, 4) * (4 * ei / h + spring));
    EXPECT_NEAR(lambda[0] / (2 * column / beam_mass), 1.0, 3e-3) << ratio;
  }
}

TEST(ModelEffects, ConnectionLossDerivativesMatchCentralDifferences) {
  for (int per_member : {1, 2}) {
    const Structure s = BuildPlaneFrameStructure(fixtures::PlaneFrame(2, 1, per_member));
    const auto e = One("stiffness_loss", s, "connections of s2:beam1");
    ASSERT_TRUE(e);
    for (double loss : {0.01, 0.3, 0.9}) {
      const double t = std::log(loss), h = 1e-6;
      const ModelChange d = e->Derivative(Theta({t}), 0, Immersion::kDry);
      const ModelChange up = e->Change(Theta({t + h}), Immersion::kDry);
      const ModelChange down = e->Change(Theta({t - h}), Immersion::kDry);
      const Eigen::MatrixXd fk =
          (Eigen::MatrixXd(up.stiffness) - Eigen::MatrixXd(down.stiffness)) / (2 * h);
      const Eigen::MatrixXd fm =
          (Eigen::MatrixXd(up.mass) - Eigen::MatrixXd(down.mass)) / (2 * h);
      EXPECT_LT((Eigen::MatrixXd(d.stiffness) - fk).cwiseAbs().maxCoeff(),
                1e-6 * fk.cwiseAbs().maxCoeff())
          << per_member << " " << loss;
      EXPECT_LT((Eigen::MatrixXd(d.mass) - fm).cwiseAbs().maxCoeff(),
                1e-6 * fm.cwiseAbs().maxCoeff())
          << per_member << " " << loss;
      EXPECT_GT(fm.cwiseAbs().maxCoeff(), 0.0);  // the end's mass moves with it
    }
  }
}

// The derivative of e's change (in water) in parameter i at theta against
// central differences of step h, each matrix to tolerance of its largest entry.
// A change that is empty on both sides needs an empty or zero derivative.
void ExpectDerivativeMatchesCentralDifferences(const ModelEffect& e,
                                               const Eigen::VectorXd& theta, int i,
                                               double h, double tolerance,
                                               const std::string& where) {
  Eigen::VectorXd up = theta, down = theta;
  up[i] += h;
  down[i] -= h;
  const ModelChange d = e.Derivative(theta, i, Immersion::kWet);
  const ModelChange u = e.Change(up, Immersion::kWet);
  const ModelChange w = e.Change(down, Immersion::kWet);
  auto check = [&](const SparseMatrix& dx, const SparseMatrix& xu, const SparseMatrix& xw,
                   const char* which) {
    if (xu.size() == 0) {
      EXPECT_TRUE(dx.size() == 0 || dx.norm() == 0) << where << " " << which;
      return;
    }
    const Eigen::MatrixXd fd = (Eigen::MatrixXd(xu) - Eigen::MatrixXd(xw)) / (2 * h);
    const double scale = std::max(fd.cwiseAbs().maxCoeff(), 1e-300);
    const Eigen::MatrixXd analytic = dx.size() == 0
                                         ? Eigen::MatrixXd::Zero(fd.rows(), fd.cols())
                                         : Eigen::MatrixXd(dx);
    EXPECT_LT((analytic - fd).cwiseAbs().maxCoeff() / scale, tolerance)
        << where << " " << which << " parameter " << i << " at " << theta.transpose();
  };
  check(d.stiffness, u.stiffness, w.stiffness, "stiffness");
  check(d.mass, u.mass, w.mass, "mass");
}

TEST(ModelEffects, DerivativesMatchCentralDifferences) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 10));
  spec.support_rotation = 4e5;
  spec.support_transverse = 5e7;  // support flexibility's two ratios
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  const Structure s = BuildCantilever(spec);
  for (const std::string& kind : ModelEffectKinds()) {
    auto e = One(kind, s);
    ASSERT_TRUE(e) << kind;
    const auto params = e->Parameters();
    Eigen::VectorXd theta(params.size());
    for (std::size_t i = 0; i < params.size(); ++i)
      theta[i] = params[i].lower + 0.37 * (params[i].upper - params[i].lower);
    for (int i = 0; i < theta.size(); ++i)
      ExpectDerivativeMatchesCentralDifferences(
          *e, theta, i, 1e-6 * (params[i].upper - params[i].lower), 1e-6, kind);
  }
}

// Every fit starts from each instance's Starts(): a derivative that is wrong
// there (zero at a kink, as the water level's was at a node) leaves the
// parameter where it started. Each start of every instance of every family,
// on a cantilever of uniform elements (whose starts fall on nodes) and on a
// plane frame, against central differences.
TEST(ModelEffects, DerivativesAtEveryStartMatchCentralDifferences) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 20));
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  const Structure bar = BuildCantilever(spec);
  const Structure frame = BuildPlaneFrameStructure(fixtures::PlaneFrame(2, 1, 2));
  std::map<std::string, int> checked;  // derivatives checked, by family
  for (const Structure* s : {&bar, &frame}) {
    for (const FamilyApplicability& a : ApplicableModelEffects(*s)) {
      if (!a.why_not.empty()) continue;
      for (const auto& e : CreateModelEffects(a.kind, *s)) {
        const auto params = e->Parameters();
        for (const Eigen::VectorXd& start : e->Starts()) {
          for (int i = 0; i < start.size(); ++i) {
            ExpectDerivativeMatchesCentralDifferences(
                *e, start, i, 1e-7 * (params[i].upper - params[i].lower), 1e-5,
                s->type + " " + e->kind() + " at " + e->region().name);
            ++checked[e->kind()];
          }
        }
      }
    }
  }
  for (const std::string kind : {"added_mass", "support_flexibility", "attached_mass",
                                 "stiffness_loss", "material_scaling"})
    EXPECT_GT(checked[kind], 1) << kind;
}

TEST(ModelEffects, SaysWhichFamiliesApplyAndWhyNot) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 4));
  for (const FamilyApplicability& a : ApplicableModelEffects(BuildCantilever(spec)))
    EXPECT_TRUE(a.why_not.empty()) << a.kind << ": " << a.why_not;
  // A model whose builder does not know what meets its rigid supports.
  Structure clamped = BuildCantilever(spec);
  clamped.rigid_supports.clear();
  for (const FamilyApplicability& a : ApplicableModelEffects(clamped)) {
    if (a.kind == "support_flexibility") {
      EXPECT_NE(a.why_not.find("rigid"), std::string::npos) << a.why_not;
    } else {
      EXPECT_TRUE(a.why_not.empty()) << a.kind << ": " << a.why_not;
    }
  }
  try {
    CreateModelEffects("support_flexibility", clamped);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cantilever"), std::string::npos) << e.what();
  }
  const Structure dry_chain = BuildSpringMassChain({{1, 1}, {10, 10}, {}});
  for (const FamilyApplicability& a : ApplicableModelEffects(dry_chain)) {
    EXPECT_EQ(a.why_not.empty(), a.kind != "added_mass" && a.kind != "axial_load")
        << a.kind << ": " << a.why_not;
  }
  EXPECT_EQ(CreateModelEffects("stiffness_loss", dry_chain).size(), 2u);
  EXPECT_EQ(CreateModelEffects("attached_mass", dry_chain).size(), 2u);
  try {
    CreateModelEffects("corrosion", dry_chain);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material_scaling"), std::string::npos);
  }
}

TEST(ModelEffects, ReferenceMassIsTheRigidTranslationsMass) {
  EXPECT_DOUBLE_EQ(ReferenceMass(TwoMassChain()), 3.0);
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 4));
  spec.support_transverse = 1e9;  // the base node moves too: the whole beam's mass
  const Structure s = BuildCantilever(spec);
  EXPECT_NEAR(ReferenceMass(s), 7850 * 8.8e-4 * 2.0, 1e-9);
}

}  // namespace
}  // namespace femup
