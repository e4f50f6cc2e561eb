// Stated priors on the effect families (problems/effect_priors.h): physical
// ranges and normal priors converted into the families' coordinates, the
// instances kept by regions, the normal priors' fit residuals against
// differences, and every refusal naming its field.
#include "femup/problems/effect_priors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/fe/space_frame.h"
#include "prior_builders.h"
#include "structure_specs.h"

namespace femup {
namespace {

ChainSpec Chain() { return fixtures::UniformChain(4, 1e4, 5e7); }

using fixtures::Normal;
using fixtures::Prior;
using fixtures::Range;

// The message of the InputError `f` throws, with its where() in *where.
template <typename F>
std::string ErrorOf(F f, std::string* where = nullptr) {
  try {
    f();
  } catch (const InputError& e) {
    if (where) *where = e.where();
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return "";
}

bool Has(const std::string& text, const std::string& needle) {
  return text.find(needle) != std::string::npos;
}

TEST(EffectPriors, QuantitiesMapToTheCoordinatesAndBack) {
  const EffectParameter log_p = LogQuantity({"ln_m", "", -1, 1, false}, "mass_kg", 37.0);
  EXPECT_NEAR(QuantityAt(log_p, std::log(2.0)), 74.0, 1e-12);
  EXPECT_NEAR(CoordinateOf(log_p, 74.0), std::log(2.0), 1e-15);
  const EffectParameter lin =
      LinearQuantity({"f", "", -1, 1, false}, "force_n", 50.0, -40.0,
                     std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(QuantityAt(lin, 0.3), 15.0);
  EXPECT_DOUBLE_EQ(CoordinateOf(lin, 15.0), 0.3);
}

TEST(EffectPriors, EveryStructureFamilyNamesItsQuantities) {
  Structure s = BuildSpringMassChain(Chain());
  s.elements[0].wet = true;
  for (const FamilyApplicability& a : ApplicableModelEffects(s)) {
    if (!a.why_not.empty()) continue;  // axial_load: a chain has no geometric stiffness
    const std::string& kind = a.kind;
    const auto made = CreateModelEffects(kind, s);
    ASSERT_FALSE(made.empty()) << kind;
    for (const EffectParameter& p : made.front()->Parameters())
      EXPECT_FALSE(p.quantity.empty()) << kind << " " << p.name;
  }
  // The attached mass is in kg: m = m_ref exp(theta).
  const auto mass = CreateModelEffects("attached_mass", s);
  const EffectParameter p = mass.front()->Parameters()[0];
  EXPECT_EQ(p.quantity, "mass_kg");
  EXPECT_NEAR(QuantityAt(p, 0.0), ReferenceMass(s), 1e-9);
}

TEST(EffectPriors, ARangeReplacesTheDefaultRangeInTheCoordinate) {
  const Structure s = BuildSpringMassChain(Chain());
  const double m_ref = ReferenceMass(s);  // 4e4 kg
  const auto made = CreateModelEffects("attached_mass", s);
  // 2 g to 10 g: far below the default range (1e-4 of the structure's mass).
  const auto params =
      ApplyFamilyPrior(made.front()->Parameters(),
                       Prior("attached_mass", {Range("mass_kg", 0.002, 0.010)}));
  EXPECT_NEAR(params[0].lower, std::log(0.002 / m_ref), 1e-12);
  EXPECT_NEAR(params[0].upper, std::log(0.010 / m_ref), 1e-12);
  EXPECT_EQ(params[0].normal_sigma, 0.0);
}

TEST(EffectPriors, ANormalPriorBoundsTheFitAtSixSigmaWithinTheDefaultRange) {
  const Structure s = BuildSpringMassChain(Chain());
  const auto material = CreateModelEffects("material_scaling", s);
  auto p = ApplyFamilyPrior(material.front()->Parameters(),
                            Prior("material_scaling", {Normal("factor", 1.0, 0.05)}));
  EXPECT_NEAR(p[0].lower, std::log(0.7), 1e-12);
  EXPECT_NEAR(p[0].upper, std::log(1.3), 1e-12);
  EXPECT_EQ(p[0].normal_mean, 1.0);
  EXPECT_EQ(p[0].normal_sigma, 0.05);
  // Wider than the default range (factor e^-0.7 to e^0.7): clipped to it.
  p = ApplyFamilyPrior(material.front()->Parameters(),
                       Prior("material_scaling", {Normal("factor", 1.0, 0.5)}));
  EXPECT_NEAR(p[0].lower, -0.7, 1e-12);
  EXPECT_NEAR(p[0].upper, 0.7, 1e-12);
  // A mean outside the default range: mean +- 6 sigma, at least 1 % of the
  // mean in a log coordinate.
  const auto mass = CreateModelEffects("attached_mass", s);
  const double m_ref = ReferenceMass(s);
  p = ApplyFamilyPrior(mass.front()->Parameters(),
                       Prior("attached_mass", {Normal("mass_kg", 0.005, 0.001)}));
  EXPECT_NEAR(p[0].lower, std::log(0.00005 / m_ref), 1e-12);
  EXPECT_NEAR(p[0].upper, std::log(0.011 / m_ref), 1e-12);
  // A loss of 0.5 +- 0.2: up to the default's 0.9, down to 1 % of the mean
  // (above the default's 3e-3).
  const auto loss = CreateModelEffects("stiffness_loss", s);
  p = ApplyFamilyPrior(loss.front()->Parameters(),
                       Prior("stiffness_loss", {Normal("loss", 0.5, 0.2)}));
  EXPECT_NEAR(p[0].upper, std::log(0.9), 1e-12);
  EXPECT_NEAR(p[0].lower, std::log(0.005), 1e-12);
}

TEST(EffectPriors, QuantitiesTheFamilyLacksAndValuesOutsideTheirDomainAreRefused) {
  const Structure s = BuildSpringMassChain(Chain());
  const auto loss = CreateModelEffects("stiffness_loss", s);
  std::string where;
  std::string msg = ErrorOf(
      [&] {
        ApplyFamilyPrior(loss.front()->Parameters(),
                         Prior("stiffness_loss", {Range("mass_kg", 1, 2)}));
      },
      &where);
  EXPECT_EQ(where, "mass_kg");
  EXPECT_TRUE(Has(msg, "its quantities: loss")) << msg;
  msg = ErrorOf(
      [&] {
        ApplyFamilyPrior(loss.front()->Parameters(),
                         Prior("stiffness_loss", {Range("loss", 0.5, 1.2)}));
      },
      &where);
  EXPECT_EQ(where, "loss");
  EXPECT_TRUE(Has(msg, "(0, 0.99]")) << msg;
  const auto mass = CreateModelEffects("attached_mass", s);
  msg = ErrorOf([&] {
    ApplyFamilyPrior(mass.front()->Parameters(),
                     Prior("attached_mass", {Range("mass_kg", -1, 2)}));
  });
  EXPECT_TRUE(Has(msg, "(0, inf)")) << msg;
  msg = ErrorOf([&] {
    ApplyFamilyPrior(mass.front()->Parameters(),
                     Prior("attached_mass", {Normal("mass_kg", 0, 2)}));
  });
  EXPECT_TRUE(Has(msg, "the mean 0")) << msg;
}

// Where the supports restrain translations and rotations (a clamped frame's
// bases), support flexibility has a ratio for each, stated one by one; the
// one-ratio key of a chain's ground spring is refused, naming the two.
TEST(EffectPriors, SupportFlexibilityOfAClampedFrameStatesEachDirectionsRatio) {
  const Structure frame = BuildPlaneFrameStructure(fixtures::PlaneFrame(2, 1, 2));
  const auto support = CreateModelEffects("support_flexibility", frame);
  ASSERT_EQ(support.size(), 1u);
  const std::vector<EffectParameter> stated = ApplyFamilyPrior(
      support.front()->Parameters(),
      Prior("support_flexibility", {Range("rotation_compliance_ratio", 0.5, 4)}));
  ASSERT_EQ(stated.size(), 2u);
  EXPECT_NEAR(stated[1].lower, std::log(0.5), 1e-15);
  EXPECT_NEAR(stated[1].upper, std::log(4.0), 1e-15);
  EXPECT_NEAR(stated[0].lower, std::log(1e-3), 1e-15);  // the translations' default
  std::string where;
  const std::string msg = ErrorOf(
      [&] {
        ApplyFamilyPrior(
            support.front()->Parameters(),
            Prior("support_flexibility", {Range("compliance_ratio", 0.1, 1)}));
      },
      &where);
  EXPECT_EQ(where, "compliance_ratio");
  EXPECT_TRUE(
      Has(msg, "its quantities: translation_compliance_ratio, rotation_compliance_ratio"))
      << msg;
}

TEST(EffectPriors, ValidateNamesTheField) {
  StatedPriors p;
  EXPECT_EQ(p.Validate().ToString(), "");
  EXPECT_TRUE(p.empty());
  p.families = {Prior("attached_mass", {Range("mass_kg", 0.01, 0.002)})};
  EXPECT_EQ(p.Validate().ToString(),
            "priors.attached_mass.mass_kg: lower 0.01 > upper 0.002");
  p.families = {Prior("attached_mass", {Range("mass_kg", 0.01, 0.01)})};
  EXPECT_TRUE(Has(p.Validate().ToString(), "priors.attached_mass.mass_kg: lower = upper"))
      << p.Validate().ToString();
  p.families = {Prior("material_scaling", {Normal("factor", 1, 0)})};
  EXPECT_TRUE(Has(p.Validate().ToString(), "priors.material_scaling.factor: normal"))
      << p.Validate().ToString();
  p.families = {
      Prior("material_scaling", {Normal("factor", 1, 0.1), Normal("factor", 1, 0.1)})};
  EXPECT_TRUE(Has(p.Validate().ToString(), "stated twice")) << p.Validate().ToString();
  p.families = {Prior("stiffness_loss", {}, {"3", "3"})};
  EXPECT_TRUE(Has(p.Validate().ToString(), "priors.stiffness_loss.regions[2]"))
      << p.Validate().ToString();
  p.families.clear();
  p.weights = {{"none", 1}, {"stiffness_loss", -2}};
  EXPECT_TRUE(Has(p.Validate().ToString(), "weights.stiffness_loss"))
      << p.Validate().ToString();
  p.weights = {{"none", 3}, {"stiffness_loss", 2}};
  EXPECT_EQ(p.Validate().ToString(), "");
  EXPECT_EQ(p.Weight("none"), 3);
  EXPECT_EQ(p.Weight("attached_mass"), 1);
}

TEST(EffectPriors, RegionsKeepTheNamedElementsAndNodes) {
  const Structure s = BuildSpringMassChain(Chain());
  // Elements by id (a chain's labels are its ids).
  auto kept = KeepStatedRegions(CreateModelEffects("stiffness_loss", s), s,
                                Prior("stiffness_loss", {}, {"3", "1"}));
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0]->region().name, "element 1");
  EXPECT_EQ(kept[1]->region().name, "element 3");
  kept = KeepStatedRegions(CreateModelEffects("attached_mass", s), s,
                           Prior("attached_mass", {}, {"x4"}));
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0]->region().name, "node x4");
  // A frame's members by label, nodes by name.
  PlaneFrameSpec frame;
  frame.storeys = 2;
  frame.bays = 1;
  frame.storey_height = 3.5;
  frame.bay_width = 6;
  frame.elements_per_member = 2;
  frame.column = {210e9, 7.8e-3, 8.4e-5, 7850};
  frame.beam = {210e9, 5.4e-3, 1.9e-4, 7850};
  const Structure f = BuildPlaneFrameStructure(frame);
  kept = KeepStatedRegions(CreateModelEffects("stiffness_loss", f), f,
                           Prior("stiffness_loss", {}, {"s1:beam1"}));
  // The beam's own stiffness loss, its end connections', and each of its two
  // elements' (a loss over half of it).
  ASSERT_EQ(kept.size(), 4u);
  EXPECT_EQ(kept[0]->region().name, "element s1:beam1");
  EXPECT_EQ(kept[1]->region().name, "connections of s1:beam1");
  EXPECT_EQ(kept[2]->region().name, "member s1:beam1 (0.00-0.50)");
  EXPECT_EQ(kept[3]->region().name, "member s1:beam1 (0.50-1.00)");
  kept = KeepStatedRegions(CreateModelEffects("attached_mass", f), f,
                           Prior("attached_mass", {}, {"n7"}));
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0]->region().name, "node n7");
  // A member named for an attached mass keeps the masses between its nodes
  // (its two elements, both ending at its middle node n7).
  kept = KeepStatedRegions(CreateModelEffects("attached_mass", f), f,
                           Prior("attached_mass", {}, {"s1:beam1"}));
  ASSERT_EQ(kept.size(), 2u);
  for (const auto& k : kept) {
    EXPECT_NE(k->region().name.find("n7"), std::string::npos) << k->region().name;
    EXPECT_EQ(k->Parameters().size(), 3u);  // mass, position, radius of gyration
  }
}

