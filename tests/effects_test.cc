// The effect library (problems/include/femup/problems/effects.h): each family
// changes the cantilever's bending frequencies in the physically expected
// direction, and where a closed form exists by the exact amount: uniform
// scaling of E (exp(s/2)), transverse mass over the whole length
// (1/sqrt(1 + r)), a tip mass and a rotational base spring (Euler-Bernoulli
// frequency equations), a stiffness loss over whole elements (a model assembled
// here by hand from fe.h's element matrices). Frequencies are computed here from
// the built matrices (bending DOFs by label), not by the effect fit.
#include "femup/problems/effects.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "beam_dofs.h"
#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/fe.h"
#include "femup/core/fe/structure.h"
#include "paper_beam.h"
#include "vector_of.h"

namespace femup {
namespace {

using fixtures::PaperSection;

const double kPi = std::acos(-1.0);
const double kLength = fixtures::kEffectBeamLength;
const int kElements = fixtures::kEffectBeamElements;

CantileverSpec Nominal() { return fixtures::EffectBeam(); }

double Ei() { return PaperSection().E * PaperSection().I; }
double RhoA() { return PaperSection().rho * PaperSection().A; }

bool IsBendingLabel(const std::string& label) {
  const auto ends = [&](const char* s) {
    const std::string t(s);
    return label.size() > t.size() &&
           label.compare(label.size() - t.size(), t.size(), t) == 0;
  };
  return ends(":ux") || ends(":rz");
}

// Ascending bending frequencies (Hz) of dense K, M over the labelled DOFs,
// keeping the ux and rz rows only (the axial uy rows are left out; a straight
// vertical cantilever does not couple them).
Eigen::VectorXd BendingFrequencies(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m,
                                   const std::vector<std::string>& labels) {
  std::vector<int> keep;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (IsBendingLabel(labels[i])) keep.push_back(static_cast<int>(i));
  }
  return fixtures::SolveReducedModes(k, m, keep).hz;
}

Eigen::VectorXd BendingFrequencies(const CantileverSpec& spec) {
  const Structure s = BuildCantilever(spec);
  return BendingFrequencies(Eigen::MatrixXd(s.stiffness), Eigen::MatrixXd(s.mass),
                            s.dof_labels);
}

// The nominal spec with `effect` applied at `theta` (a dry state).
CantileverSpec Applied(const Effect& effect, const Eigen::VectorXd& theta,
                       const CantileverSpec& nominal = Nominal()) {
  CantileverSpec spec = nominal;
  effect.Apply(theta, Immersion::kDry, false, nominal, &spec);
  return spec;
}

Eigen::VectorXd Theta(std::initializer_list<double> v) { return fixtures::VectorOf(v); }

const EffectMagnitude* FindMagnitude(const std::vector<EffectMagnitude>& m,
                                     const std::string& name) {
  for (const EffectMagnitude& x : m) {
    if (x.name == name) return &x;
  }
  return nullptr;
}

// Expects the magnitude `name` with `unit` and `value` (relative 1e-12).
void ExpectMagnitude(const std::vector<EffectMagnitude>& m, const std::string& name,
                     const std::string& unit, double value) {
  const EffectMagnitude* x = FindMagnitude(m, name);
  ASSERT_NE(x, nullptr) << "no magnitude " << name;
  EXPECT_EQ(x->unit, unit) << name;
  EXPECT_NEAR(x->value, value, 1e-12 * std::abs(value)) << name;
}

// Root of f in [a, b] (f(a), f(b) of opposite signs) by bisection.
double Bisect(const std::function<double(double)>& f, double a, double b) {
  double fa = f(a);
  EXPECT_LT(fa * f(b), 0) << "no sign change in [" << a << ", " << b << "]";
  for (int i = 0; i < 200 && b - a > 1e-15 * std::abs(b); ++i) {
    const double c = 0.5 * (a + b), fc = f(c);
    if ((fc < 0) == (fa < 0)) {
      a = c;
      fa = fc;
    } else {
      b = c;
    }
  }
  return 0.5 * (a + b);
}

// The first root above `from` of f, scanning in steps of `step`.
double FirstRoot(const std::function<double(double)>& f, double from, double step) {
  double a = from, fa = f(a);
  for (int i = 0; i < 100000; ++i) {
    const double b = a + step, fb = f(b);
    if ((fa < 0) != (fb < 0)) return Bisect(f, a, b);
    a = b;
    fa = fb;
  }
  ADD_FAILURE() << "no root found";
  return std::numeric_limits<double>::quiet_NaN();
}

// Euler-Bernoulli frequency (Hz) for a root lambda = beta L.
double EulerBernoulliHz(double lambda) {
  return lambda * lambda / (2 * kPi * kLength * kLength) * std::sqrt(Ei() / RhoA());
}

// The node (x / L) of the clamped-free beam's second mode, from its closed-form
// shape cosh - cos - sigma (sinh - sin).
double SecondModeNode() {
  const double lambda = 4.69409113;
  const double sigma =
      (std::cosh(lambda) + std::cos(lambda)) / (std::sinh(lambda) + std::sin(lambda));
  const auto phi = [&](double xi) {
    const double a = lambda * xi;
    return std::cosh(a) - std::cos(a) - sigma * (std::sinh(a) - std::sin(a));
  };
  return Bisect(phi, 0.5, 0.95);
}

// ----------------------------------------------------------------------------

TEST(Effects, AvailableKindsAreCreatedWithTheirNames) {
  const std::vector<std::string> kinds = AvailableEffects();
  const std::vector<std::string> defaults = {"added_mass", "support_flexibility",
                                             "attached_mass", "stiffness_loss",
                                             "material_scaling"};
  EXPECT_EQ(DefaultEffects(), defaults);
  std::vector<std::string> expected = defaults;
  expected.push_back("axial_load");
  EXPECT_EQ(kinds, expected);
  for (const std::string& kind : kinds) {
    const std::unique_ptr<Effect> e = CreateEffect(kind);
    ASSERT_NE(e, nullptr) << kind;
    EXPECT_EQ(e->kind(), kind);
  }
}

TEST(Effects, UnknownKindThrowsInputErrorListingTheKnownOnes) {
  try {
    CreateEffect("nope");
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("nope"), std::string::npos) << what;
    for (const std::string& kind : AvailableEffects())
      EXPECT_NE(what.find(kind), std::string::npos) << kind << " not in: " << what;
  }
  EXPECT_THROW(CreateEffect(""), InputError);
  EXPECT_THROW(CreateEffect("Added_Mass"), InputError);
}