// A space frame's stiffness loss acts on its groups, on each member
// (Structure::members) and on each member's finite elements: a member is named
// by its label and keeps its parts, a group keeps itself and its members, and
// a member named for a family that does not act on members is refused as such.
TEST(EffectPriors, RegionsNameTheMembersOfASpaceFrame) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(2, 1, 1, 2, 10, 12, 12);
  spec.bracing = FaceBracing::kX;
  const Structure s = BuildSpaceFrameStructure(spec);
  // Each member and each of its two finite elements (MemberPartName).
  auto all = CreateModelEffects("stiffness_loss", s);
  ASSERT_EQ(all.size(), s.elements.size() + 3 * s.members.size());
  auto kept = KeepStatedRegions(CreateModelEffects("stiffness_loss", s), s,
                                Prior("stiffness_loss", {}, {"brace n1-n13"}));
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept[0]->region().name, "member brace n1-n13");
  EXPECT_EQ(kept[1]->region().name, "member brace n1-n13 (0.00-0.50)");
  EXPECT_EQ(kept[2]->region().name, "member brace n1-n13 (0.50-1.00)");
  EXPECT_EQ(kept[0]->region().part, -1);
  EXPECT_EQ(kept[2]->region().part, 1);
  EXPECT_EQ(kept[2]->region().member, kept[0]->region().member);
  kept = KeepStatedRegions(CreateModelEffects("stiffness_loss", s), s,
                           Prior("stiffness_loss", {}, {"l1:legs1"}));
  ASSERT_EQ(kept.size(), 1u + 4u * 3u);
  EXPECT_EQ(kept[0]->region().name, "element l1:legs1");
  EXPECT_EQ(kept[1]->region().name, "member leg b1-n1");
  EXPECT_EQ(kept[2]->region().name, "member leg b1-n1 (0.00-0.50)");
  std::string where;
  const std::string msg = ErrorOf(
      [&] {
        KeepStatedRegions(CreateModelEffects("attached_mass", s), s,
                          Prior("attached_mass", {}, {"brace n1-n13"}));
      },
      &where);
  EXPECT_EQ(where, "regions[1]");
  EXPECT_TRUE(Has(msg, "names a member, but attached_mass acts at places such as"))
      << msg;
  // Fewer members allowed than the frame has: the groups alone.
  ModelEffectOptions few;
  few.max_members = 3;
  EXPECT_EQ(CreateModelEffects("stiffness_loss", s, few).size(), s.elements.size());
}