TEST(Effects, ParameterRangesAreFiniteAndStartsLieInside) {
  const CantileverSpec nominal = Nominal();
  EXPECT_DOUBLE_EQ(BeamLength(nominal), kLength);
  EXPECT_DOUBLE_EQ(BeamMassPerLength(nominal), RhoA());
  EXPECT_DOUBLE_EQ(BeamBendingStiffness(nominal), Ei());
  for (const std::string& kind : AvailableEffects()) {
    SCOPED_TRACE(kind);
    const std::unique_ptr<Effect> e = CreateEffect(kind);
    const std::vector<EffectParameter> params = e->Parameters(nominal);
    ASSERT_FALSE(params.empty());
    for (const EffectParameter& p : params) {
      SCOPED_TRACE(p.name);
      EXPECT_FALSE(p.name.empty());
      EXPECT_FALSE(p.description.empty());
      EXPECT_TRUE(std::isfinite(p.lower));
      EXPECT_TRUE(std::isfinite(p.upper));
      EXPECT_LT(p.lower, p.upper);
      if (p.location) {
        // Positions along the structure, in metres from the support.
        EXPECT_GE(p.lower, 0.0);
        EXPECT_LE(p.upper, kLength);
      }
    }
    const std::vector<Eigen::VectorXd> starts = e->Starts(nominal);
    ASSERT_FALSE(starts.empty());
    for (const Eigen::VectorXd& s : starts) {
      ASSERT_EQ(s.size(), static_cast<Eigen::Index>(params.size()));
      for (std::size_t i = 0; i < params.size(); ++i) {
        EXPECT_GE(s[i], params[i].lower) << params[i].name;
        EXPECT_LE(s[i], params[i].upper) << params[i].name;
      }
    }
  }
}

TEST(Effects, LocationParametersScaleWithTheLength) {
  // Ranges of positions follow the nominal's length: double it, they double.
  CantileverSpec longer = Nominal();
  longer.node_heights = UniformHeights(2 * kLength, kElements);
  for (const std::string& kind : AvailableEffects()) {
    SCOPED_TRACE(kind);
    const std::unique_ptr<Effect> e = CreateEffect(kind);
    const auto a = e->Parameters(Nominal()), b = e->Parameters(longer);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!a[i].location) continue;
      EXPECT_NEAR(b[i].lower, 2 * a[i].lower, 1e-12);
      EXPECT_NEAR(b[i].upper, 2 * a[i].upper, 1e-12);
    }
  }
}

TEST(Effects, EachKindLowersOrScalesTheBendingFrequencies) {
  const Eigen::VectorXd f0 = BendingFrequencies(Nominal());
  // A sizeable parameter vector per kind, inside the ranges.
  const std::map<std::string, Eigen::VectorXd> theta = {
      {"added_mass", Theta({std::log(0.5), 0.6 * kLength, 0.0})},
      {"support_flexibility", Theta({std::log(0.1), std::log(0.1)})},
      {"attached_mass", Theta({std::log(0.2), 0.55 * kLength, std::log(0.1)})},
      {"stiffness_loss", Theta({std::log(0.5), 0.37 * kLength, std::log(0.1)})},
  };
  for (const auto& [kind, t] : theta) {
    SCOPED_TRACE(kind);
    const std::unique_ptr<Effect> e = CreateEffect(kind);
    const Eigen::VectorXd f = BendingFrequencies(Applied(*e, t));
    for (int k = 0; k < 4; ++k) {
      EXPECT_LT(f[k], f0[k] * (1 - 1e-3)) << "mode " << k + 1;
    }
  }
}

TEST(Effects, MaterialScalingScalesEveryBendingFrequencyByExpHalfS) {
  const std::unique_ptr<Effect> e = CreateEffect("material_scaling");
  const Eigen::VectorXd f0 = BendingFrequencies(Nominal());
  for (double s : {-0.6, -0.2, 0.3, 0.7}) {
    const CantileverSpec spec = Applied(*e, Theta({s}));
    EXPECT_NEAR(spec.section.E, PaperSection().E * std::exp(s), 1e-6);
    EXPECT_EQ(spec.section.rho, PaperSection().rho);
    const Eigen::VectorXd f = BendingFrequencies(spec);
    ASSERT_EQ(f.size(), f0.size());
    for (int k = 0; k < 8; ++k) {
      EXPECT_NEAR(f[k] / f0[k], std::exp(0.5 * s), 1e-10) << "s " << s << " mode " << k;
    }
  }
}

TEST(Effects, MaterialScalingReportsWholeLengthAndFactor) {
  const std::unique_ptr<Effect> e = CreateEffect("material_scaling");
  const EffectLocation l = e->Location(Nominal(), Theta({0.25}));
  EXPECT_DOUBLE_EQ(l.x0, 0.0);
  EXPECT_DOUBLE_EQ(l.x1, kLength);
  ExpectMagnitude(e->Magnitudes(Nominal(), Theta({0.25})), "e_factor", "1",
                  std::exp(0.25));
}

TEST(Effects, AxialLoadIsAFractionOfEulersLoadThatMovesEveryBendingFrequency) {
  const std::unique_ptr<Effect> e = CreateEffect("axial_load");
  const double euler = M_PI * M_PI * Ei() / (4 * kLength * kLength);
  const Eigen::VectorXd f0 = BendingFrequencies(Nominal());
  for (double ratio : {-0.6, 0.4, 5.0}) {
    const CantileverSpec spec = Applied(*e, Theta({ratio}));
    EXPECT_NEAR(spec.axial_force, ratio * euler, 1e-9 * euler);
    const Eigen::VectorXd f = BendingFrequencies(spec);
    for (int k = 0; k < 4; ++k) {
      if (ratio > 0) {
        EXPECT_GT(f[k], f0[k] * (1 + 1e-4)) << ratio << " mode " << k + 1;
      } else {
        EXPECT_LT(f[k], f0[k] * (1 - 1e-4)) << ratio << " mode " << k + 1;
      }
    }
    // Geometric stiffness weighs slopes, bending stiffness curvatures: the
    // lowest mode, with the smallest curvature per slope, moves most.
    EXPECT_GT(std::abs(f[0] / f0[0] - 1), std::abs(f[3] / f0[3] - 1)) << ratio;
    const auto m = e->Magnitudes(Nominal(), Theta({ratio}));
    ExpectMagnitude(m, "axial_force", "N", ratio * euler);
    ExpectMagnitude(m, "force_ratio", "1", ratio);
  }
  const EffectLocation l = e->Location(Nominal(), Theta({1.0}));
  EXPECT_DOUBLE_EQ(l.x0, 0.0);
  EXPECT_DOUBLE_EQ(l.x1, kLength);
  // Compression stays below buckling over the whole range.
  const std::vector<EffectParameter> p = e->Parameters(Nominal());
  ASSERT_EQ(p.size(), 1u);
  EXPECT_GT(p[0].lower, -1.0);
  EXPECT_GT(BendingFrequencies(Applied(*e, Theta({p[0].lower})))[0], 0.0);
}