TEST(EffectPriors, RegionsThatNameNoPlaceOfTheFamilyAreRefused) {
  const Structure s = BuildSpringMassChain(Chain());
  std::string where;
  std::string msg = ErrorOf(
      [&] {
        KeepStatedRegions(CreateModelEffects("attached_mass", s), s,
                          Prior("attached_mass", {}, {"x2", "n99"}));
      },
      &where);
  EXPECT_EQ(where, "regions[2]");
  EXPECT_TRUE(Has(msg, "'n99' names no element")) << msg;
  msg = ErrorOf(
      [&] {
        KeepStatedRegions(CreateModelEffects("stiffness_loss", s), s,
                          Prior("stiffness_loss", {}, {"x2"}));
      },
      &where);
  EXPECT_EQ(where, "regions[1]");
  EXPECT_TRUE(Has(msg, "names a node")) << msg;
  msg = ErrorOf(
      [&] {
        KeepStatedRegions(CreateModelEffects("attached_mass", s), s,
                          Prior("attached_mass", {}, {"2"}));
      },
      &where);
  EXPECT_TRUE(Has(msg, "names an element")) << msg;
  msg = ErrorOf(
      [&] {
        KeepStatedRegions(CreateModelEffects("material_scaling", s), s,
                          Prior("material_scaling", {}, {"2"}));
      },
      &where);
  EXPECT_EQ(where, "regions");
  EXPECT_TRUE(Has(msg, "one place")) << msg;
}