TEST(Effects, AddedMassOverTheWholeLengthLowersByOneOverSqrtOnePlusR) {
  // Transverse-only mass r rho A per length everywhere: the bending mass matrix
  // is (1 + r) times the nominal one, so every bending frequency divides by
  // sqrt(1 + r).
  const std::unique_ptr<Effect> e = CreateEffect("added_mass");
  const Eigen::VectorXd f0 = BendingFrequencies(Nominal());
  for (double r : {0.01, 0.5, 2.0, 4.9}) {
    const Eigen::VectorXd f =
        BendingFrequencies(Applied(*e, Theta({std::log(r), kLength, 0.0})));
    for (int k = 0; k < 8; ++k) {
      EXPECT_NEAR(f[k] / f0[k], 1 / std::sqrt(1 + r), 1e-9) << "r " << r << " mode " << k;
    }
  }
}

TEST(Effects, AddedMassDeeperLowersMoreAndReportsDepth) {
  const std::unique_ptr<Effect> e = CreateEffect("added_mass");
  const double r = 0.8;
  Eigen::VectorXd previous = BendingFrequencies(Nominal());
  for (double depth : {0.2, 0.45, 0.7, 1.0}) {
    const Eigen::VectorXd t = Theta({std::log(r), depth * kLength, 0.0});
    const Eigen::VectorXd f = BendingFrequencies(Applied(*e, t));
    // Mode 1 moves most where it moves most: more wetted length, lower f1.
    EXPECT_LT(f[0], previous[0]) << depth;
    previous = f;
    const EffectLocation l = e->Location(Nominal(), t);
    EXPECT_DOUBLE_EQ(l.depth, depth * kLength);
    EXPECT_DOUBLE_EQ(l.x0, 0.0);
    EXPECT_DOUBLE_EQ(l.x1, depth * kLength);
    const auto m = e->Magnitudes(Nominal(), t);
    ExpectMagnitude(m, "added_mass_per_length", "kg/m", r * RhoA());
    ExpectMagnitude(m, "added_mass_total", "kg", r * RhoA() * depth * kLength);
    ASSERT_NE(FindMagnitude(m, "added_mass_ratio"), nullptr);
    EXPECT_NEAR(FindMagnitude(m, "added_mass_ratio")->value, r, 1e-12);
  }
}

TEST(Effects, AddedMassFadeLiesBetweenTheSharpEndsItSpans) {
  // A mass faded linearly over the top part f d of its depth d carries
  // r rho A (d - f d / 2) kg; its mass distribution lies between that of the
  // sharp-ended mass to d - f d and the sharp-ended mass to d, so every bending
  // frequency does too (the Rayleigh quotient falls as mass is added).
  const std::unique_ptr<Effect> e = CreateEffect("added_mass");
  const std::vector<EffectParameter> p = e->Parameters(Nominal());
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[2].name, "fade");
  EXPECT_EQ(p[2].lower, 0.0);
  EXPECT_EQ(p[2].upper, 0.5);
  const double r = 0.6, depth = 0.8 * kLength;
  for (double fade : {0.1, 0.3, 0.5}) {
    SCOPED_TRACE(fade);
    const Eigen::VectorXd t = Theta({std::log(r), depth, fade});
    const Eigen::VectorXd faded = BendingFrequencies(Applied(*e, t));
    const Eigen::VectorXd full =
        BendingFrequencies(Applied(*e, Theta({std::log(r), depth, 0.0})));
    const Eigen::VectorXd shorter =
        BendingFrequencies(Applied(*e, Theta({std::log(r), depth * (1 - fade), 0.0})));
    for (int k = 0; k < 4; ++k) {
      EXPECT_LT(full[k], faded[k]) << k;
      EXPECT_LT(faded[k], shorter[k]) << k;
    }
    const auto m = e->Magnitudes(Nominal(), t);
    ExpectMagnitude(m, "fade_length", "m", fade * depth);
    ExpectMagnitude(m, "added_mass_total", "kg", r * RhoA() * depth * (1 - fade / 2));
    EXPECT_DOUBLE_EQ(e->Location(Nominal(), t).depth, depth);
  }
}

TEST(Effects, AddedMassActsInWetStatesOnlyWhenAsked) {
  const std::unique_ptr<Effect> e = CreateEffect("added_mass");
  const CantileverSpec nominal = Nominal();
  const Eigen::VectorXd t = Theta({std::log(0.5), kLength, 0.0});
  CantileverSpec dry = nominal, wet = nominal, dry_always = nominal;
  e->Apply(t, Immersion::kDry, true, nominal, &dry);
  e->Apply(t, Immersion::kWet, true, nominal, &wet);
  e->Apply(t, Immersion::kDry, false, nominal, &dry_always);
  const Eigen::VectorXd f0 = BendingFrequencies(nominal);
  const Eigen::VectorXd f_dry = BendingFrequencies(dry);
  const Eigen::VectorXd f_wet = BendingFrequencies(wet);
  const Eigen::VectorXd f_always = BendingFrequencies(dry_always);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(f_dry[k] / f0[k], 1.0, 1e-12);
    EXPECT_NEAR(f_wet[k] / f0[k], 1 / std::sqrt(1.5), 1e-9);
    EXPECT_NEAR(f_always[k] / f0[k], 1 / std::sqrt(1.5), 1e-9);
  }
}