TEST(EffectPriors, StatedInstancesCarryTheRangesAndStartInsideThem) {
  const Structure s = BuildSpringMassChain(Chain());
  auto made = CreateModelEffects("stiffness_loss", s);
  const auto stated = WithFamilyPrior(
      std::move(made.front()), Prior("stiffness_loss", {Range("loss", 0.05, 0.6)}));
  const EffectParameter p = stated->Parameters()[0];
  EXPECT_NEAR(p.lower, std::log(0.05), 1e-12);
  EXPECT_NEAR(p.upper, std::log(0.6), 1e-12);
  const auto starts = stated->Starts();
  ASSERT_EQ(starts.size(), 3u);  // ln 0.03 clipped to ln 0.05, ln 0.3, the middle
  EXPECT_NEAR(starts[0][0], std::log(0.05), 1e-12);
  EXPECT_NEAR(starts[1][0], std::log(0.3), 1e-12);
  EXPECT_NEAR(starts[2][0], 0.5 * (std::log(0.05) + std::log(0.6)), 1e-12);
  EXPECT_EQ(stated->kind(), "stiffness_loss");
  EXPECT_EQ(stated->region().name, "element 1");
  // The cantilever's effects the same way: a point mass between 1.4 and 1.9 m.
  CantileverSpec beam;
  beam.node_heights = UniformHeights(2.0, 10);
  beam.section = {210e9, 9e-4, 1.6875e-8, 7850};
  const auto mass =
      WithFamilyPrior(CreateEffect("attached_mass"),
                      Prior("attached_mass", {Range("x_m", 1.4, 1.9)}), beam);
  EXPECT_DOUBLE_EQ(mass->Parameters(beam)[1].lower, 1.4);
  EXPECT_DOUBLE_EQ(mass->Parameters(beam)[1].upper, 1.9);
  for (const Eigen::VectorXd& start : mass->Starts(beam)) {
    EXPECT_GE(start[1], 1.4);
    EXPECT_LE(start[1], 1.9);
  }
  EXPECT_THROW(WithFamilyPrior(CreateEffect("attached_mass"),
                               Prior("attached_mass", {Range("x_m", 1.4, 2.5)}), beam),
               InputError);
}

// The normal prior's residual and its Jacobian, against differences; the data's
// residuals and Jacobian untouched before it.
TEST(EffectPriors, NormalPriorResidualsAreAppendedWithTheirDerivative) {
  std::vector<EffectParameter> params = {
      LogQuantity({"ln_m", "", -5, 5, false}, "mass_kg", 20.0),
      LinearQuantity({"level", "", 0, 3, true}, "level_m", 1.0, 0.0, 3.0)};
  NonlinearProblem data;
  data.num_residuals = 2;
  data.initial = Eigen::Vector2d(0.1, 1.0);
  data.evaluate = [](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* j,
                     std::string*) {
    *r = Eigen::Vector2d(x[0] * x[1] - 1, x[0] - 2);
    if (j) {
      j->resize(2, 2);
      *j << x[1], x[0], 1, 0;
    }
    return true;
  };
  EXPECT_EQ(WithPriorResiduals(data, params).num_residuals, 2);  // no normal prior
  params[0].normal_mean = 30;
  params[0].normal_sigma = 4;
  params[1].normal_mean = 1.2;
  params[1].normal_sigma = 0.3;
  const NonlinearProblem p = WithPriorResiduals(data, params);
  ASSERT_EQ(p.num_residuals, 4);
  const Eigen::Vector2d x(0.3, 1.5);
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  ASSERT_TRUE(p.evaluate(x, &r, &j, nullptr));
  EXPECT_DOUBLE_EQ(r[0], 0.3 * 1.5 - 1);
  EXPECT_NEAR(r[2], (20 * std::exp(0.3) - 30) / 4, 1e-12);
  EXPECT_NEAR(r[3], (1.5 - 1.2) / 0.3, 1e-12);
  for (int c = 0; c < 2; ++c) {
    const double h = 1e-6;
    Eigen::VectorXd xp = x, xm = x, rp, rm;
    xp[c] += h;
    xm[c] -= h;
    p.evaluate(xp, &rp, nullptr, nullptr);
    p.evaluate(xm, &rm, nullptr, nullptr);
    EXPECT_LT(((rp - rm) / (2 * h) - j.col(c)).cwiseAbs().maxCoeff(), 1e-7) << c;
  }
  // Linearised in the coordinate: the same residual and the same slope.
  Eigen::VectorXd mean, sigma;
  LocalNormalPriors(params, x, &mean, &sigma);
  ASSERT_EQ(sigma.size(), 2);
  for (int c = 0; c < 2; ++c) {
    EXPECT_NEAR((x[c] - mean[c]) / sigma[c], r[2 + c], 1e-12);
    EXPECT_NEAR(1 / sigma[c], j(2 + c, c), 1e-12);
  }
  params[1].normal_sigma = 0;  // uniform again: sigma 0 there
  LocalNormalPriors(params, x, &mean, &sigma);
  EXPECT_EQ(sigma[1], 0.0);
}