TEST(Effects, SupportFlexibilityMatchesTheRotationalSpringFrequencyEquation) {
  // Translation nearly rigid (compliance 1e-6), rotation compliance c = EI / (k L):
  // the Euler-Bernoulli beam with w(0) = 0, EI w''(0) = k w'(0), free tip. With
  // w = a cos + b sin + c cosh + d sinh of lambda x / L and kappa = k L / EI:
  //   a + c = 0, lambda (c - a) - kappa (b + d) = 0,
  //   -a cos + -b sin + c cosh + d sinh = 0 at lambda, a sin - b cos + c sinh + d
  //   cosh = 0 at lambda.
  const std::unique_ptr<Effect> e = CreateEffect("support_flexibility");
  for (double compliance : {0.05, 0.5, 3.0}) {
    SCOPED_TRACE(compliance);
    const double kappa = 1 / compliance;
    const auto det = [kappa](double lambda) {
      const double c = std::cos(lambda), s = std::sin(lambda), ch = std::cosh(lambda),
                   sh = std::sinh(lambda);
      Eigen::Matrix4d m;
      m << 1, 0, 1, 0,                      //
          -lambda, -kappa, lambda, -kappa,  //
          -c, -s, ch, sh,                   //
          s, -c, sh, ch;
      return m.determinant();
    };
    const double lambda1 = FirstRoot(det, 0.05, 0.01);
    const double lambda2 = FirstRoot(det, lambda1 + 0.05, 0.01);
    const Eigen::VectorXd t = Theta({std::log(compliance), std::log(1e-6)});
    const CantileverSpec spec = Applied(*e, t);
    EXPECT_NEAR(spec.support_rotation, Ei() / (kLength * compliance),
                1e-9 * spec.support_rotation);
    const Eigen::VectorXd f = BendingFrequencies(spec);
    EXPECT_NEAR(f[0] / EulerBernoulliHz(lambda1), 1.0, 2e-5);
    EXPECT_NEAR(f[1] / EulerBernoulliHz(lambda2), 1.0, 2e-5);
    // Softer than the clamped beam.
    EXPECT_LT(lambda1, 1.87510407);
  }
}

TEST(Effects, SupportFlexibilityLowersMoreWhenSofterAndReportsStiffnesses) {
  const std::unique_ptr<Effect> e = CreateEffect("support_flexibility");
  const Eigen::VectorXd f0 = BendingFrequencies(Nominal());
  // Each spring alone lowers every mode; a softer spring lowers more.
  for (int which = 0; which < 2; ++which) {
    Eigen::VectorXd previous = f0;
    for (double c : {1e-3, 1e-2, 1e-1, 1.0}) {
      Eigen::VectorXd t = Theta({std::log(1e-6), std::log(1e-6)});
      t[which] = std::log(c);
      const Eigen::VectorXd f = BendingFrequencies(Applied(*e, t));
      for (int k = 0; k < 4; ++k) EXPECT_LT(f[k], previous[k]) << which << " " << c;
      previous = f;
    }
  }
  const Eigen::VectorXd t = Theta({std::log(0.2), std::log(0.05)});
  const CantileverSpec spec = Applied(*e, t);
  const double k_rot = Ei() / (kLength * 0.2);
  const double k_tr = 3 * Ei() / (kLength * kLength * kLength * 0.05);
  EXPECT_NEAR(spec.support_rotation, k_rot, 1e-9 * k_rot);
  EXPECT_NEAR(spec.support_transverse, k_tr, 1e-9 * k_tr);
  const EffectLocation l = e->Location(Nominal(), t);
  EXPECT_DOUBLE_EQ(l.x, 0.0);
  const auto m = e->Magnitudes(Nominal(), t);
  ExpectMagnitude(m, "rotational_stiffness", "N m/rad", k_rot);
  ExpectMagnitude(m, "translational_stiffness", "N/m", k_tr);
}