// The three levels: none, one effect, two effects, a third each (a half each
// on none and one effect without pairs), equal within a level, times the
// stated weights; the classes' priors add up to 1 when the weights are 1.
TEST(EffectPriors, LevelPriorSplitsNoneSinglesAndPairs) {
  const StatedPriors flat;
  const std::vector<std::string> a = {"added_mass"},
                                 ab = {"added_mass", "material_scaling"};
  EXPECT_DOUBLE_EQ(LevelPrior(flat, {}, 4, 6), 1.0 / 3);
  EXPECT_DOUBLE_EQ(LevelPrior(flat, a, 4, 6), 1.0 / 12);
  EXPECT_DOUBLE_EQ(LevelPrior(flat, ab, 4, 6), 1.0 / 18);
  EXPECT_DOUBLE_EQ(LevelPrior(flat, {}, 4, 6) + 4 * LevelPrior(flat, a, 4, 6) +
                       6 * LevelPrior(flat, ab, 4, 6),
                   1.0);
  EXPECT_DOUBLE_EQ(LevelPrior(flat, {}, 4, 0), 0.5);
  EXPECT_DOUBLE_EQ(LevelPrior(flat, a, 4, 0), 1.0 / 8);
  StatedPriors weighted;
  weighted.weights = {{"none", 3.0}, {"added_mass", 2.0}, {"material_scaling", 0.5}};
  EXPECT_DOUBLE_EQ(LevelPrior(weighted, {}, 4, 6), 1.0);
  EXPECT_DOUBLE_EQ(LevelPrior(weighted, a, 4, 6), 2.0 / 12);
  EXPECT_DOUBLE_EQ(LevelPrior(weighted, ab, 4, 6), 1.0 / 18);
}

}  // namespace
}  // namespace femup