TEST(Effects, SupportFlexibilityActsInSeriesWithANominalSpring) {
  const std::unique_ptr<Effect> e = CreateEffect("support_flexibility");
  CantileverSpec nominal = Nominal();
  nominal.support_rotation = 5e4;
  nominal.support_transverse = 2e6;
  const Eigen::VectorXd t = Theta({std::log(0.3), std::log(0.1)});
  const CantileverSpec spec = Applied(*e, t, nominal);
  const double k_rot = Ei() / (kLength * 0.3);
  const double k_tr = 3 * Ei() / (kLength * kLength * kLength * 0.1);
  EXPECT_NEAR(spec.support_rotation, 1 / (1 / 5e4 + 1 / k_rot), 1e-6);
  EXPECT_NEAR(spec.support_transverse, 1 / (1 / 2e6 + 1 / k_tr), 1e-4);
  const Eigen::VectorXd f0 = BendingFrequencies(nominal);
  const Eigen::VectorXd f = BendingFrequencies(spec);
  for (int k = 0; k < 4; ++k) EXPECT_LT(f[k], f0[k]);
}

TEST(Effects, AttachedMassAtTheTipMatchesTheTipMassFrequencyEquation) {
  // Clamped-free beam with a tip mass mu rho A L (no rotary inertia):
  //   1 + cos cosh + mu lambda (cos sinh - sin cosh) = 0.
  const std::unique_ptr<Effect> e = CreateEffect("attached_mass", {false});
  for (double mu : {0.05, 0.5, 2.0}) {
    SCOPED_TRACE(mu);
    const auto g = [mu](double l) {
      return 1 + std::cos(l) * std::cosh(l) +
             mu * l * (std::cos(l) * std::sinh(l) - std::sin(l) * std::cosh(l));
    };
    const double lambda1 = FirstRoot(g, 0.1, 0.01);
    const double lambda2 = FirstRoot(g, lambda1 + 0.05, 0.01);
    const Eigen::VectorXd t = Theta({std::log(mu), kLength});
    const Eigen::VectorXd f = BendingFrequencies(Applied(*e, t));
    EXPECT_NEAR(f[0] / EulerBernoulliHz(lambda1), 1.0, 1e-6);
    EXPECT_NEAR(f[1] / EulerBernoulliHz(lambda2), 1.0, 1e-5);
    EXPECT_DOUBLE_EQ(e->Location(Nominal(), t).x, kLength);
    const auto m = e->Magnitudes(Nominal(), t);
    ExpectMagnitude(m, "mass", "kg", mu * RhoA() * kLength);
    ASSERT_NE(FindMagnitude(m, "mass_ratio"), nullptr);
    EXPECT_NEAR(FindMagnitude(m, "mass_ratio")->value, mu, 1e-12);
  }
}

// With its rotary inertia j rho A L^3 (j = mu (r / L)^2), the tip's moment
// balancing it too:
//   1 + cos cosh + mu l (cos sinh - sin cosh) - j l^3 (cosh sin + sinh cos)
//     + mu j l^4 (1 - cos cosh) = 0
// (checked against a 200-element numpy beam to 1e-6 when written).
TEST(Effects, AttachedMassWithRotaryInertiaMatchesTheTipBodyFrequencyEquation) {
  const std::unique_ptr<Effect> e = CreateEffect("attached_mass");
  ASSERT_EQ(e->Parameters(Nominal()).size(), 3u);
  EXPECT_EQ(e->Parameters(Nominal())[2].quantity, "radius_of_gyration_m");
  for (const auto& [mu, rel] : {std::pair{0.3, 0.26}, std::pair{1.0, 0.1}}) {
    SCOPED_TRACE(mu);
    const double j = mu * rel * rel;
    const auto g = [mu = mu, j](double l) {
      const double c = std::cos(l), s = std::sin(l), ch = std::cosh(l), sh = std::sinh(l);
      return 1 + c * ch + mu * l * (c * sh - s * ch) - j * l * l * l * (ch * s + sh * c) +
             mu * j * l * l * l * l * (1 - c * ch);
    };
    const double lambda1 = FirstRoot(g, 0.1, 0.01);
    const double lambda2 = FirstRoot(g, lambda1 + 0.05, 0.01);
    const Eigen::VectorXd t = Theta({std::log(mu), kLength, std::log(rel)});
    const Eigen::VectorXd f = BendingFrequencies(Applied(*e, t));
    EXPECT_NEAR(f[0] / EulerBernoulliHz(lambda1), 1.0, 1e-5);
    EXPECT_NEAR(f[1] / EulerBernoulliHz(lambda2), 1.0, 1e-4);
    const auto m = e->Magnitudes(Nominal(), t);
    ExpectMagnitude(m, "radius_of_gyration", "m", rel * kLength);
    ExpectMagnitude(m, "rotary_inertia", "kg m^2", j * RhoA() * std::pow(kLength, 3));
  }
}

TEST(Effects, AttachedMassAtTheTipLowersModeOneMoreThanAtMidHeight) {
  const std::unique_ptr<Effect> e = CreateEffect("attached_mass", {false});
  const Eigen::VectorXd f0 = BendingFrequencies(Nominal());
  const double ln_mu = std::log(0.1);
  const Eigen::VectorXd tip = BendingFrequencies(Applied(*e, Theta({ln_mu, kLength})));
  const Eigen::VectorXd mid =
      BendingFrequencies(Applied(*e, Theta({ln_mu, 0.5 * kLength})));
  EXPECT_LT(mid[0], f0[0]);
  EXPECT_LT(f0[0] - mid[0], f0[0] - tip[0]);
  // Rayleigh, first order: the drop of f1 scales with phi1^2 at the mass; the
  // Euler-Bernoulli shape has phi1(L/2)^2 / phi1(L)^2 ~ 0.116, so the mid-height
  // drop is well under a third of the tip's.
  EXPECT_LT(f0[0] - mid[0], 0.3 * (f0[0] - tip[0]));
}

TEST(Effects, AttachedMassAtANodeOfModeTwoLeavesModeTwoAlone) {
  // At the node of mode 2 (from the closed-form shape, x / L ~ 0.7834, between
  // mesh nodes) the mass does no work in mode 2 to first order; modes 1 and 3
  // still drop. The same mass at the tip moves mode 2 by orders of magnitude more.
  const std::unique_ptr<Effect> e = CreateEffect("attached_mass", {false});
  const double node = SecondModeNode();
  EXPECT_NEAR(node, 0.7834, 2e-4);
  const Eigen::VectorXd f0 = BendingFrequencies(Nominal());
  const double ln_mu = std::log(0.05);
  const Eigen::VectorXd at_node =
      BendingFrequencies(Applied(*e, Theta({ln_mu, node * kLength})));
  const Eigen::VectorXd at_tip = BendingFrequencies(Applied(*e, Theta({ln_mu, kLength})));
  const double drop_node = (f0[1] - at_node[1]) / f0[1];
  const double drop_tip = (f0[1] - at_tip[1]) / f0[1];
  EXPECT_GT(drop_tip, 0.02);
  EXPECT_GE(drop_node, -1e-12);  // a mass never raises a frequency
  EXPECT_LT(drop_node, 1e-3 * drop_tip);
  EXPECT_LT(at_node[0], f0[0] * (1 - 1e-3));
  EXPECT_LT(at_node[2], f0[2] * (1 - 1e-3));
  EXPECT_DOUBLE_EQ(e->Location(Nominal(), Theta({ln_mu, node * kLength})).x,
                   node * kLength);
}

// Bending (ux, rz) stiffness and mass of the clamped cantilever assembled here
// from fe.h's element matrices, element e's E I times ei_factor[e].
void AssembleByHand(const std::vector<double>& ei_factor, Eigen::MatrixXd* k,
                    Eigen::MatrixXd* m, std::vector<std::string>* labels) {
  const std::vector<double> z = UniformHeights(kLength, kElements);
  const int nodes = static_cast<int>(z.size());
  const int n = 3 * (nodes - 1);  // base clamped
  k->setZero(n, n);
  m->setZero(n, n);
  labels->clear();
  for (int node = 1; node < nodes; ++node) {
    for (const char* name : {":ux", ":uy", ":rz"})
      labels->push_back("n" + std::to_string(node) + name);
  }
  for (int e = 0; e < kElements; ++e) {
    BeamSection s = PaperSection();
    s.E *= ei_factor[e];
    const Matrix6 ke = Frame2dStiffness(s, 0, z[e], 0, z[e + 1]);
    const Matrix6 me = Frame2dConsistentMass(PaperSection(), 0, z[e], 0, z[e + 1]);
    for (int a = 0; a < 6; ++a) {
      const int ga = 3 * (e + a / 3) + a % 3 - 3;  // node e + a/3, base gone
      if (ga < 0) continue;
      for (int b = 0; b < 6; ++b) {
        const int gb = 3 * (e + b / 3) + b % 3 - 3;
        if (gb < 0) continue;
        (*k)(ga, gb) += ke(a, b);
        (*m)(ga, gb) += me(a, b);
      }
    }
  }
}

TEST(Effects, StiffnessLossOverWholeElementsMatchesAHandAssembledBeam) {
  // The region is a tenth of the length (two elements here); centred on a mesh
  // node it covers exactly two elements, whose E I becomes (1 - loss) E I.
  const std::unique_ptr<Effect> e = CreateEffect("stiffness_loss");
  const double loss = 0.4;
  for (int centre_node : {1, 5, 12, 19}) {
    SCOPED_TRACE(centre_node);
    const double x = kLength * centre_node / kElements;
    const Eigen::VectorXd t = Theta({std::log(loss), x, std::log(0.1)});
    std::vector<double> factor(kElements, 1.0);
    factor[centre_node - 1] = factor[centre_node] = 1 - loss;
    Eigen::MatrixXd k, m;
    std::vector<std::string> labels;
    AssembleByHand(factor, &k, &m, &labels);
    const Eigen::VectorXd expected = BendingFrequencies(k, m, labels);
    const Eigen::VectorXd f = BendingFrequencies(Applied(*e, t));
    ASSERT_EQ(f.size(), expected.size());
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(f[i] / expected[i], 1.0, 1e-9) << i;
    const EffectLocation l = e->Location(Nominal(), t);
    EXPECT_DOUBLE_EQ(l.x, x);
    EXPECT_NEAR(l.x0, x - 0.05 * kLength, 1e-14);
    EXPECT_NEAR(l.x1, x + 0.05 * kLength, 1e-14);
    const auto mags = e->Magnitudes(Nominal(), t);
    ExpectMagnitude(mags, "ei_loss_fraction", "1", loss);
    ExpectMagnitude(mags, "region_width", "m", 0.1 * kLength);
  }
}

TEST(Effects, StiffnessLossWidthSetsTheRegionAndIsClippedAtTheEnds) {
  // Width 0.3 L centred on node 10 covers elements 8..13 (six elements).
  const std::unique_ptr<Effect> e = CreateEffect("stiffness_loss");
  const std::vector<EffectParameter> p = e->Parameters(Nominal());
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[2].name, "ln_width");
  EXPECT_NEAR(std::exp(p[2].lower), 0.02, 1e-15);
  EXPECT_NEAR(std::exp(p[2].upper), 0.4, 1e-15);
  const double loss = 0.5, x = 0.5 * kLength;
  const Eigen::VectorXd t = Theta({std::log(loss), x, std::log(0.3)});
  std::vector<double> factor(kElements, 1.0);
  for (int k = 7; k < 13; ++k) factor[k] = 1 - loss;
  Eigen::MatrixXd k, m;
  std::vector<std::string> labels;
  AssembleByHand(factor, &k, &m, &labels);
  const Eigen::VectorXd expected = BendingFrequencies(k, m, labels);
  const Eigen::VectorXd f = BendingFrequencies(Applied(*e, t));
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(f[i] / expected[i], 1.0, 1e-9) << i;
  ExpectMagnitude(e->Magnitudes(Nominal(), t), "region_width", "m", 0.3 * kLength);
  // Centred 0.05 L from the base with width 0.3 L: the region is [0, 0.2 L],
  // and its location is that region's centre.
  const Eigen::VectorXd at_base = Theta({std::log(loss), 0.05 * kLength, std::log(0.3)});
  const EffectLocation l = e->Location(Nominal(), at_base);
  EXPECT_NEAR(l.x0, 0.0, 1e-15);
  EXPECT_NEAR(l.x1, 0.2 * kLength, 1e-14);
  EXPECT_NEAR(l.x, 0.1 * kLength, 1e-14);
  ExpectMagnitude(e->Magnitudes(Nominal(), at_base), "region_width", "m", 0.2 * kLength);
}

TEST(Effects, StiffnessLossNearTheBaseLowersModeOneMoreThanNearTheTip) {
  const std::unique_ptr<Effect> e = CreateEffect("stiffness_loss");
  const Eigen::VectorXd f0 = BendingFrequencies(Nominal());
  const double ln_loss = std::log(0.3);
  const Eigen::VectorXd base =
      BendingFrequencies(Applied(*e, Theta({ln_loss, 0.05 * kLength, std::log(0.1)})));
  const Eigen::VectorXd tip =
      BendingFrequencies(Applied(*e, Theta({ln_loss, 0.95 * kLength, std::log(0.1)})));
  EXPECT_LT(base[0], f0[0]);
  EXPECT_LE(tip[0], f0[0]);
  // Mode 1's curvature is largest at the base and vanishes at the tip.
  EXPECT_GT(f0[0] - base[0], 10 * (f0[0] - tip[0]));
  // A larger loss at the same place lowers more.
  const Eigen::VectorXd bigger = BendingFrequencies(
      Applied(*e, Theta({std::log(0.6), 0.05 * kLength, std::log(0.1)})));
  EXPECT_LT(bigger[0], base[0]);
}

}  // namespace
}  // namespace femup
