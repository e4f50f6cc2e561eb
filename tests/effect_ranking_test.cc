// Ranking unmodelled effects on a structure that is not a cantilever: a
// six-storey shear building whose "measured" modes come from a chain built
// directly with the change (the builder, not the effect's code), with noise
// drawn at the stated level from a fixed seed.
#include "femup/studies/effect_ranking.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/form_variant.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/fe/space_frame.h"
#include "femup/core/linalg/modal.h"
#include "femup/problems/model_effect_pair.h"
#include "femup/problems/model_effects.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/structure_diagnosis.h"
#include "prior_builders.h"
#include "scratch_dir.h"
#include "structure_specs.h"

namespace femup {
namespace {

ChainSpec ShearBuilding() { return fixtures::UniformChain(6, 1e5, 2e8); }

// The lowest four modes with shapes at every floor, noise 0.2 % on frequencies
// and 2 % of the largest entry on shapes.
ModalData Measured(const SparseMatrix& stiffness, const SparseMatrix& mass,
                   unsigned seed) {
  const Modes modes = SolveModes(stiffness, mass);
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  ModalData d;
  d.state = "air";
  d.frequencies_hz = modes.FrequenciesHz().head(4);
  for (int j = 0; j < 4; ++j) d.frequencies_hz[j] *= 1 + 0.002 * normal(rng);
  d.shapes = modes.shapes.leftCols(4);
  for (int j = 0; j < 4; ++j) {
    const double peak = d.shapes.col(j).cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < d.shapes.rows(); ++i)
      d.shapes(i, j) += 0.02 * peak * normal(rng);
  }
  return d;
}
ModalData Measured(const ChainSpec& truth, unsigned seed) {
  const Structure s = BuildSpringMassChain(truth);
  return Measured(s.stiffness, s.mass, seed);
}

EffectRankingOptions Options() {
  EffectRankingOptions o;
  o.frequency_sigma = 0.002;
  o.shape_sigma = 0.02;
  return o;
}

// KindProbability reads a kind's share from kind_probabilities (0 for a kind
// not ranked); RmsFrequencyError is the rms of model / measured - 1 over a
// class's paired modes, NaN without any.
TEST(EffectRanking, KindProbabilityAndRmsFrequencyErrorOfAClass) {
  EffectRanking r;
  r.kind_probabilities = {{"stiffness_loss", 0.7}, {"none", 0.2}, {"attached_mass", 0.1}};
  EXPECT_EQ(KindProbability(r, "none"), 0.2);
  EXPECT_EQ(KindProbability(r, "attached_mass"), 0.1);
  EXPECT_EQ(KindProbability(r, "axial_load"), 0.0);
  RankedClass c;
  EXPECT_TRUE(std::isnan(RmsFrequencyError(c)));
  PairedModeMisfit a, b;
  a.measured_hz = 10;
  a.model_hz = 10.3;  // +3 %
  b.measured_hz = 20;
  b.model_hz = 19.2;  // -4 %
  c.modes = {a, b};
  EXPECT_NEAR(RmsFrequencyError(c), std::sqrt((0.03 * 0.03 + 0.04 * 0.04) / 2), 1e-15);
}

TEST(EffectRanking, NamesTheDamagedStorey) {
  ChainSpec truth = ShearBuilding();
  truth.springs[2] *= 0.8;
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  const EffectRanking r = RankModelEffects(nominal, {Measured(truth, 7)}, Options());
  ASSERT_FALSE(r.classes.empty());
  EXPECT_EQ(r.classes[0].kind, "stiffness_loss");
  EXPECT_EQ(r.classes[0].region, "element 3");
  EXPECT_GT(r.classes[0].probability, 0.9);
  EXPECT_NEAR(r.classes[0].magnitudes[0].value, 0.2, 0.03);
  EXPECT_EQ(r.kind_probabilities[0].first, "stiffness_loss");
  double total = 0;
  for (const RankedClass& c : r.classes) total += c.probability;
  EXPECT_NEAR(total, 1.0, 1e-12);
  // A dry chain: added mass does not apply, and the result says why.
  ASSERT_EQ(r.skipped.size(), 1u);
  EXPECT_NE(r.skipped[0].find("added_mass"), std::string::npos);
  // Mode by mode: none predicts the nominal chain's frequencies, the verdict
  // the truth's (its storey's loss fitted: within the 0.2 % noise), both with
  // shapes that match (MAC at every floor).
  const Modes nominal_modes = SolveModes(nominal.stiffness, nominal.mass);
  const Structure damaged = BuildSpringMassChain(truth);
  const Modes truth_modes = SolveModes(damaged.stiffness, damaged.mass);
  const auto none = std::find_if(r.classes.begin(), r.classes.end(),
                                 [](const RankedClass& c) { return c.kind == "none"; });
  ASSERT_NE(none, r.classes.end());
  ASSERT_EQ(none->modes.size(), 4u);
  ASSERT_EQ(r.classes[0].modes.size(), 4u);
  for (int j = 0; j < 4; ++j) {
    const PairedModeMisfit& a = none->modes[static_cast<std::size_t>(j)];
    const PairedModeMisfit& b = r.classes[0].modes[static_cast<std::size_t>(j)];
    EXPECT_EQ(a.mode, j);
    EXPECT_NEAR(a.model_hz / nominal_modes.FrequenciesHz()[j], 1.0, 1e-9) << j;
    EXPECT_NEAR(b.model_hz / truth_modes.FrequenciesHz()[j], 1.0, 0.006) << j;
    EXPECT_GT(b.mac, 0.99) << j;
  }
}

// Two damaged storeys (20 % and 25 % of their springs lost), with pairs: the
// two storeys named together (not the storey that fits best alone, the first,
// beside the next best), each loss within 0.03; without pairs one storey alone
// is named, with a misfit more than ten times the pair's.
// The gap is shown with the verdict, or where the verdict is none with the
// most probable class of another family; no other class, no gap class.
TEST(EffectRanking, ShowsTheGapWithTheVerdictOrTheMostProbableEffect) {
  auto ranked = [](std::vector<std::string> kinds) {
    EffectRanking r;
    for (const std::string& k : kinds) {
      RankedClass c;
      c.kind = k;
      r.classes.push_back(c);
    }
    return r;
  };
  const EffectRanking named = ranked({"attached_mass", "none", "stiffness_loss"});
  EXPECT_EQ(GapClass(named), &named.classes[0]);
  EXPECT_EQ(NoneClass(named), &named.classes[1]);
  const EffectRanking nothing = ranked({"none", "stiffness_loss", "attached_mass"});
  EXPECT_EQ(GapClass(nothing), &nothing.classes[1]);
  EXPECT_EQ(NoneClass(nothing), &nothing.classes[0]);
  const EffectRanking alone = ranked({"none"});
  EXPECT_EQ(GapClass(alone), nullptr);
  EXPECT_EQ(NoneClass(alone), &alone.classes[0]);
  const EffectRanking no_none = ranked({"material_scaling"});
  EXPECT_EQ(GapClass(no_none), &no_none.classes[0]);
  EXPECT_EQ(NoneClass(no_none), nullptr);
  EXPECT_EQ(GapClass(EffectRanking{}), nullptr);
}

TEST(EffectRanking, NamesTwoDamagedStoreysTogether) {
  ChainSpec truth = ShearBuilding();
  truth.springs[1] *= 0.8;
  truth.springs[4] *= 0.75;
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  EffectRankingOptions o = Options();
  o.kinds = {"stiffness_loss"};
  o.max_effects = 2;
  const std::vector<ModalData> data = {Measured(truth, 7)};
  const EffectRanking r = RankModelEffects(nominal, data, o);
  ASSERT_FALSE(r.classes.empty());
  const RankedClass& top = r.classes[0];
  EXPECT_EQ(top.kind, "stiffness_loss+stiffness_loss");
  EXPECT_TRUE(top.region == "element 2 + element 5" ||
              top.region == "element 5 + element 2")
      << top.region;
  EXPECT_GT(top.probability, 0.9);
  ASSERT_EQ(top.magnitudes.size(), 2u);
  const bool second_first = top.region.rfind("element 2", 0) == 0;
  EXPECT_NEAR(top.magnitudes[second_first ? 0 : 1].value, 0.2, 0.03);
  EXPECT_NEAR(top.magnitudes[second_first ? 1 : 0].value, 0.25, 0.03);
  double total = 0;
  for (const RankedClass& c : r.classes) total += c.probability;
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_EQ(FamilyPresence(r).front().first, "stiffness_loss");
  // The report names each family's presence where only one family's pairs
  // were tried too.
  StructureDiagnosisResult result;
  result.ranking = r;
  EXPECT_NE(StructureDiagnosisReport(result).find("each family, alone or in a pair: "),
            std::string::npos);

  // Pairs among the two places that fit best alone only (storeys 1 and 5):
  // the true pair is not fitted.
  o.pair_places = 2;
  const EffectRanking two_places = RankModelEffects(nominal, data, o);
  for (const RankedClass& c : two_places.classes) {
    if (c.kind == "stiffness_loss+stiffness_loss") {
      EXPECT_EQ(c.region, "element 1 + element 5");
    }
  }

  o.max_effects = 1;
  const EffectRanking single = RankModelEffects(nominal, data, o);
  EXPECT_EQ(single.classes[0].kind, "stiffness_loss");
  EXPECT_GT(single.classes[0].chi2, 10 * top.chi2);
}

// A model whose frequencies are off by a form error (the higher the mode, the
// more: 1 % per mode above the first, as an idealised model's often are) while
// its shapes are right: the frequencies' noise is scaled (a temperature of
// their own) and the shapes', which fit, is not, so the shapes still point to
// the damaged storey rather than to an effect that absorbs the form error.
// The instances are fitted in parallel (options.threads); the ranking is the
// same bits on one thread and on three.
TEST(EffectRanking, DoesNotDependOnTheThreadCount) {
  ChainSpec truth = ShearBuilding();
  truth.springs[2] *= 0.8;
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  EffectRankingOptions one = Options(), three = Options();
  one.threads = 1;
  three.threads = 3;
  const EffectRanking a = RankModelEffects(nominal, {Measured(truth, 7)}, one);
  const EffectRanking b = RankModelEffects(nominal, {Measured(truth, 7)}, three);
  ASSERT_EQ(a.classes.size(), b.classes.size());
  ASSERT_GT(a.classes.size(), 5u);
  for (std::size_t i = 0; i < a.classes.size(); ++i) {
    EXPECT_EQ(a.classes[i].kind, b.classes[i].kind) << i;
    EXPECT_EQ(a.classes[i].region, b.classes[i].region) << i;
    EXPECT_EQ(a.classes[i].chi2, b.classes[i].chi2) << i;
    EXPECT_EQ(a.classes[i].probability, b.classes[i].probability) << i;
    EXPECT_EQ(a.classes[i].theta, b.classes[i].theta) << i;
  }
  EffectRankingOptions bad = Options();
  bad.threads = -1;
  EXPECT_NE(bad.Validate().ToString().find("threads"), std::string::npos);
}

TEST(EffectRanking, FormErrorInFrequenciesIsTemperedApartFromTheShapes) {
  ChainSpec truth = ShearBuilding();
  truth.springs[2] *= 0.8;
  ModalData d = Measured(truth, 7);
  for (int j = 0; j < d.num_modes(); ++j) d.frequencies_hz[j] *= 1 + 0.01 * j;
  const EffectRanking r =
      RankModelEffects(BuildSpringMassChain(ShearBuilding()), {d}, Options());
  EXPECT_GT(r.temperature, 10.0);
  // The shapes' misfit stays near their noise (the fit's compromise with the
  // frequencies shows in them a little).
  EXPECT_LT(r.shape_temperature, 3.0);
  EXPECT_EQ(r.classes[0].kind, "stiffness_loss");
  EXPECT_EQ(r.classes[0].region, "element 3");
}

// With a marginal frequency temperature, a class's evidence is its likelihood
// integrated over T = 1 + d^2 (d: each mode's discrepancy in noise units),
// half the prior at T = 1 and half uniform in log T up to 1e4. For `none`
// (no parameter, no Occam factor) on frequencies alone that is
//   log(1/2 e^(-chi2/2) + 1/2 int_0^U T^(-n/2) e^(-chi2/(2T)) du / U),
// u = log T, U = log 1e4: checked here by Simpson's rule on 20,000 intervals
// against the ranking's 41-point grid.
TEST(EffectRanking, AMarginalTemperatureIntegratesNonesEvidenceOverT) {
  ModalData d = Measured(ShearBuilding(), 3);
  const double offsets[4] = {0.012, -0.010, 0.008, -0.012};  // 4-6 noise units
  for (int j = 0; j < 4; ++j) d.frequencies_hz[j] *= 1 + offsets[j];
  EffectRankingOptions o = Options();
  o.use_shapes = false;
  o.frequency_temperature = EffectRankingOptions::FrequencyTemperature::kMarginal;
  const EffectRanking r = RankModelEffects(BuildSpringMassChain(ShearBuilding()), {d}, o);
  const auto none = std::find_if(r.classes.begin(), r.classes.end(),
                                 [](const RankedClass& c) { return c.kind == "none"; });
  ASSERT_NE(none, r.classes.end());
  const double chi2 = none->chi2, n = 4, span = std::log(1e4);
  ASSERT_GT(chi2, 50.0);  // far beyond the noise: the integral is what decides
  const int intervals = 20000;
  double integral = 0;
  for (int k = 0; k <= intervals; ++k) {
    const double u = span * k / intervals, t = std::exp(u);
    const double w = (k == 0 || k == intervals) ? 1 : (k % 2 == 1 ? 4 : 2);
    integral += w * std::exp(-0.5 * n * u - 0.5 * chi2 / t);
  }
  integral *= span / intervals / 3 / span;
  const double expected = std::log(0.5 * std::exp(-0.5 * chi2) + 0.5 * integral);
  EXPECT_NEAR(none->evidence.log_evidence, expected, 1e-3);
  // The frequencies' misfit is uneven, mode by mode, as a form error of no
  // particular shape makes it: no family is named for it.
  EXPECT_EQ(r.classes[0].kind, "none");
  EXPECT_GT(none->frequency_temperature, 5.0);
}

// A marginal temperature still names real effects: a storey at 80 % with
// shapes (the frequencies then fitted at T near 1), and leaves data that fit
// the model within the noise at T near 1.
TEST(EffectRanking, AMarginalTemperatureStillNamesTheDamagedStorey) {
  EffectRankingOptions o = Options();
  o.frequency_temperature = EffectRankingOptions::FrequencyTemperature::kMarginal;
  ChainSpec truth = ShearBuilding();
  truth.springs[2] *= 0.8;
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  const EffectRanking r = RankModelEffects(nominal, {Measured(truth, 7)}, o);
  EXPECT_EQ(r.classes[0].kind, "stiffness_loss");
  EXPECT_EQ(r.classes[0].region, "element 3");
  EXPECT_GT(r.classes[0].probability, 0.9);
  EXPECT_LT(r.classes[0].frequency_temperature, 2.0);
  const EffectRanking quiet =
      RankModelEffects(nominal, {Measured(ShearBuilding(), 3)}, o);
  EXPECT_EQ(quiet.classes[0].kind, "none");
  EXPECT_LT(quiet.classes[0].frequency_temperature, 2.0);
}

// A model stiffer than its structure by 1.5 % overall (every frequency about
// 0.75 % high: 3.7 noise units) is named a material scaling when nothing is
// stated, and `none` when the user states its overall stiffness is known to
// 2 % (the uniform change is then the model's own form error). A real E error
// of 10 % (5 % on every frequency, 2.5 times the stated uncertainty's 2 %
// on lambda) is still named, and a damaged storey, which changes the modes
// unevenly, still at its storey.
TEST(EffectRanking, AllowsForAStatedUncertaintyOfTheModelsStiffness) {
  ChainSpec truth = ShearBuilding();
  for (double& k : truth.springs) k *= 0.985;
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  const ModalData d = Measured(truth, 7);
  EffectRankingOptions stated = Options();
  stated.stiffness_uncertainty = 0.02;
  const EffectRanking plain = RankModelEffects(nominal, {d}, Options());
  EXPECT_EQ(plain.classes[0].kind, "material_scaling");
  const EffectRanking allowed = RankModelEffects(nominal, {d}, stated);
  EXPECT_EQ(allowed.classes[0].kind, "none");
  EXPECT_GT(allowed.classes[0].probability, 0.5);
  ASSERT_EQ(allowed.form_errors.size(), 1u);
  EXPECT_NE(allowed.form_errors[0].name.find("overall stiffness (2 %)"),
            std::string::npos);
  // Relative to the measured frequencies, 0.75 % and noise away from the model's.
  EXPECT_NEAR(allowed.form_errors[0].max_frequency_change, 0.01, 3e-4);

  ChainSpec softer = ShearBuilding();
  for (double& k : softer.springs) k *= 0.9;
  const EffectRanking e = RankModelEffects(nominal, {Measured(softer, 7)}, stated);
  EXPECT_EQ(e.classes[0].kind, "material_scaling");
  EXPECT_GT(e.classes[0].probability, 0.9);

  ChainSpec damaged = ShearBuilding();
  damaged.springs[2] *= 0.8;
  const EffectRanking s = RankModelEffects(nominal, {Measured(damaged, 7)}, stated);
  EXPECT_EQ(s.classes[0].kind, "stiffness_loss");
  EXPECT_EQ(s.classes[0].region, "element 3");

  EffectRankingOptions bad = Options();
  bad.stiffness_uncertainty = -0.01;
  EXPECT_NE(bad.Validate().ToString().find("stiffness_uncertainty"), std::string::npos);
  bad = Options();
  bad.mass_uncertainty = 0.5;
  EXPECT_NE(bad.Validate().ToString().find("mass_uncertainty"), std::string::npos);
}

TEST(EffectRanking, NamesAnAttachedMassOnTheRoof) {
  ChainSpec truth = ShearBuilding();
  truth.masses[5] += 1.5e4;  // 15 % of a floor on the roof
  const EffectRanking r = RankModelEffects(BuildSpringMassChain(ShearBuilding()),
                                           {Measured(truth, 11)}, Options());
  EXPECT_EQ(r.classes[0].kind, "attached_mass");
  EXPECT_EQ(r.classes[0].region, "node x6");
  EXPECT_NEAR(r.classes[0].magnitudes[0].value, 1.5e4, 0.2e4);
}

// A two-storey portal frame of steel sections (HE-like columns).
PlaneFrameSpec TwoStoreyPortal() {
  PlaneFrameSpec spec = fixtures::PlaneFrame(2, 1, 2, 3.5, 6.0);
  spec.column = {210e9, 7.8e-3, 8.4e-5, 7850};
  spec.beam = {210e9, 5.4e-3, 1.9e-4, 5.6e5};
  return spec;
}

// The lowest four modes of `truth` measured as a test would (sway at the
// joints and the beams' middles), noise 0.2 % / 2 % from `seed`. With `model`
// (a coarser mesh of the same frame) the sensors are at the model's DOFs of
// those labels, read on the truth at the same places (MatchDofs).
ModalData PortalMeasured(const Structure& truth, unsigned seed,
                         const Structure* model = nullptr) {
  const Modes modes = SolveModes(truth.stiffness, truth.mass);
  const Structure& named = model != nullptr ? *model : truth;
  std::vector<int> sensors, read;
  const std::vector<int> at_truth =
      model != nullptr ? MatchDofs(*model, truth) : std::vector<int>{};
  for (const char* label : {"n1:ux", "n2:ux", "n3:ux", "n4:ux", "n7:uy", "n10:uy"}) {
    const auto at = std::find(named.dof_labels.begin(), named.dof_labels.end(), label);
    EXPECT_NE(at, named.dof_labels.end()) << label;
    sensors.push_back(static_cast<int>(at - named.dof_labels.begin()));
    read.push_back(model != nullptr ? at_truth[static_cast<std::size_t>(sensors.back())]
                                    : sensors.back());
  }
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  ModalData d;
  d.state = "air";
  d.sensor_dofs = sensors;
  d.frequencies_hz = modes.FrequenciesHz().head(4);
  d.shapes.resize(sensors.size(), 4);
  for (int j = 0; j < 4; ++j) {
    d.frequencies_hz[j] *= 1 + 0.002 * normal(rng);
    for (std::size_t i = 0; i < sensors.size(); ++i)
      d.shapes(i, j) = modes.shapes(read[i], j);
    const double peak = d.shapes.col(j).cwiseAbs().maxCoeff();
    for (std::size_t i = 0; i < sensors.size(); ++i)
      d.shapes(i, j) += 0.02 * peak * normal(rng);
  }
  return d;
}

// An attached mass with a rotary inertia nests the point mass (its radius of
// gyration at the lower bound): the fit with the radius free ends no worse than
// the point mass's at each place that explains the data, since one of its
// starts holds the radius there (EffectParameter::nested_at_lower; without it
// the true place's fit ended at chi2 5.9e7 against 14.5). The truth: a 5 t
// point mass at a beam's middle (n7) of a portal.
TEST(EffectRanking, AMassWithRotaryInertiaFitsNoWorseThanThePointMass) {
  const Structure nominal = BuildPlaneFrameStructure(TwoStoreyPortal());
  Structure truth = nominal;
  std::vector<Eigen::Triplet<double>> t;
  for (const char* label : {"n7:ux", "n7:uy"}) {
    const auto at = std::find(truth.dof_labels.begin(), truth.dof_labels.end(), label);
    ASSERT_NE(at, truth.dof_labels.end()) << label;
    const int d = static_cast<int>(at - truth.dof_labels.begin());
    t.emplace_back(d, d, 5e3);
  }
  SparseMatrix point(truth.mass.rows(), truth.mass.cols());
  point.setFromTriplets(t.begin(), t.end());
  truth.mass += point;
  const ModalData d = PortalMeasured(truth, 7);
  EffectRankingOptions options = Options();
  options.kinds = {"attached_mass"};
  options.form_step = false;  // chi2: the fits' own (no step on the form error)
  options.rotary_inertia = false;
  const EffectRanking point_mass = RankModelEffects(nominal, {d}, options);
  options.rotary_inertia = true;
  const EffectRanking rotary = RankModelEffects(nominal, {d}, options);
  int compared = 0;
  for (const RankedClass& c : rotary.classes) {
    if (c.kind != "attached_mass") continue;
    for (const RankedClass& p : point_mass.classes) {
      // The places that explain the data (28 residuals); far from them the
      // misfit jumps where the modes' pairing changes and a fit's end
      // depends on its path.
      if (p.kind != c.kind || p.region != c.region || p.chi2 > 100) continue;
      EXPECT_LE(c.chi2, p.chi2 * (1 + 1e-3) + 0.1) << c.region;
      ++compared;
    }
  }
  EXPECT_GE(compared, 2);
  EXPECT_EQ(rotary.classes[0].region, "node n7");
}

// A pair of one family's places takes its share of the prior split among the
// pairs that family can form: every two of its places that lie apart. On a
// portal, stiffness loss acts on members and on their parts, which overlap
// and never pair, so the count (by brute force here) is below n (n - 1) / 2.
TEST(EffectRanking, SplitsAOneFamilyPairsPriorAmongThePlacesThatLieApart) {
  const Structure portal = BuildPlaneFrameStructure(TwoStoreyPortal());
  const auto instances = CreateModelEffects("stiffness_loss", portal);
  const auto n = static_cast<double>(instances.size());
  double apart = 0;
  for (std::size_t i = 0; i < instances.size(); ++i)
    for (std::size_t j = i + 1; j < instances.size(); ++j)
      if (!RegionsOverlap(instances[i]->region(), instances[j]->region())) apart += 1;
  ASSERT_GT(apart, 0);
  EXPECT_LT(apart, n * (n - 1) / 2);

  const Modes modes = SolveModes(portal.stiffness, portal.mass);
  ModalData d;
  d.state = "air";
  d.frequencies_hz = modes.FrequenciesHz().head(3);
  EffectRankingOptions o = Options();
  o.kinds = {"stiffness_loss"};
  o.max_effects = 2;
  o.pair_places = 2;
  o.bagging_copies = 0;
  const EffectRanking r = RankModelEffects(portal, {d}, o);
  int pairs = 0, singles = 0;
  for (const RankedClass& c : r.classes) {
    if (c.kind == "stiffness_loss+stiffness_loss") {
      ++pairs;
      EXPECT_NEAR(c.log_prior, std::log(1.0 / 3) - std::log(apart), 1e-12) << c.region;
    } else if (c.kind == "stiffness_loss") {
      ++singles;
      EXPECT_NEAR(c.log_prior, std::log(1.0 / 3) - std::log(n), 1e-12) << c.region;
    }
  }
  EXPECT_EQ(singles, static_cast<int>(n));
  EXPECT_GE(pairs, 1);
}

// A portal frame on base rotation springs (the foundation as the engineer
// estimated it) whose real foundation is four times softer: the truth is built
// by the builder with the softer springs.
// The same portal modelled as clamped, standing on a foundation that is not
// rigid (base rotation springs of a column's own 4 E I / h, on the builder's
// base DOFs, which the model does not have): support flexibility, released
// at the model's rigid supports, is named, and its rotation springs are of the
// truth's size.
TEST(EffectRanking, NamesAFoundationTheModelTakesAsRigid) {
  PlaneFrameSpec spec = TwoStoreyPortal();
  const Structure nominal = BuildPlaneFrameStructure(spec);
  ASSERT_EQ(nominal.rigid_supports.size(), 2u);
  const double column_rotation = 4 * 210e9 * 8.4e-5 / 3.5;  // 4 E I / h
  spec.base.rotation = column_rotation;
  const ModalData d = PortalMeasured(BuildPlaneFrameStructure(spec), 5, &nominal);
  const EffectRanking r = RankModelEffects(nominal, {d}, Options());
  ASSERT_FALSE(r.classes.empty());
  EXPECT_EQ(r.classes[0].kind, "support_flexibility");
  EXPECT_EQ(r.classes[0].region, "supports");
  EXPECT_GT(r.classes[0].probability, 0.9);
  const std::vector<EffectMagnitude>& m = r.classes[0].magnitudes;
  // The translations' and the rotations' compliance ratios, then the ux, uy
  // and rz springs.
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[0].name, "translation_compliance_ratio");
  EXPECT_EQ(m[1].name, "rotation_compliance_ratio");
  EXPECT_EQ(m[4].name, "base spring rz (mean of 2 supports)");
  EXPECT_EQ(m[4].unit, "N m/rad");
  // The rotation springs are the truth's; the foundation holds sideways, so
  // the translations stay nearly rigid (a horizontal spring far stiffer than
  // the column's end: a small ratio).
  EXPECT_NEAR(m[4].value / column_rotation, 1.0, 0.1) << m[1].value;
  EXPECT_LT(m[0].value, 0.05);
}

TEST(EffectRanking, NamesASofterFoundationOfAPortalFrame) {
  PlaneFrameSpec spec = TwoStoreyPortal();
  const double column_rotation = 4 * 210e9 * 8.4e-5 / 3.5;  // 4 E I / h
  spec.base.rotation = 2 * column_rotation;
  const Structure nominal = BuildPlaneFrameStructure(spec);
  spec.base.rotation /= 4;
  const ModalData d = PortalMeasured(BuildPlaneFrameStructure(spec), 5);
  const EffectRanking r = RankModelEffects(nominal, {d}, Options());
  ASSERT_FALSE(r.classes.empty());
  EXPECT_EQ(r.classes[0].kind, "support_flexibility");
  EXPECT_GT(r.classes[0].probability, 0.9);
  // k / (1 + c) = k / 4: an added compliance three times the spring's own.
  EXPECT_NEAR(r.classes[0].magnitudes[0].value, 3.0, 0.6);
}

// The Euler-Bernoulli model of a frame (two elements per member) whose
// members deform in shear (the truth: Timoshenko members of shear area 0.4 A,
// not the A / 2 of the model's form variant, on eight elements per member),
// with no effect added: without the form error allowed for, an E scaling is
// named for the frame's uniform softness; with it, no family is (the gap is
// the model's own formulation and mesh). A damaged column on the same truth
// is still found, and at its place.
TEST(EffectRanking, AllowsForTheModelsOwnShearDeformation) {
  const Structure model = BuildPlaneFrameStructure(TwoStoreyPortal());
  ASSERT_EQ(model.form_variants.size(), 2u);
  PlaneFrameSpec truth = TwoStoreyPortal();
  truth.elements_per_member = 8;
  truth.theory = BeamTheory::kTimoshenko;
  truth.column_shear_area = 0.4 * truth.column.A;
  truth.beam_shear_area = 0.4 * truth.beam.A;
  const ModalData d = PortalMeasured(BuildPlaneFrameStructure(truth), 3, &model);

  EffectRankingOptions without = Options();
  without.formulation_error = false;
  const EffectRanking blind = RankModelEffects(model, {d}, without);
  EXPECT_TRUE(blind.form_errors.empty());
  ASSERT_NE(blind.classes[0].kind, "none");
  EXPECT_GT(blind.classes[0].probability, 0.5);

  const EffectRanking r = RankModelEffects(model, {d}, Options());
  ASSERT_EQ(r.form_errors.size(), 2u);
  // With its form variants allowed for, the frame's frequencies are tempered by
  // the threshold rule (FrequencyTemperature::kAuto); without them, by the
  // marginal one.
  EXPECT_EQ(r.frequency_temperature,
            EffectRankingOptions::FrequencyTemperature::kThreshold);
  EXPECT_EQ(blind.frequency_temperature,
            EffectRankingOptions::FrequencyTemperature::kMarginal);
  EXPECT_NE(r.form_errors[1].name.find("finer mesh"), std::string::npos);
  EXPECT_NE(r.form_errors[0].name.find("shear deformation"), std::string::npos);
  // Shear makes the four modes up to 6 % softer here (the stocky columns' higher
  // modes): many noise units.
  EXPECT_GT(r.form_errors[0].max_frequency_change, 0.005);
  EXPECT_LT(r.form_errors[0].max_frequency_change, 0.1);
  EXPECT_EQ(r.classes[0].kind, "none");
  EXPECT_GT(r.classes[0].probability, 0.5);

  // The first storey's left column at 60 % of its stiffness, on the same truth.
  Structure damaged = BuildPlaneFrameStructure(truth);
  damaged.stiffness -= 0.4 * damaged.elements[0].stiffness;
  ASSERT_EQ(damaged.elements[0].label, "s1:col1");
  const EffectRanking found =
      RankModelEffects(model, {PortalMeasured(damaged, 3, &model)}, Options());
  EXPECT_EQ(found.classes[0].kind, "stiffness_loss");
  EXPECT_NE(found.classes[0].region.find("s1:col1"), std::string::npos)
      << found.classes[0].region;
}

// A shear building (model.shear_building) measured on a building whose
// storeys also resist a change of drift, as the chain's two flexural variants
// say, each at its standard deviation: no effect, only the model's own form
// error, which moves the six floors' shapes as well as the frequencies
// (ModelFormError.AllowsForAShearBuildingsFlexureOnItsShapesToo). Allowed for on the
// frequencies alone, what it does to the shapes is named a stiffness loss of the top
// storey at P 0.95; on the shapes too, none is the verdict. A damaged storey on the same
// building is still named, more surely. (At one and a half standard deviations the
// damaged storey is named none either way: the frequency temperature rises to 50.)
TEST(EffectRanking, AllowsForAShearBuildingsFlexureOnItsShapes) {
  ChainSpec spec = ShearBuilding();
  spec.shear_building = true;
  const Structure model = BuildSpringMassChain(spec);
  ASSERT_EQ(model.form_variants.size(), 2u);
  SparseMatrix flexural = model.stiffness;
  for (const FormVariant& v : model.form_variants)
    flexural += v.stiffness - model.stiffness;
  const ModalData d = Measured(flexural, model.mass, 8);

  EffectRankingOptions on_frequencies = Options();
  on_frequencies.form_error_on_shapes = false;
  const EffectRankingOptions on_shapes = Options();
  EXPECT_TRUE(on_shapes.form_error_on_shapes);  // by default
  const EffectRanking f = RankModelEffects(model, {d}, on_frequencies);
  const EffectRanking s = RankModelEffects(model, {d}, on_shapes);
  ASSERT_EQ(f.form_errors.size(), 2u);
  ASSERT_EQ(s.form_errors.size(), 2u);
  // The report's sizes are the frequencies' either way.
  EXPECT_EQ(s.form_errors[0].noise_units, f.form_errors[0].noise_units);
  EXPECT_EQ(f.classes[0].kind, "stiffness_loss");
  EXPECT_LT(KindProbability(f, "none"), 0.1);
  EXPECT_EQ(s.classes[0].kind, "none");
  EXPECT_GT(KindProbability(s, "none"), 0.3);

  // Storey 3 at 75 % of its spring, on the same building.
  SparseMatrix damaged = flexural;
  damaged -= 0.25 * model.elements[2].stiffness;
  const ModalData dd = Measured(damaged, model.mass, 8);
  for (const EffectRankingOptions& o : {on_frequencies, on_shapes}) {
    const EffectRanking found = RankModelEffects(model, {dd}, o);
    EXPECT_EQ(found.classes[0].kind, "stiffness_loss");
    EXPECT_EQ(found.classes[0].region, "element 3");
    EXPECT_GT(found.classes[0].probability, 0.98);
  }
}

// With form_fit each fitted class is moved to the mode of the whitened misfit
// by a fit, not one Gauss-Newton step: on the portal whose only gap is its own
// shear deformation, with stiffness_loss alone tried, the step left the six
// fitted losses short of that mode (log evidence -17.2 to -58.3 when
// measured, session 47), the fit brings each to within 1.2 of "none"'s (-13.6,
// the same in both: it has no unknowns; the losses -14.0 to -14.8), and "none"
// stays first, at P 0.58 instead of 0.96 here (0.47 instead of 0.94 with every
// family tried: AllowsForTheModelsOwnShearDeformation with the switch on). Off
// by default until measured on the blind suites (docs/diagnosis.md).
TEST(EffectRanking, FormFitMovesEachFittedClassToTheWhitenedMode) {
  PlaneFrameSpec truth = TwoStoreyPortal();
  truth.elements_per_member = 8;
  truth.theory = BeamTheory::kTimoshenko;
  truth.column_shear_area = 0.4 * truth.column.A;
  truth.beam_shear_area = 0.4 * truth.beam.A;
  const Structure model = BuildPlaneFrameStructure(TwoStoreyPortal());
  const ModalData d = PortalMeasured(BuildPlaneFrameStructure(truth), 3, &model);
  EffectRankingOptions options = Options();
  options.kinds = {"stiffness_loss"};
  EXPECT_FALSE(options.form_fit);  // off unless asked
  const EffectRanking step = RankModelEffects(model, {d}, options);
  options.form_fit = true;
  const EffectRanking fit = RankModelEffects(model, {d}, options);
  ASSERT_FALSE(fit.classes.empty());
  EXPECT_EQ(fit.classes[0].kind, "none");
  auto evidence = [](const EffectRanking& r, const std::string& region) {
    for (const RankedClass& c : r.classes)
      if (c.region == region) return c.evidence.log_evidence;
    return -std::numeric_limits<double>::infinity();
  };
  const double none = evidence(fit, "");
  EXPECT_NEAR(none, evidence(step, ""), 1e-9);
  int moved = 0;
  for (const RankedClass& c : fit.classes) {
    if (c.kind != "stiffness_loss" || !c.fitted) continue;
    const double before = evidence(step, c.region);
    EXPECT_GE(c.evidence.log_evidence, before - 0.1) << c.region;
    EXPECT_GT(c.evidence.log_evidence, none - 3) << c.region;
    moved += c.evidence.log_evidence > before + 1;
  }
  EXPECT_GE(moved, 3);
}

// A chain's ground spring softened in series and its first storey's loss are
// the same change: named equivalent, their probability stated together.
TEST(EffectRanking, NamesObservationallyEquivalentClasses) {
  ChainSpec truth = ShearBuilding();
  truth.springs[0] *= 0.8;
  EffectRankingOptions o = Options();
  o.kinds = {"support_flexibility", "stiffness_loss", "attached_mass"};
  const EffectRanking r =
      RankModelEffects(BuildSpringMassChain(ShearBuilding()), {Measured(truth, 5)}, o);
  const RankedClass& top = r.classes[0];
  ASSERT_TRUE(top.kind == "support_flexibility" || top.region == "element 1")
      << top.kind << " " << top.region;
  ASSERT_EQ(top.equivalent.size(), 1u);
  const std::string other = top.kind == "support_flexibility"
                                ? "stiffness_loss at element 1"
                                : "support_flexibility at supports";
  EXPECT_EQ(top.equivalent[0], other);
  EXPECT_NEAR(top.group_probability, r.classes[0].probability + r.classes[1].probability,
              1e-12);
  EXPECT_GT(top.group_probability, 0.99);
  // An attached mass is not equivalent to either.
  for (const RankedClass& c : r.classes) {
    if (c.kind == "attached_mass") {
      EXPECT_TRUE(c.equivalent.empty()) << c.region;
    }
  }
}

// A model brought as global matrices only (Matrix Market without elements):
// only the families that need no element matrices are tried.
TEST(EffectRanking, GlobalMatricesOnlyGetTheFamiliesThatNeedNoElements) {
  Structure s = BuildSpringMassChain(ShearBuilding());
  s.type = "matrix_market";
  s.elements.clear();
  s.supports.clear();
  ChainSpec truth = ShearBuilding();
  truth.masses[3] += 2e4;
  const EffectRanking r = RankModelEffects(s, {Measured(truth, 13)}, Options());
  EXPECT_EQ(r.classes[0].kind, "attached_mass");
  EXPECT_EQ(r.classes[0].region, "node x4");
  EXPECT_EQ(r.skipped.size(), 4u);  // the four that need elements or supports
}

TEST(EffectRanking, NoGapWhenTheNoiseExplainsTheData) {
  // A chain has no form variant: its temperature is marginal by default, the
  // verdict's a little above 1 (the prior's half above 1 keeps some weight).
  const EffectRanking r = RankModelEffects(BuildSpringMassChain(ShearBuilding()),
                                           {Measured(ShearBuilding(), 3)}, Options());
  EXPECT_EQ(r.kind_probabilities[0].first, "none");
  EXPECT_EQ(r.frequency_temperature,
            EffectRankingOptions::FrequencyTemperature::kMarginal);
  EXPECT_GE(r.temperature, 1.0);
  EXPECT_LT(r.temperature, 1.5);
  EffectRankingOptions threshold = Options();
  threshold.frequency_temperature =
      EffectRankingOptions::FrequencyTemperature::kThreshold;
  const EffectRanking t = RankModelEffects(BuildSpringMassChain(ShearBuilding()),
                                           {Measured(ShearBuilding(), 3)}, threshold);
  EXPECT_EQ(t.kind_probabilities[0].first, "none");
  EXPECT_DOUBLE_EQ(t.temperature, 1.0);
}

// A gap is named only at the stated confidence: with the gap's probability
// (1 - P(none)) below gap_confidence the verdict is "none" and comes first,
// every probability as it was; just below it, the family is named as with
// gap_confidence 0. The report says why none was named.
TEST(EffectRanking, NamesAGapOnlyAtTheGapConfidence) {
  EXPECT_EQ(EffectRankingOptions().gap_confidence, 0.0);  // by default: the most probable
  ChainSpec truth = ShearBuilding();
  truth.springs[2] *= 0.97;
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  EffectRankingOptions o = Options();
  o.kinds = {"stiffness_loss", "attached_mass"};
  o.gap_confidence = 0;
  const std::vector<ModalData> data = {Measured(truth, 7)};
  const EffectRanking named = RankModelEffects(nominal, data, o);
  ASSERT_FALSE(named.classes.empty());
  ASSERT_NE(named.classes[0].kind, "none");
  EXPECT_FALSE(named.gap_below_confidence);
  double p_none = -1;
  for (const RankedClass& c : named.classes)
    if (c.kind == "none") p_none = c.probability;
  ASSERT_GE(p_none, 0);
  EXPECT_NEAR(named.gap_probability, 1 - p_none, 1e-15);
  ASSERT_LT(named.gap_probability, 1.0);
  auto by_label = [](const EffectRanking& r) {
    std::map<std::string, double> p;
    for (const RankedClass& c : r.classes) p[c.kind + "@" + c.region] = c.probability;
    return p;
  };

  o.gap_confidence = 0.5 * (named.gap_probability + 1);
  const EffectRanking held = RankModelEffects(nominal, data, o);
  ASSERT_FALSE(held.classes.empty());
  EXPECT_EQ(held.classes[0].kind, "none");
  EXPECT_TRUE(held.gap_below_confidence);
  EXPECT_DOUBLE_EQ(held.gap_probability, named.gap_probability);
  EXPECT_EQ(by_label(held), by_label(named));
  EXPECT_EQ(held.kind_probabilities, named.kind_probabilities);
  // The other classes keep their order after none.
  for (std::size_t i = 1, j = 0; i < held.classes.size(); ++i, ++j) {
    if (named.classes[j].kind == "none") ++j;
    EXPECT_EQ(held.classes[i].kind + held.classes[i].region,
              named.classes[j].kind + named.classes[j].region);
  }
  StructureDiagnosisResult r;
  r.study_name = "s";
  r.model_type = "chain";
  r.gap_confidence = o.gap_confidence;
  r.ranking = held;
  EXPECT_NE(StructureDiagnosisReport(r).find(
                "verdict: no significant gap: a gap of any kind has P"),
            std::string::npos)
      << StructureDiagnosisReport(r);

  o.gap_confidence = 0.5 * named.gap_probability;
  const EffectRanking again = RankModelEffects(nominal, data, o);
  EXPECT_FALSE(again.gap_below_confidence);
  EXPECT_EQ(again.classes[0].kind + again.classes[0].region,
            named.classes[0].kind + named.classes[0].region);

  o.gap_confidence = 1;
  EXPECT_THROW(RankModelEffects(nominal, data, o), InputError);
}

// A gap no family explains is not named after the family that nibbles at it
// most: a chain whose storeys are alternately stiffer and softer than its model
// (a form error no single place, uniform scaling or support can make) is
// diagnosed "none", with the class that explained too little listed next and
// every probability as with gap_explained 0, which names it. A damaged storey
// is explained in full and still named. The report says why none was named.
TEST(EffectRanking, NamesNoEffectThatExplainsTooLittleOfTheGap) {
  EXPECT_EQ(EffectRankingOptions().gap_explained, 1.0 / 3);
  EXPECT_EQ(DiagnosisSpec().gap_explained, 1.0 / 3);
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  ChainSpec uneven = ShearBuilding();
  for (std::size_t i = 0; i < uneven.springs.size(); ++i)
    uneven.springs[i] *= i % 2 == 0 ? 1.1 : 0.9;
  const std::vector<ModalData> data = {Measured(uneven, 21)};
  EffectRankingOptions o = Options();
  const EffectRanking r = RankModelEffects(nominal, data, o);
  o.gap_explained = 0;
  const EffectRanking any = RankModelEffects(nominal, data, o);
  ASSERT_GE(any.classes.size(), 2u);
  ASSERT_EQ(any.classes[0].kind, "stiffness_loss");  // what gap_explained 0 names
  EXPECT_FALSE(any.gap_unexplained);
  EXPECT_GT(any.gap_probability, 0.5);
  EXPECT_LT(any.classes[0].explained, EffectRankingOptions().gap_explained);
  ASSERT_EQ(r.classes.size(), any.classes.size());
  EXPECT_EQ(r.classes[0].kind, "none");
  EXPECT_TRUE(r.gap_unexplained);
  EXPECT_EQ(r.classes[1].kind + r.classes[1].region,
            any.classes[0].kind + any.classes[0].region);
  EXPECT_EQ(r.kind_probabilities, any.kind_probabilities);
  EXPECT_DOUBLE_EQ(r.gap_probability, any.gap_probability);
  for (const RankedClass& c : r.classes) {
    EXPECT_GE(c.explained, 0.0);
    EXPECT_LE(c.explained, 1.0);
    if (c.kind == "none") {
      EXPECT_EQ(c.explained, 0.0);
      continue;
    }
    // The definition, from the class's chi2 and none's: 4 frequencies and 4
    // shapes of 6 entries, each shape scaled to fit.
    ASSERT_EQ(r.num_residuals, 28);
    const double gap = r.classes[0].chi2 - (28 - 4);
    const double left = c.chi2 - (28 - 4 - static_cast<double>(c.theta.size()));
    EXPECT_NEAR(c.explained, std::clamp(1 - std::max(0.0, left) / gap, 0.0, 1.0), 1e-12);
  }
  StructureDiagnosisResult report;
  report.study_name = "s";
  report.model_type = "chain";
  report.ranking = r;
  EXPECT_NE(
      StructureDiagnosisReport(report).find(
          "verdict: no effect explains the gap: the most probable, stiffness_loss at"),
      std::string::npos)
      << StructureDiagnosisReport(report);

  // A damaged storey: explained (to the noise) and named.
  ChainSpec damaged = ShearBuilding();
  damaged.springs[2] *= 0.8;
  const EffectRanking d = RankModelEffects(nominal, {Measured(damaged, 21)}, Options());
  EXPECT_EQ(d.classes[0].kind, "stiffness_loss");
  EXPECT_FALSE(d.gap_unexplained);
  EXPECT_GT(d.classes[0].explained, 0.95);

  o.gap_explained = 1;
  EXPECT_EQ(o.Validate().field, "gap_explained");
  o.gap_explained = -0.1;
  EXPECT_THROW(RankModelEffects(nominal, data, o), InputError);
}

// Without bagging the probabilities are the Laplace posterior's; with it both
// are reported, each summing to 1, and the same fits (chi2, evidence) serve
// both.
TEST(EffectRanking, BaggedAndLaplaceProbabilitiesFromTheSameFits) {
  ChainSpec truth = ShearBuilding();
  truth.springs[2] *= 0.8;
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  const std::vector<ModalData> data = {Measured(truth, 5)};
  EffectRankingOptions o = Options();
  o.bagging_copies = 0;
  const EffectRanking laplace = RankModelEffects(nominal, data, o);
  EXPECT_EQ(laplace.bagging_copies, 0);
  double sum = 0;
  for (const RankedClass& c : laplace.classes) {
    EXPECT_DOUBLE_EQ(c.probability, c.laplace_probability);
    sum += c.probability;
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
  o.bagging_copies = 400;
  const EffectRanking bagged = RankModelEffects(nominal, data, o);
  EXPECT_EQ(bagged.bagging_copies, 400);
  ASSERT_EQ(bagged.classes.size(), laplace.classes.size());
  // The damaged storey, supported by every mode: certain either way.
  EXPECT_EQ(bagged.classes[0].region, "element 3");
  EXPECT_GT(bagged.classes[0].probability, 0.99);
  double bagged_sum = 0;
  for (const RankedClass& c : bagged.classes) {
    bagged_sum += c.probability;
    for (const RankedClass& l : laplace.classes) {
      if (l.kind != c.kind || l.region != c.region) continue;
      EXPECT_DOUBLE_EQ(c.chi2, l.chi2);
      EXPECT_DOUBLE_EQ(c.evidence.log_evidence, l.evidence.log_evidence);
      EXPECT_DOUBLE_EQ(c.laplace_probability, l.laplace_probability);
    }
  }
  EXPECT_NEAR(bagged_sum, 1.0, 1e-12);
}

TEST(EffectRanking, RefusesBadOptionsAndFamiliesThatDoNotApply) {
  const Structure s = BuildSpringMassChain(ShearBuilding());
  const ModalData d = Measured(ShearBuilding(), 1);
  EffectRankingOptions o = Options();
  o.bagging_copies = -1;
  EXPECT_THROW(RankModelEffects(s, {d}, o), InputError);
  o = Options();
  o.frequency_sigma = 0;
  EXPECT_THROW(RankModelEffects(s, {d}, o), InputError);
  o = Options();
  o.solver = "magic";
  EXPECT_THROW(RankModelEffects(s, {d}, o), InputError);
  o = Options();
  o.kinds = {"added_mass"};  // nothing is wet
  try {
    RankModelEffects(s, {d}, o);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wet"), std::string::npos) << e.what();
  }
}

// Stated priors (effect_priors.h). On a chain the ground spring's flexibility
// and storey 1's loss are the same change; by default the support (one place
// against six storeys) takes most of their joint probability. Knowing the
// foundation stiff (at most 5 % more compliant than modelled) rules it out,
// and the verdict becomes storey 1's loss.
TEST(EffectRanking, AStatedRangeThatExcludesTheWrongExplanationChangesTheVerdict) {
  ChainSpec truth = ShearBuilding();
  truth.springs[0] *= 0.8;  // a loss of 0.2, or a compliance ratio of 0.25
  EffectRankingOptions o = Options();
  o.kinds = {"support_flexibility", "stiffness_loss", "attached_mass"};
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  const std::vector<ModalData> data = {Measured(truth, 5)};
  const EffectRanking by_default = RankModelEffects(nominal, data, o);
  ASSERT_EQ(by_default.classes[0].kind, "support_flexibility");
  o.priors.families = {fixtures::Prior(
      "support_flexibility", {fixtures::Range("compliance_ratio", 1e-3, 0.05)})};
  const EffectRanking stated = RankModelEffects(nominal, data, o);
  EXPECT_EQ(stated.classes[0].kind, "stiffness_loss");
  EXPECT_EQ(stated.classes[0].region, "element 1");
  EXPECT_GT(stated.classes[0].probability, 0.99);
  EXPECT_NEAR(stated.classes[0].magnitudes[0].value, 0.2, 0.03);
  // The support's fit stays inside the stated range (and fits far worse).
  for (const RankedClass& c : stated.classes) {
    if (c.kind != "support_flexibility") continue;
    EXPECT_LE(c.magnitudes[0].value, 0.05 * (1 + 1e-9));
    EXPECT_GT(c.chi2, stated.classes[0].chi2 + 100);
  }
}

// A normal prior centred on the truth: the estimate stays on it and its
// posterior standard deviation (in ln loss) shrinks to the combination of the
// data's and the prior's, 1 / sqrt(1 / s_data^2 + 1 / s_prior^2), s_prior =
// 0.01 / 0.2 in ln loss.
TEST(EffectRanking, ANormalPriorCentredOnTheTruthNarrowsTheFit) {
  ChainSpec truth = ShearBuilding();
  truth.springs[2] *= 0.8;
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  const std::vector<ModalData> data = {Measured(truth, 7)};
  EffectRankingOptions o = Options();
  o.kinds = {"stiffness_loss"};
  const EffectRanking plain = RankModelEffects(nominal, data, o);
  o.priors.families = {
      fixtures::Prior("stiffness_loss", {fixtures::Normal("loss", 0.2, 0.01)})};
  const EffectRanking stated = RankModelEffects(nominal, data, o);
  const RankedClass& a = plain.classes[0];
  const RankedClass& b = stated.classes[0];
  ASSERT_EQ(a.region, "element 3");
  ASSERT_EQ(b.region, "element 3");
  const double s_data = a.evidence.sigma[0], s_prior = 0.01 / 0.2;
  EXPECT_LT(b.evidence.sigma[0], s_data);
  EXPECT_NEAR(b.evidence.sigma[0],
              1 / std::sqrt(1 / (s_data * s_data) + 1 / (s_prior * s_prior)),
              0.05 * b.evidence.sigma[0]);
  EXPECT_LE(std::abs(b.magnitudes[0].value - 0.2), std::abs(a.magnitudes[0].value - 0.2));
  // The mode moves towards the mean; the data's chi2 cannot fall below the
  // data's own best.
  EXPECT_GE(b.chi2, a.chi2 - 1e-6);
}

// A weight multiplies a family's prior, so the posterior odds of two classes
// change by the ratio of their families' weights whatever their evidence; the
// log priors are the weights' shares (split among a family's instances).
TEST(EffectRanking, WeightsChangeThePosteriorOddsByTheirRatio) {
  ChainSpec truth = ShearBuilding();
  truth.springs[0] *= 0.8;
  EffectRankingOptions o = Options();
  o.kinds = {"support_flexibility", "stiffness_loss", "attached_mass"};
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  const std::vector<ModalData> data = {Measured(truth, 5)};
  auto find = [](const EffectRanking& r, const std::string& label) {
    for (const RankedClass& c : r.classes)
      if (c.kind + " at " + c.region == label || (c.kind == label && c.region.empty()))
        return c;
    ADD_FAILURE() << label;
    return RankedClass();
  };
  const EffectRanking plain = RankModelEffects(nominal, data, o);
  o.priors.weights = {{"none", 2}, {"stiffness_loss", 3}};
  const EffectRanking weighted = RankModelEffects(nominal, data, o);
  const std::string loss = "stiffness_loss at element 1";
  const std::string support = "support_flexibility at supports";
  // Exactly so for the Laplace posterior; the bagged one (the mean over
  // bootstrap copies of posteriors each changed so) moves the same way.
  const double odds_plain =
      find(plain, loss).laplace_probability / find(plain, support).laplace_probability;
  const double odds_weighted = find(weighted, loss).laplace_probability /
                               find(weighted, support).laplace_probability;
  EXPECT_NEAR(odds_weighted / odds_plain, 3.0, 1e-9);
  EXPECT_GT(find(weighted, loss).probability / find(weighted, support).probability,
            find(plain, loss).probability / find(plain, support).probability);
  // Same evidence with or without the weights.
  EXPECT_DOUBLE_EQ(find(weighted, loss).evidence.log_evidence,
                   find(plain, loss).evidence.log_evidence);
  // Shares: none 2, each family 1 but stiffness_loss 3: 2 / 7 for none, 3 / 7
  // split among six storeys.
  EXPECT_NEAR(find(weighted, "none").log_prior, std::log(2.0 / 7.0), 1e-12);
  EXPECT_NEAR(find(weighted, loss).log_prior, std::log(3.0 / 7.0 / 6.0), 1e-12);
  EXPECT_NEAR(find(plain, loss).log_prior, std::log(1.0 / 4.0 / 6.0), 1e-12);
}

TEST(EffectRanking, RefusesStatedPriorsThatDoNotFitTheFamilies) {
  const Structure s = BuildSpringMassChain(ShearBuilding());
  const ModalData d = Measured(ShearBuilding(), 1);
  auto where = [&](const EffectRankingOptions& o) {
    try {
      RankModelEffects(s, {d}, o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EffectRankingOptions o = Options();
  o.kinds = {"stiffness_loss"};
  FamilyPrior f;
  f.kind = "attached_mass";  // not tried
  f.regions = {"x2"};
  o.priors.families = {f};
  EXPECT_NE(
      where(o).find("diagnosis.priors.attached_mass: is not among the families tried"),
      std::string::npos)
      << where(o);
  f.kind = "stiffness_loss";
  f.regions = {"9"};
  o.priors.families = {f};
  EXPECT_NE(
      where(o).find("diagnosis.priors.stiffness_loss.regions[1]: '9' names no element"),
      std::string::npos)
      << where(o);
  f.regions.clear();
  f.quantities = {fixtures::Range("loss", 0.6, 0.05)};
  o.priors.families = {f};
  EXPECT_NE(where(o).find("diagnosis.priors.stiffness_loss.loss: lower 0.6 > upper 0.05"),
            std::string::npos)
      << where(o);
  o.priors.families.clear();
  o.priors.weights = {{"added_mass", 2}};  // does not apply to a dry chain
  o.kinds.clear();
  EXPECT_NE(where(o).find("diagnosis.weights.added_mass: does not apply"),
            std::string::npos)
      << where(o);
}

// The stated-priors example: the portal frame's two lowest modes cannot tell a
// mass at the first-floor joints from one at the beam's middle; stating where
// the machine stands and what it weighs can.
TEST(StructureDiagnosis, PortalFramePriorsExample) {
  Study study =
      LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/portal_frame_priors.yaml");
  ASSERT_TRUE(study.diagnosis.has_value());
  EXPECT_FALSE(study.diagnosis->priors.empty());
  const StructureDiagnosisResult stated = RunStructureDiagnosis(study);
  EXPECT_EQ(stated.ranking.classes[0].kind, "attached_mass");
  EXPECT_EQ(stated.ranking.classes[0].region, "node n7");
  EXPECT_GT(stated.ranking.classes[0].laplace_probability, 0.99);
  EXPECT_GT(stated.ranking.classes[0].probability, 0.97);  // bagged
  EXPECT_NE(StructureDiagnosisReport(stated).find("stated priors: attached_mass"),
            std::string::npos);
  study.diagnosis->priors = StatedPriors();
  const StructureDiagnosisResult plain = RunStructureDiagnosis(study);
  EXPECT_EQ(plain.ranking.classes[0].kind, "attached_mass");
  EXPECT_LT(plain.ranking.classes[0].probability, 0.5);
}

// Sensors between nodes: the portal frame of portal_frame.yaml seen at points
// on its members (none a node of the model), the data made by numpy's own
// frame elements (12 per member). The machine (2.0 t at the first-floor beam's
// middle) is found where it is and about as heavy.
TEST(StructureDiagnosis, PortalFrameSensorsBetweenNodesExample) {
  const Study study =
      LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/portal_frame_points.yaml");
  ASSERT_EQ(study.measurements.size(), 1u);
  const ModalData& data = study.measurements[0].data;
  ASSERT_TRUE(data.HasInterpolatedSensors());
  EXPECT_EQ(data.sensor_weights.rows(), 8);
  EXPECT_EQ(data.sensor_names[4], "at(1.5, 3.5, 0):uy");
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  ASSERT_FALSE(r.ranking.classes.empty());
  EXPECT_EQ(r.ranking.classes[0].kind, "attached_mass");
  EXPECT_EQ(r.ranking.classes[0].region, "node n7");
  // The family is all but certain; where exactly is shared between n7 and
  // the masses between nodes next to it (their positions fitted); every class
  // elsewhere together has less than 0.03 (the Laplace posterior: less than
  // 0.01 each).
  ASSERT_FALSE(r.ranking.kind_probabilities.empty());
  EXPECT_EQ(r.ranking.kind_probabilities[0].first, "attached_mass");
  EXPECT_GT(r.ranking.kind_probabilities[0].second, 0.97);
  double elsewhere = 0;
  for (const RankedClass& c : r.ranking.classes) {
    if (c.region.find("n7") == std::string::npos) elsewhere += c.probability;
    if (c.laplace_probability > 0.01) {
      EXPECT_NE(c.region.find("n7"), std::string::npos) << c.region;
    }
  }
  EXPECT_LT(elsewhere, 0.03);
  ASSERT_FALSE(r.ranking.classes[0].magnitudes.empty());
  EXPECT_EQ(r.ranking.classes[0].magnitudes[0].unit, "kg");
  EXPECT_NEAR(r.ranking.classes[0].magnitudes[0].value, 2000.0, 200.0);
}

// A four-element cantilever's and a three-storey chain's study text, without
// their diagnosis: the study readers' tests add one.
std::string SmallCantileverStudy() {
  return "name: x\nmodel: {type: cantilever, length: 2.0, elements: 4,\n"
         "  section: {E: 2.1e11, A: 9.0e-4, I: 1.6875e-8, rho: 7850}}\n"
         "measurements:\n  - {state: a, frequencies_hz: [3.1]}\n";
}

std::string SmallChainStudy() {
  return "name: x\nmodel: {type: chain, masses: [1e5, 1e5, 1e5], springs: [2e8, 2e8, "
         "2e8]}\n"
         "measurements:\n  - {state: air, frequencies_hz: [3.48, 9.6, 13.9]}\n";
}

// diagnosis.engine: the one engine (effects as changes of the model) by
// default on every model, a cantilever included; the cantilever's own
// pipeline where the study says so; a bad value, or the cantilever's pipeline
// on another model, is the study's error naming the field.
TEST(StructureDiagnosis, TheStudyChoosesTheEngine) {
  EXPECT_EQ(DiagnosisSpec().Engine(), "model_effects");
  const std::string cantilever = SmallCantileverStudy();
  EXPECT_EQ(ParseStudy(cantilever + "diagnosis: {noise: {frequency: 0.01}}\n", "x.yaml")
                .diagnosis->Engine(),
            "model_effects");
  const Study chosen =
      ParseStudy(cantilever + "diagnosis: {engine: model_effects}\n", "x.yaml");
  EXPECT_EQ(chosen.diagnosis->Engine(), "model_effects");
  const Study own =
      ParseStudy(cantilever + "diagnosis: {engine: cantilever}\n", "x.yaml");
  EXPECT_EQ(own.diagnosis->Engine(), "cantilever");
  testing::ExpectInputError(
      [&] { ParseStudy(cantilever + "diagnosis: {engine: fast}\n", "x.yaml"); },
      {"engine", "model_effects or cantilever", "fast"});
  testing::ExpectInputError(
      [] {
        ParseStudy(
            "name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
            "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
            "diagnosis: {engine: cantilever}\n",
            "x.yaml");
      },
      {"engine", "needs a cantilever model"});
  // max_effects unstated: pairs on the cantilever's own pipeline; on the one
  // engine, pairs where two or more states were measured (air and water) and
  // single effects otherwise; stated, the same on both.
  EXPECT_EQ(DiagnosisSpec().MaxEffectsFor(/*own_pipeline=*/true, 1), 2);
  EXPECT_EQ(DiagnosisSpec().MaxEffectsFor(/*own_pipeline=*/false, 1), 1);
  EXPECT_EQ(DiagnosisSpec().MaxEffectsFor(/*own_pipeline=*/false, 2), 2);
  const Study pairs = ParseStudy(
      cantilever + "diagnosis: {engine: model_effects, max_effects: 2}\n", "x.yaml");
  EXPECT_EQ(pairs.diagnosis->MaxEffectsFor(false, 1), 2);
  const Study singles =
      ParseStudy(cantilever + "diagnosis: {max_effects: 1}\n", "x.yaml");
  EXPECT_EQ(singles.diagnosis->MaxEffectsFor(false, 2), 1);
  EXPECT_EQ(singles.diagnosis->MaxEffectsFor(true, 1), 1);
  EffectRankingOptions three;
  three.max_effects = 3;
  EXPECT_EQ(three.Validate().field, "max_effects");
  // pair_places: 10 unless stated, at least 2 or -1 (every place).
  EXPECT_EQ(pairs.diagnosis->pair_places, 10);
  EXPECT_EQ(EffectRankingOptions().pair_places, 10);
  EXPECT_EQ(
      ParseStudy(cantilever + "diagnosis: {max_effects: 2, pair_places: -1}\n", "x.yaml")
          .diagnosis->pair_places,
      -1);
  testing::ExpectInputError(
      [&] { ParseStudy(cantilever + "diagnosis: {pair_places: 1}\n", "x.yaml"); },
      {"diagnosis.pair_places", "at least 2, or -1"});
  EffectRankingOptions one_place;
  one_place.pair_places = 1;
  EXPECT_EQ(one_place.Validate().field, "pair_places");
  one_place.pair_places = -1;
  EXPECT_FALSE(one_place.Validate());
}

// diagnosis.model_uncertainty: what the study states of the model's overall
// stiffness and mass reaches the ranking, and the report names it among the
// form errors allowed for; out of range, an unknown key, or on the
// cantilever's own pipeline, the field is named before any fit.
TEST(StructureDiagnosis, ReadsAStatedModelUncertainty) {
  const std::string chain = SmallChainStudy();
  const Study study = ParseStudy(
      chain + "diagnosis: {model_uncertainty: {stiffness: 0.02, mass: 0.01}}\n",
      "x.yaml");
  EXPECT_EQ(study.diagnosis->stiffness_uncertainty, 0.02);
  EXPECT_EQ(study.diagnosis->mass_uncertainty, 0.01);
  EXPECT_EQ(DiagnosisSpec().stiffness_uncertainty, 0);
  EXPECT_EQ(EffectRankingOptions().mass_uncertainty, 0);
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  ASSERT_EQ(r.ranking.form_errors.size(), 2u);
  EXPECT_NE(r.ranking.form_errors[0].name.find("overall stiffness (2 %)"),
            std::string::npos);
  EXPECT_NE(StructureDiagnosisReport(r).find("overall mass (1 %)"), std::string::npos);
  testing::ExpectInputError(
      [&] {
        ParseStudy(chain + "diagnosis: {model_uncertainty: {stiffness: -0.01}}\n",
                   "x.yaml");
      },
      {"diagnosis.model_uncertainty.stiffness", "0 <= value < 0.5", "-0.01"});
  testing::ExpectInputError(
      [&] {
        ParseStudy(chain + "diagnosis: {model_uncertainty: {mass: 0.5}}\n", "x.yaml");
      },
      {"diagnosis.model_uncertainty.mass", "0 <= value < 0.5"});
  testing::ExpectInputError(
      [&] {
        ParseStudy(chain + "diagnosis: {model_uncertainty: {damping: 0.1}}\n", "x.yaml");
      },
      {"damping"});
  const std::string cantilever = SmallCantileverStudy();
  // Refused on the cantilever's own pipeline only; a cantilever's default
  // engine (the one engine) reads them.
  testing::ExpectInputError(
      [&] {
        ParseStudy(cantilever +
                       "diagnosis: {engine: cantilever, model_uncertainty: "
                       "{stiffness: 0.02}}\n",
                   "x.yaml");
      },
      {"diagnosis.model_uncertainty", "engine: model_effects"});
  testing::ExpectInputError(
      [&] {
        ParseStudy(cantilever + "diagnosis: {engine: cantilever, gap_explained: 0.3}\n",
                   "x.yaml");
      },
      {"diagnosis.gap_explained", "engine: model_effects"});
  EXPECT_EQ(ParseStudy(cantilever + "diagnosis: {model_uncertainty: {stiffness: 0.02}}\n",
                       "x.yaml")
                .diagnosis->stiffness_uncertainty,
            0.02);
  EXPECT_EQ(ParseStudy(cantilever + "diagnosis: {gap_explained: 0.3}\n", "x.yaml")
                .diagnosis->gap_explained,
            0.3);
}

// Measured frequencies out of ascending order are the study's error, named with
// the state and the two modes, before any fit (on every model type: a chain
// and a cantilever, the default engine on both). Two modes within 5 standard
// deviations of the stated frequency noise of each other (a symmetric
// structure's pair, as the bundled jacket lists them) may come in either order.
TEST(StructureDiagnosis, RefusesFrequenciesOutOfOrder) {
  const std::string chain =
      "name: x\nmodel: {type: chain, masses: [1e5, 1e5, 1e5], springs: [2e8, 2e8, "
      "2e8]}\n";
  testing::ExpectInputError(
      [&] {
        RunStructureDiagnosis(ParseStudy(
            chain +
                "measurements:\n  - {state: air, frequencies_hz: [9.6, 3.48, 13.9]}\n",
            "x.yaml"));
      },
      {"x.yaml", "measurements[1]", "state air", "ascending", "mode 1 is 9.6 Hz",
       "mode 2 is 3.48 Hz"});
  testing::ExpectInputError(
      [&] {
        RunStructureDiagnosis(
            ParseStudy("name: x\nmodel: {type: cantilever, length: 2.0, elements: 4,\n"
                       "  section: {E: 2.1e11, A: 9.0e-4, I: 1.6875e-8, rho: 7850}}\n"
                       "measurements:\n  - {state: a, frequencies_hz: [3.1, 19.6]}\n"
                       "  - {state: b, frequencies_hz: [19.6, 3.1]}\n",
                       "x.yaml"));
      },
      {"measurements[2]", "state b", "ascending", "mode 1 is 19.6 Hz"});
  // 0.9 % apart, 4.5 sigma of 0.2 %: in either order.
  const StructureDiagnosisResult close = RunStructureDiagnosis(ParseStudy(
      chain + "measurements:\n  - {state: air, frequencies_hz: [3.48, 3.4487, 13.9]}\n"
              "diagnosis: {candidates: [stiffness_loss], bagging_copies: 0}\n",
      "x.yaml"));
  EXPECT_FALSE(close.ranking.classes.empty());
  // 1.1 % apart, 5.5 sigma: refused.
  testing::ExpectInputError(
      [&] {
        RunStructureDiagnosis(ParseStudy(
            chain +
                "measurements:\n  - {state: air, frequencies_hz: [3.48, 3.4417, 13.9]}\n",
            "x.yaml"));
      },
      {"ascending", "mode 2 is 3.4417 Hz"});
}

// diagnosis.frequency_temperature chooses how the frequencies' noise
// temperature enters the evidence; the report and diagnosis.json say which.
TEST(StructureDiagnosis, ReadsTheFrequencyTemperature) {
  const std::string chain = SmallChainStudy();
  const Study study =
      ParseStudy(chain + "diagnosis: {frequency_temperature: marginal}\n", "x.yaml");
  EXPECT_EQ(study.diagnosis->frequency_temperature,
            EffectRankingOptions::FrequencyTemperature::kMarginal);
  EXPECT_EQ(ToString(DiagnosisSpec().frequency_temperature), "auto");
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  EXPECT_EQ(ToString(r.ranking.frequency_temperature), "marginal");
  EXPECT_EQ(r.ranking.temperature, r.ranking.classes[0].frequency_temperature);
  EXPECT_NE(StructureDiagnosisReport(r).find("integrated over for each class"),
            std::string::npos);
  EXPECT_EQ(FrequencyTemperatureNamed("threshold"),
            EffectRankingOptions::FrequencyTemperature::kThreshold);
  EXPECT_FALSE(FrequencyTemperatureNamed("Marginal").has_value());
  testing::ExpectInputError(
      [&] { ParseStudy(chain + "diagnosis: {frequency_temperature: Auto}\n", "x.yaml"); },
      {"diagnosis.frequency_temperature", "auto, threshold or marginal", "Auto"});
  const std::string cantilever = SmallCantileverStudy();
  testing::ExpectInputError(
      [&] {
        ParseStudy(
            cantilever +
                "diagnosis: {engine: cantilever, frequency_temperature: marginal}\n",
            "x.yaml");
      },
      {"diagnosis.frequency_temperature", "engine: model_effects"});
  EXPECT_EQ(
      ParseStudy(cantilever + "diagnosis: {frequency_temperature: marginal}\n", "x.yaml")
          .diagnosis->frequency_temperature,
      EffectRankingOptions::FrequencyTemperature::kMarginal);
}

// The verdict checked on a mode it was not fitted to (diagnosis.held_out): on the
// bundled shear building (storey 3 lost 25 %), "auto" holds out the highest of
// its four modes; the damaged storey fitted on the other three predicts it
// better than the nominal model does, with its loss still near 0.25. "none"
// makes no check; a named mode that is not measured, or every mode, is refused
// naming the field.
TEST(StructureDiagnosis, ChecksTheVerdictOnAHeldOutMode) {
  Study study =
      LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/shear_building.yaml");
  ASSERT_TRUE(study.diagnosis.has_value());
  study.diagnosis->candidates = {"stiffness_loss", "material_scaling"};
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  ASSERT_TRUE(r.ranking.held_out.has_value());
  const HeldOutCheck& h = *r.ranking.held_out;
  ASSERT_TRUE(h.ok) << h.why;
  EXPECT_EQ(h.kind, "stiffness_loss");
  EXPECT_EQ(h.region, "element 3");
  ASSERT_EQ(h.nominal.size(), 1u);
  ASSERT_EQ(h.refit.size(), 1u);
  EXPECT_EQ(h.refit[0].mode, 3);
  const double nominal_error =
      std::abs(h.nominal[0].model_hz / h.nominal[0].measured_hz - 1);
  const double refit_error = std::abs(h.refit[0].model_hz / h.refit[0].measured_hz - 1);
  EXPECT_LT(refit_error, nominal_error / 2);
  EXPECT_NEAR(std::exp(h.theta[0]), 0.25, 0.04);
  const std::string report = StructureDiagnosisReport(r);
  EXPECT_NE(report.find("held-out check: stiffness_loss at element 3"), std::string::npos)
      << report;

  study.diagnosis->held_out = "none";
  EXPECT_FALSE(RunStructureDiagnosis(study).ranking.held_out.has_value());
  study.diagnosis->held_out = "list";
  study.diagnosis->held_out_modes = {{"test", 5}};
  testing::ExpectInputError([&] { RunStructureDiagnosis(study); },
                            {"diagnosis.held_out", "modes 1..4", "5"});
  study.diagnosis->held_out_modes = {{"water", 1}};
  testing::ExpectInputError([&] { RunStructureDiagnosis(study); },
                            {"diagnosis.held_out", "water"});
  study.diagnosis->held_out_modes = {{"test", 1}, {"test", 2}, {"test", 3}, {"test", 4}};
  testing::ExpectInputError([&] { RunStructureDiagnosis(study); },
                            {"diagnosis.held_out", "every measured mode"});
  EffectRankingOptions o;
  o.held_out = {{1, 0}};
  testing::ExpectInputError([&] { RankModelEffects(study.structure, r.measured, o); },
                            {"diagnosis.held_out", "state 2 mode 1", "not measured"});
}

// The bundled cantilever whose real base has springs (1.0e5 N/m, 3.5e4 N m/rad;
// its data made by a 60-element truth) on the one engine (the default; the
// scenario diagnose.sh runs the same from the command line in Release): the
// clamped model's base released as a rigid support, the springs found within
// 2 %.
TEST(StructureDiagnosis, NamesAClampedCantileversSpringsOnTheOneEngine) {
  Study study =
      LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/support_flexibility.yaml");
  ASSERT_TRUE(study.diagnosis.has_value());
  study.diagnosis->engine = "model_effects";
  study.diagnosis->candidates = {"support_flexibility", "material_scaling", "added_mass"};
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  EXPECT_EQ(r.model_type, "cantilever");
  ASSERT_FALSE(r.ranking.classes.empty());
  const RankedClass& top = r.ranking.classes[0];
  EXPECT_EQ(top.kind, "support_flexibility");
  EXPECT_GT(top.probability, 0.99);
  std::map<std::string, double> found;
  for (const EffectMagnitude& m : top.magnitudes) found[m.name] = m.value;
  EXPECT_NEAR(found["base spring ux (mean of 1 supports)"], 1.0e5, 2e3);
  EXPECT_NEAR(found["base spring rz (mean of 1 supports)"], 3.5e4, 7e2);
}

// The bundled bar with water's 2.83 kg/m to 1.5 m, fading over its top
// 0.15 m (a 60-element truth), measured by four frequencies only, on the one
// engine: water named, its level fitted near 1.5 m. Every start of the level
// (0.6, 1.2 and 1.9 m) is a node of the 20-element model; the level stayed at
// 1.2 m (chi2 654) while its derivative at a node was zero.
TEST(StructureDiagnosis, FitsTheWaterLevelFromFourFrequenciesOnTheOneEngine) {
  Study study =
      LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/frequencies_only.yaml");
  ASSERT_TRUE(study.diagnosis.has_value());
  study.diagnosis->engine = "model_effects";
  study.diagnosis->candidates = {"added_mass", "material_scaling", "support_flexibility"};
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  ASSERT_FALSE(r.ranking.classes.empty());
  const RankedClass& top = r.ranking.classes[0];
  EXPECT_EQ(top.kind, "added_mass");
  std::map<std::string, double> found;
  for (const EffectMagnitude& m : top.magnitudes) found[m.name] = m.value;
  EXPECT_GT(found["water_level"], 1.35);
  EXPECT_LT(found["water_level"], 1.55);
  EXPECT_LT(top.chi2, 4 * 9.0);  // four frequencies within 3 noise units each
}

// The bundled bar tested in air and in water (E 3 % low in both; water's
// 2.83 kg/m to 1.2 m, fading over its top 0.2 m; data from 60-element truths)
// on the one engine with pairs: water and the material error named together,
// the E factor within 0.5 % of 203.7 / 210, among every family (the first
// test) and among three (the second, which the sanitizers run); with
// max_effects unstated too (a study of two states tries pairs). With single
// effects only, no pair is tried.
void ExpectWaterAndAMaterialErrorTogether(const std::vector<std::string>& candidates) {
  Study study =
      LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/air_and_water.yaml");
  ASSERT_TRUE(study.diagnosis.has_value());
  study.diagnosis->engine = "model_effects";
  study.diagnosis->max_effects = 2;
  study.diagnosis->candidates = candidates;
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  ASSERT_FALSE(r.ranking.classes.empty());
  const RankedClass& top = r.ranking.classes[0];
  EXPECT_EQ(top.kind, "added_mass+material_scaling");
  EXPECT_GT(top.probability, 0.9);
  std::map<std::string, double> found;
  for (const EffectMagnitude& m : top.magnitudes) found[m.name] = m.value;
  EXPECT_NEAR(found["e_factor"], 203.7 / 210.0, 0.005);
  EXPECT_GT(found["water_level"], 0.9);
  EXPECT_LT(found["water_level"], 1.3);
  double sum = 0;
  for (const RankedClass& c : r.ranking.classes) sum += c.probability;
  EXPECT_NEAR(sum, 1.0, 1e-9);
  // Each of the two is present with at least the pair's probability, and the
  // report says so.
  for (const auto& [family, p] : FamilyPresence(r.ranking)) {
    if (family == "added_mass" || family == "material_scaling") {
      EXPECT_GE(p, top.probability - 1e-12) << family;
    }
  }
  EXPECT_NE(StructureDiagnosisReport(r).find("each family, alone or in a pair: "),
            std::string::npos)
      << StructureDiagnosisReport(r);

  // Unstated, pairs are tried here: the study measured two states.
  study.diagnosis->max_effects = 0;
  study.diagnosis->candidates = {"added_mass", "material_scaling"};
  const StructureDiagnosisResult by_default = RunStructureDiagnosis(study);
  ASSERT_FALSE(by_default.ranking.classes.empty());
  EXPECT_EQ(by_default.ranking.classes[0].kind, "added_mass+material_scaling");
  study.diagnosis->max_effects = 1;
  const StructureDiagnosisResult single = RunStructureDiagnosis(study);
  for (const RankedClass& c : single.ranking.classes)
    EXPECT_EQ(c.kind.find('+'), std::string::npos) << c.kind;
  EXPECT_EQ(FamilyPresence(single.ranking), single.ranking.kind_probabilities);
  EXPECT_EQ(StructureDiagnosisReport(single).find("alone or in a pair"),
            std::string::npos);
}

// A pair's probability counts for each of its two families; a family's own
// entry and its pairs add up.
TEST(EffectRanking, FamilyPresenceSumsEachFamilyOverThePairsThatHoldIt) {
  EXPECT_EQ(FamiliesOf("added_mass"), (std::vector<std::string>{"added_mass"}));
  EXPECT_EQ(FamiliesOf("added_mass+support_flexibility"),
            (std::vector<std::string>{"added_mass", "support_flexibility"}));
  EXPECT_EQ(FamiliesOf("stiffness_loss+stiffness_loss"),
            (std::vector<std::string>{"stiffness_loss"}));
  EffectRanking r;
  r.kind_probabilities = {{"added_mass+support_flexibility", 0.5},
                          {"support_flexibility", 0.25},
                          {"added_mass+material_scaling", 0.0625},
                          {"material_scaling+material_scaling", 0.0625},
                          {"none", 0.125}};
  const std::vector<std::pair<std::string, double>> expected = {
      {"support_flexibility", 0.75},
      {"added_mass", 0.5625},
      {"material_scaling", 0.125},
      {"none", 0.125}};
  EXPECT_EQ(FamilyPresence(r), expected);
}

TEST(StructureDiagnosis, NamesWaterAndAMaterialErrorTogetherOnTheOneEngine) {
  ExpectWaterAndAMaterialErrorTogether({});  // every family that applies
}

TEST(StructureDiagnosis, NamesWaterAndAMaterialErrorTogetherAmongThreeFamilies) {
  ExpectWaterAndAMaterialErrorTogether(
      {"added_mass", "support_flexibility", "material_scaling"});
}

// The bundled bar under a 3.0 kN tension (1.37 times its buckling load; data
// from a 60-element truth) on the one engine, axial_load named among the
// candidates: the force found within 2 %.
TEST(StructureDiagnosis, NamesACantileversAxialLoadOnTheOneEngine) {
  Study study = LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/axial_load.yaml");
  ASSERT_TRUE(study.diagnosis.has_value());
  study.diagnosis->engine = "model_effects";
  study.diagnosis->candidates = {"axial_load", "material_scaling", "support_flexibility"};
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  ASSERT_FALSE(r.ranking.classes.empty());
  const RankedClass& top = r.ranking.classes[0];
  EXPECT_EQ(top.kind, "axial_load");
  EXPECT_GT(top.probability, 0.99);
  ASSERT_FALSE(top.magnitudes.empty());
  EXPECT_EQ(top.magnitudes[0].name, "axial_force");
  EXPECT_NEAR(top.magnitudes[0].value, 3000.0, 60.0);
}

// The pipeline on the bundled example (data made by numpy, not femup).
TEST(StructureDiagnosis, ShearBuildingExampleEndToEnd) {
  const Study study =
      LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/shear_building.yaml");
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  EXPECT_EQ(r.model_type, "chain");
  ASSERT_FALSE(r.ranking.classes.empty());
  EXPECT_EQ(r.ranking.classes[0].region, "element 3");
  const std::string report = StructureDiagnosisReport(r);
  EXPECT_NE(report.find("verdict: stiffness_loss at element 3"), std::string::npos)
      << report;
  testing::ScratchDir dir;
  {
    OutputDir out(dir.File("diag"));
    std::vector<std::string> warnings;
    WriteStructureDiagnosisOutputs(r, false, &out, &warnings);
    out.Commit();
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.File("diag/diagnosis.json")));
}

TEST(StructureDiagnosis, RefusesAFamilyThatDoesNotApplyBeforeAnyFit) {
  Study study =
      LoadStudy(std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/shear_building.yaml");
  DiagnosisSpec spec = study.diagnosis.value_or(DiagnosisSpec());
  spec.candidates = {"added_mass"};
  study.diagnosis = spec;
  try {
    RunStructureDiagnosis(study);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("diagnosis.candidates"), std::string::npos)
        << e.what();
  }
}

// A portal whose beam carries a floor's mass (rho A = 1,800 kg/m), modelled on
// two Euler-Bernoulli elements per member: its third and fourth modes are the
// beam's and columns' own bending, which two elements resolve poorly. The
// truth: Timoshenko members (shear area 0.4 A) on 12 elements per member with
// a 1.5 t machine at the beam's middle (model node n5); four modes at four
// sensors, noise 0.2 % / 2 % (seeded). The model's mesh moves the measured
// modes by far more than the noise, so the diagnosis runs on the finer mesh,
// says so, and names the machine in the model's own terms.
std::string HeavyPortalStudy(bool refine) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(1, 1, 2, 3.9, 6.8);
  spec.column = {210e9, 3.0e-3, 1.0e-5, 7850};
  spec.beam = {210e9, 6.9e-3, 1.4e-4, 2.6e5};
  const Structure model = BuildPlaneFrameStructure(spec);
  PlaneFrameSpec truth_spec = spec;
  truth_spec.elements_per_member = 12;
  truth_spec.theory = BeamTheory::kTimoshenko;
  truth_spec.column_shear_area = 0.4 * spec.column.A;
  truth_spec.beam_shear_area = 0.4 * spec.beam.A;
  Structure truth = BuildPlaneFrameStructure(truth_spec);
  const std::vector<int> at = MatchDofs(model, truth);
  auto dof = [&](const std::string& label) {
    const auto it = std::find(model.dof_labels.begin(), model.dof_labels.end(), label);
    EXPECT_NE(it, model.dof_labels.end()) << label;
    return at[static_cast<std::size_t>(it - model.dof_labels.begin())];
  };
  std::vector<Eigen::Triplet<double>> machine;
  for (const char* d : {"n5:ux", "n5:uy"}) machine.emplace_back(dof(d), dof(d), 1500.0);
  SparseMatrix added(truth.mass.rows(), truth.mass.cols());
  added.setFromTriplets(machine.begin(), machine.end());
  const Modes modes = SolveModes(truth.stiffness, truth.mass + added);
  const std::vector<std::string> sensors = {"n1:ux", "n2:ux", "n3:ux", "n5:uy"};
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::ostringstream hz, shapes;
  hz << std::setprecision(10);
  shapes << std::setprecision(10);
  for (int j = 0; j < 4; ++j) {
    hz << (j ? ", " : "") << modes.FrequenciesHz()[j] * (1 + 0.002 * normal(rng));
    Eigen::VectorXd phi(sensors.size());
    for (std::size_t i = 0; i < sensors.size(); ++i)
      phi[static_cast<Eigen::Index>(i)] = modes.shapes(dof(sensors[i]), j);
    const double peak = phi.cwiseAbs().maxCoeff();
    shapes << "      - [";
    for (Eigen::Index i = 0; i < phi.size(); ++i)
      shapes << (i ? ", " : "") << phi[i] + 0.02 * peak * normal(rng);
    shapes << "]\n";
  }
  return R"(
name: heavy_portal
model:
  type: plane_frame
  storeys: 1
  bays: 1
  storey_height: 3.9
  bay_width: 6.8
  elements_per_member: 2
  column: {E: 2.1e11, A: 3.0e-3, I: 1.0e-5, rho: 7850}
  beam: {E: 2.1e11, A: 6.9e-3, I: 1.4e-4, rho: 2.6e5}
measurements:
  - state: test
    sensors: [n1:ux, n2:ux, n3:ux, n5:uy]
    frequencies_hz: [)" +
         hz.str() + R"(]
    shapes:
)" + shapes.str() +
         R"(diagnosis:
  noise: {frequency: 0.002, shape: 0.02}
  refine_mesh: )" +
         (refine ? "true" : "false") + "\n";
}

TEST(StructureDiagnosis, RunsOnAFinerMeshWhereTheModelsMovesTheModes) {
  EXPECT_FALSE(DiagnosisSpec().refine_mesh);  // off unless the study asks
  const Study study = ParseStudy(HeavyPortalStudy(true), "heavy_portal.yaml");
  ASSERT_TRUE(study.diagnosis.has_value());
  EXPECT_TRUE(study.diagnosis->refine_mesh);
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  ASSERT_FALSE(r.ranking.notes.empty());
  EXPECT_NE(r.ranking.notes[0].find("mesh is not converged"), std::string::npos)
      << r.ranking.notes[0];
  EXPECT_NE(r.ranking.notes[0].find("8 elements per member"), std::string::npos);
  // The finer mesh's own form variant is the shear one.
  ASSERT_EQ(r.ranking.form_errors.size(), 1u);
  EXPECT_NE(r.ranking.form_errors[0].name.find("shear deformation"), std::string::npos);
  ASSERT_FALSE(r.ranking.classes.empty());
  EXPECT_EQ(r.ranking.classes[0].kind, "attached_mass");
  EXPECT_NE(r.ranking.classes[0].region.find("n5"), std::string::npos)
      << r.ranking.classes[0].region;
  // Every region is named as the model's: its nodes, its segments, its members.
  for (const RankedClass& c : r.ranking.classes)
    EXPECT_EQ(c.region.find(" f"), std::string::npos) << c.region;

  const Study coarse = ParseStudy(HeavyPortalStudy(false), "heavy_portal.yaml");
  EXPECT_FALSE(coarse.diagnosis->refine_mesh);
  const StructureDiagnosisResult c = RunStructureDiagnosis(coarse);
  for (const std::string& note : c.ranking.notes)
    EXPECT_EQ(note.find("mesh is not converged"), std::string::npos) << note;
  EXPECT_EQ(c.ranking.form_errors.size(), 2u);
  testing::ExpectInputError(
      [] {
        ParseStudy(
            "name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
            "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
            "diagnosis: {refine_mesh: maybe}\n",
            "x.yaml");
      },
      {"refine_mesh"});
  testing::ExpectInputError(
      [] {
        ParseStudy(
            "name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
            "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
            "diagnosis: {form_step: sometimes}\n",
            "x.yaml");
      },
      {"form_step"});
  EXPECT_FALSE(ParseStudy("name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
                          "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
                          "diagnosis: {form_step: false}\n",
                          "x.yaml")
                   .diagnosis->form_step);
  EXPECT_TRUE(ParseStudy("name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
                         "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
                         "diagnosis: {form_fit: true}\n",
                         "x.yaml")
                  .diagnosis->form_fit);
  EXPECT_TRUE(ParseStudy("name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
                         "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
                         "diagnosis: {}\n",
                         "x.yaml")
                  .diagnosis->form_error_on_shapes);
  EXPECT_FALSE(ParseStudy("name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
                          "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
                          "diagnosis: {form_error_on_shapes: false}\n",
                          "x.yaml")
                   .diagnosis->form_error_on_shapes);
  testing::ExpectInputError(
      [] {
        ParseStudy(
            "name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
            "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
            "diagnosis: {form_error_on_shapes: 2}\n",
            "x.yaml");
      },
      {"form_error_on_shapes"});
  testing::ExpectInputError(
      [] {
        ParseStudy(
            "name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
            "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
            "diagnosis: {rotary_inertia: perhaps}\n",
            "x.yaml");
      },
      {"rotary_inertia"});
  EXPECT_TRUE(ParseStudy("name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
                         "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
                         "diagnosis: {}\n",
                         "x.yaml")
                  .diagnosis->rotary_inertia);
  EXPECT_FALSE(ParseStudy("name: x\nmodel: {type: chain, masses: [1], springs: [1]}\n"
                          "measurements:\n  - {state: a, frequencies_hz: [1]}\n"
                          "diagnosis: {rotary_inertia: false}\n",
                          "x.yaml")
                   .diagnosis->rotary_inertia);
}

// A small jacket (1 x 1 bays, 3 levels of 10 m, X-braced faces, 2 elements per
// member, Euler-Bernoulli) and its "measured" modes from the same generator
// built otherwise: Timoshenko elements, 4 per member, with the stiffness of
// one group lowered through the generator's own factor. Sensors: ux and uy at
// the 12 leg joints (the same node names in both meshes); noise 0.2 % / 2 %.
SpaceFrameSpec SmallJacket() {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 1, 1, 2, 10, 12, 12);
  spec.blocks_per_level = 1;
  spec.bracing = FaceBracing::kX;
  return spec;
}

// A jacket's "measured" twin: Timoshenko elements, 4 per member.
SpaceFrameSpec TimoshenkoJacket(SpaceFrameSpec spec = SmallJacket()) {
  spec.theory = BeamTheory::kTimoshenko;
  spec.elements_per_member = 4;
  return spec;
}

// The lowest `num_modes` modes of (k, m), a 3-level jacket's, as measured: ux
// and uy at its 12 leg joints, 0.2 % noise on the frequencies and 2 % of each
// shape's peak on its entries (mt19937 `seed`).
ModalData JacketData(const ParametrisedModel& truth, const SparseMatrix& k,
                     const SparseMatrix& m, int num_modes, unsigned seed) {
  const Modes modes = SolveModes(k, m);
  ModalData out;
  out.state = "air";
  for (int node = 1; node <= 12; ++node) {
    for (const char* c : {":ux", ":uy"})
      out.sensor_dofs.push_back(truth.FindDof("n" + std::to_string(node) + c));
  }
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  out.frequencies_hz = modes.FrequenciesHz().head(num_modes);
  out.shapes.resize(static_cast<Eigen::Index>(out.sensor_dofs.size()), num_modes);
  for (int j = 0; j < num_modes; ++j) {
    out.frequencies_hz[j] *= 1 + 0.002 * normal(rng);
    for (std::size_t i = 0; i < out.sensor_dofs.size(); ++i)
      out.shapes(static_cast<Eigen::Index>(i), j) = modes.shapes(out.sensor_dofs[i], j);
    const double peak = out.shapes.col(j).cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < out.shapes.rows(); ++i)
      out.shapes(i, j) += 0.02 * peak * normal(rng);
  }
  return out;
}

ModalData JacketMeasured(const std::string& damaged, double loss, int num_modes,
                         unsigned seed) {
  const SpaceFrameSpec truth_spec = TimoshenkoJacket();
  const ParametrisedModel truth = BuildSpaceFrame(truth_spec);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(truth.num_parameters());
  const int p = truth.FindParameter("stiffness[" + damaged + "]");
  EXPECT_GE(p, 0) << damaged;
  if (p >= 0) d[p] = -loss;
  // the sensors' DOF indices are the same in the coarser model
  return JacketData(truth, truth.UpdatedStiffness(d), truth.UpdatedDryMass(d), num_modes,
                    seed);
}

// E 1.5 % low on the Timoshenko truth: the Euler-Bernoulli model's fit of a
// uniform E takes up the truth's shear deformation too (its raw optimum is
// well below 0.985), and at that point the whitened misfit (the model's form
// error allowed for) gains nothing over "none". Each class is moved to the
// whitened misfit's mode before its evidence: E is named, near its value.
// Without that step (EffectRankingOptions::form_step false) the verdict is
// "none". The jacket is square: its x and y sway modes come in pairs of equal
// frequency, in truth and model, which the engine turns to the measured shapes
// before pairing (EigenSensitivity.EqualPairsArePairedWhateverTheirRotation);
// before it did, an AMD EPYC's eigensolver rotation gave "none" a chi2 of
// 1.5e6 and named a leg group. (P 0.90 and E 0.984 with the step, when written.)
TEST(EffectRanking, NamesAUniformEErrorBesideTheModelsShearDeformation) {
  const Structure nominal = BuildSpaceFrameStructure(SmallJacket());
  const SpaceFrameSpec truth_spec = TimoshenkoJacket();
  const ParametrisedModel truth = BuildSpaceFrame(truth_spec);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(truth.num_parameters());
  for (int p = 0; p < truth.num_parameters(); ++p)
    if (truth.parameter(p).kind == ParameterKind::kStiffness) e[p] = -0.015;
  const ModalData d =
      JacketData(truth, truth.UpdatedStiffness(e), truth.UpdatedDryMass(e), 6, 11);
  EffectRankingOptions options = Options();
  options.max_members = 0;
  options.kinds = {"material_scaling", "stiffness_loss"};
  const EffectRanking r = RankModelEffects(nominal, {d}, options);
  ASSERT_FALSE(r.classes.empty());
  EXPECT_EQ(r.classes[0].kind, "material_scaling");
  EXPECT_GT(r.classes[0].probability, 0.7);
  ASSERT_FALSE(r.classes[0].magnitudes.empty());
  EXPECT_NEAR(r.classes[0].magnitudes[0].value, 0.985, 0.005);
  ASSERT_EQ(r.form_errors.size(), 1u);

  EXPECT_TRUE(EffectRankingOptions().form_step);  // on unless asked otherwise
  options.form_step = false;
  const EffectRanking raw = RankModelEffects(nominal, {d}, options);
  ASSERT_FALSE(raw.classes.empty());
  // The raw fit of E: 0.973 here, the verdict "none" at P 0.78.
  for (const RankedClass& c : raw.classes) {
    if (c.kind == "material_scaling") {
      ASSERT_FALSE(c.magnitudes.empty());
      EXPECT_LT(c.magnitudes[0].value, 0.985 - 0.005);
    }
  }
  EXPECT_EQ(raw.classes[0].kind, "none");
}

// The ranking on a space frame's Structure names a damaged brace group from
// data made with Timoshenko elements on a finer mesh. The groups alone: with
// the 72 members (NamesOneDamagedBraceOfAJacket) this test took 475 s under
// the sanitizers, and the same group was named.
TEST(EffectRanking, NamesADamagedBraceGroupOfAJacket) {
  const Structure nominal = BuildSpaceFrameStructure(SmallJacket());
  const ModalData d = JacketMeasured("l1:braces1", 0.5, 6, 3);
  EffectRankingOptions options = Options();
  options.max_members = 0;
  const EffectRanking r = RankModelEffects(nominal, {d}, options);
  ASSERT_FALSE(r.classes.empty());
  EXPECT_EQ(r.classes[0].kind, "stiffness_loss");
  EXPECT_EQ(r.classes[0].region, "element l1:braces1");
  EXPECT_GT(r.classes[0].probability, 0.9);
  EXPECT_NEAR(r.classes[0].magnitudes[0].value, 0.5, 0.1);
  // Attached masses only at the four top joints (n9..n12), not at every node,
  // and between them on the top horizontals' 8 segments.
  int attached = 0, between = 0;
  for (const RankedClass& c : r.classes) {
    if (c.kind != "attached_mass") continue;
    if (c.region.rfind("node ", 0) != 0) {
      ++between;
      continue;
    }
    ++attached;
    EXPECT_TRUE(c.region == "node n9" || c.region == "node n10" ||
                c.region == "node n11" || c.region == "node n12")
        << c.region;
  }
  EXPECT_EQ(attached, 4);
  EXPECT_EQ(between, 8);
}

// One damaged brace (half of an X, 60 % of its stiffness lost) is not its
// group's loss: the ranking tries each member and each of its finite elements
// on its own (EffectRankingOptions::max_members) and names that brace, with
// its loss.
// The data are the Timoshenko frame of four elements per member with the
// brace softened, through the finer Structure's own member matrix. Of the 72
// members, the 12 a linearised step ranks best are fitted
// (EffectRankingOptions::members_fitted), the others ranked at their screen's
// step, and a note says so. With fewer
// members allowed than the frame has, only the groups are tried and a note
// says so; naming the group under the stated regions tries its members again.
TEST(EffectRanking, NamesOneDamagedBraceOfAJacket) {
  const Structure nominal = BuildSpaceFrameStructure(SmallJacket());
  const SpaceFrameSpec truth_spec = TimoshenkoJacket();
  const Structure fine = BuildSpaceFrameStructure(truth_spec);
  const auto brace =
      std::find_if(fine.members.begin(), fine.members.end(),
                   [](const ElementMember& m) { return m.label == "brace n1-n17"; });
  ASSERT_NE(brace, fine.members.end());
  const SparseMatrix k = fine.stiffness - 0.6 * brace->stiffness.ToSparse();
  const ModalData d = JacketData(BuildSpaceFrame(truth_spec), k, fine.mass, 6, 7);
  const EffectRanking r = RankModelEffects(nominal, {d}, Options());
  ASSERT_FALSE(r.classes.empty());
  // The brace is named: the whole of it, or one of its two finite elements
  // (here its first half, 87 % lost, is preferred to the whole, 60 %: chi2 426
  // against 720 at a noise temperature of 11, the 2-element Euler-Bernoulli
  // model against the 4-element Timoshenko truth), the brace's places together
  // at P > 0.9; the whole member's own fit finds its loss.
  EXPECT_EQ(r.classes[0].kind, "stiffness_loss");
  EXPECT_EQ(r.classes[0].region.rfind("member brace n1-n17", 0), 0u)
      << r.classes[0].region;
  double brace_p = 0;
  for (const RankedClass& c : r.classes) {
    if (c.region.rfind("member brace n1-n17", 0) != 0) continue;
    brace_p += c.probability;
    if (c.region == "member brace n1-n17") {
      EXPECT_TRUE(c.fitted);
      EXPECT_NEAR(c.magnitudes[0].value, 0.6, 0.1);
    }
  }
  EXPECT_GT(brace_p, 0.9);
  // Every member and each of its two finite elements is ranked: the 12
  // fitted first, then the 204 others on their screen's step
  // (RankedClass::fitted), still of the family.
  int members = 0, fitted = 0;
  bool screened_seen = false;
  for (const RankedClass& c : r.classes) {
    if (c.region.rfind("member ", 0) != 0) continue;
    ++members;
    fitted += c.fitted;
    EXPECT_EQ(c.kind, "stiffness_loss");
    EXPECT_FALSE(c.fitted && screened_seen)
        << c.region << " listed after a screened class";
    screened_seen = screened_seen || !c.fitted;
    EXPECT_TRUE(std::isfinite(c.evidence.log_evidence)) << c.region;
    EXPECT_EQ(c.theta.size(), 1);
  }
  EXPECT_EQ(members, 72 * 3);
  EXPECT_EQ(fitted, 12);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("fitted on 12 of its 216 places on single members (72 "
                            "members and 144 of their finite elements)"),
            std::string::npos)
      << r.notes[0];
  EXPECT_NE(r.notes[0].find("diagnosis.members_fitted"), std::string::npos);

  EffectRankingOptions few = Options();
  few.kinds = {"stiffness_loss"};
  few.max_members = 10;
  const EffectRanking groups = RankModelEffects(nominal, {d}, few);
  for (const RankedClass& c : groups.classes)
    EXPECT_EQ(c.region.rfind("member ", 0), std::string::npos) << c.region;
  ASSERT_EQ(groups.notes.size(), 1u);
  EXPECT_NE(groups.notes[0].find("not on each of the 72 members"), std::string::npos)
      << groups.notes[0];
  EXPECT_NE(groups.notes[0].find("diagnosis.priors.stiffness_loss.regions"),
            std::string::npos);
  few.priors.families.push_back(fixtures::Prior("stiffness_loss", {}, {"l2:braces1"}));
  few.members_fitted = 4;
  const EffectRanking stated = RankModelEffects(nominal, {d}, few);
  // The group and 4 of the 48 places on its 16 half braces, after the screen.
  ASSERT_EQ(stated.notes.size(), 1u);
  EXPECT_NE(stated.notes[0].find("fitted on 4 of its 48 places"), std::string::npos)
      << stated.notes[0];
  EXPECT_EQ(stated.classes.size(), 1u + 1u + 48u);
  EXPECT_EQ(stated.classes[0].region.rfind("member brace n1-n17", 0), 0u)
      << stated.classes[0].region;
  EXPECT_EQ(std::count_if(stated.classes.begin(), stated.classes.end(),
                          [](const RankedClass& c) { return !c.fitted; }),
            44);

  // No place fitted after the screen: the group is the family's only fitted
  // class, the brace's screened places come out more probable than it, and
  // the most probable of them is fitted (one per round) before the ranking is
  // said; once fitted, it outranks every screened place and no second round
  // is needed.
  few.members_fitted = 0;
  const EffectRanking refit = RankModelEffects(nominal, {d}, few);
  ASSERT_FALSE(refit.classes.empty());
  EXPECT_EQ(refit.classes[0].region.rfind("member brace n1-n17", 0), 0u)
      << refit.classes[0].region;
  EXPECT_TRUE(refit.classes[0].fitted);
  EXPECT_EQ(std::count_if(refit.classes.begin(), refit.classes.end(),
                          [](const RankedClass& c) { return !c.fitted; }),
            47);
  ASSERT_FALSE(refit.notes.empty());
  EXPECT_NE(refit.notes[0].find("fitted on 1 of its 48 places"), std::string::npos)
      << refit.notes[0];
  EXPECT_NE(refit.notes[0].find("): the 1 whose step came out more probable than every "
                                "fitted place"),
            std::string::npos)
      << refit.notes[0];
  EXPECT_EQ(refit.notes[0].find("the 0 "), std::string::npos) << refit.notes[0];
}

// A deck's equipment sits on the top level's horizontals as often as on its
// joints: the attached-mass family tries the horizontals' element segments
// with the mass's position fitted (Structure::attached_mass_segments). 20 t at
// a quarter of the horizontal n9-n10 (a node of the Timoshenko truth's finer
// mesh, on its three translations) is named on that horizontal's first
// segment, near its position, with its mass. Stiffness loss (its groups) is
// the competing family.
TEST(EffectRanking, NamesADeckMassBetweenTheTopJointsOfAJacket) {
  const Structure nominal = BuildSpaceFrameStructure(SmallJacket());
  ASSERT_EQ(nominal.attached_mass_segments.size(), 4u * 2u);
  const SpaceFrameSpec truth_spec = TimoshenkoJacket();
  const Structure fine = BuildSpaceFrameStructure(truth_spec);
  const ParametrisedModel truth = BuildSpaceFrame(truth_spec);
  const auto quarter = std::find_if(
      fine.nodes.begin(), fine.nodes.end(),
      [](const ModelNode& node) { return node.xyz.isApprox(Eigen::Vector3d(3, 0, 30)); });
  ASSERT_NE(quarter, fine.nodes.end());
  std::vector<Eigen::Triplet<double>> t;
  for (const char* c : {":ux", ":uy", ":uz"})
    t.emplace_back(truth.FindDof(quarter->name + c), truth.FindDof(quarter->name + c),
                   2e4);
  SparseMatrix point(fine.mass.rows(), fine.mass.cols());
  point.setFromTriplets(t.begin(), t.end());
  const SparseMatrix m = fine.mass + point;
  const ModalData d = JacketData(truth, fine.stiffness, m, 6, 17);
  EffectRankingOptions options = Options();
  options.kinds = {"attached_mass", "stiffness_loss"};
  options.max_members = 0;
  const EffectRanking r = RankModelEffects(nominal, {d}, options);
  ASSERT_FALSE(r.classes.empty());
  const RankedClass& v = r.classes[0];
  EXPECT_EQ(v.kind, "attached_mass");
  // n9-n10's inner node in the model: after the 12 joints and 12 X centres,
  // one per member, and that horizontal is member 53 (24 per level; the top
  // level's 4 legs, then its horizontals along X): n(24 + 53).
  EXPECT_EQ(v.region, "n9-n77") << v.region;
  EXPECT_GT(v.probability, 0.5);
  // Mass, its ratio, the distance from n9, and the radius of gyration and
  // rotary inertia (the truth's mass has none).
  ASSERT_EQ(v.magnitudes.size(), 5u);
  EXPECT_NEAR(v.magnitudes[0].value, 2e4, 0.2 * 2e4);
  EXPECT_NEAR(v.magnitudes[2].value, 3.0, 1.0);  // m from n9
  EXPECT_EQ(v.magnitudes[4].name, "rotary_inertia");
  int nodes = 0, segments = 0;
  for (const RankedClass& c : r.classes) {
    if (c.kind != "attached_mass") continue;
    ++(c.region.rfind("node ", 0) == 0 ? nodes : segments);
  }
  EXPECT_EQ(nodes, 4);
  EXPECT_EQ(segments, 8);
}

// A jacket on springs under its legs (the model's engineering estimate) whose
// real foundation is three times softer in every direction: support
// flexibility acts on the springs and is named, with the translations' and
// the rotations' compliance ratios near 2 (k / (1 + 2) = k / 3). The data are
// the Timoshenko frame of four elements per member on the softer springs.
TEST(EffectRanking, NamesASofterFoundationOfAJacketOnSprings) {
  SpaceFrameSpec spec = SmallJacket();
  spec.base.horizontal = 1e9;
  spec.base.vertical = 1e9;
  spec.base.rocking = 1e9;
  const Structure nominal = BuildSpaceFrameStructure(spec);
  ASSERT_EQ(nominal.supports.size(), 4u * 5u);
  SpaceFrameSpec truth_spec = TimoshenkoJacket(spec);
  truth_spec.base.horizontal /= 3;
  truth_spec.base.vertical /= 3;
  truth_spec.base.rocking /= 3;
  const ParametrisedModel truth = BuildSpaceFrame(truth_spec);
  const ModalData d = JacketData(truth, truth.stiffness(), truth.mass(), 6, 11);
  EffectRankingOptions options = Options();
  options.max_members = 0;  // the groups alone: the members add 72 fits, not the point
  const EffectRanking r = RankModelEffects(nominal, {d}, options);
  ASSERT_FALSE(r.classes.empty());
  EXPECT_EQ(r.classes[0].kind, "support_flexibility");
  EXPECT_GT(r.classes[0].probability, 0.9);
  ASSERT_FALSE(r.classes[0].magnitudes.empty());
  // Its horizontal, vertical and rocking springs all three times softer: the
  // translations' ratio near 2. The rotations' is not: the braced legs hardly
  // turn at their feet (the jacket rocks on its legs' vertical springs), and
  // the Euler-Bernoulli model, stiffer than its Timoshenko truth, takes part of
  // its own form error up there: 8.1 (sd 0.40 in ln c) on this machine, so 2
  // lies 3.5 standard deviations off. What holds is the direction: softer than
  // modelled.
  const RankedClass& top = r.classes[0];
  ASSERT_GE(top.magnitudes.size(), 2u);
  EXPECT_EQ(top.magnitudes[0].name, "translation_compliance_ratio");
  EXPECT_EQ(top.magnitudes[1].name, "rotation_compliance_ratio");
  EXPECT_NEAR(top.magnitudes[0].value, 2.0, 0.5);
  EXPECT_GT(top.magnitudes[1].value, 1.0);
  EXPECT_LT(top.magnitudes[1].value, 20.0);
}

// What the model's own form error alone could do, the data cannot tell from
// "none": with two modes of the Timoshenko jacket (no effect added), a uniform
// E moves both frequencies as the Euler-Bernoulli model's shear variant does,
// and gains less than 3 noise standard deviations once that form error is
// allowed for. The two are named equivalent both ways, with a note, and
// "none"'s group probability is the sum; the probabilities themselves are
// unchanged (this is a statement, not a new verdict).
TEST(EffectRanking, NamesWhatTheFormErrorAloneCouldDoEquivalentToNone) {
  const Structure nominal = BuildSpaceFrameStructure(SmallJacket());
  const ParametrisedModel truth = BuildSpaceFrame(TimoshenkoJacket());
  // The first two modes of six (the noise is drawn mode by mode).
  const ModalData six = JacketData(truth, truth.stiffness(), truth.mass(), 6, 5);
  ModalData d = six;
  d.frequencies_hz = six.frequencies_hz.head(2);
  d.shapes = six.shapes.leftCols(2);
  EffectRankingOptions options = Options();
  options.max_members = 0;
  options.kinds = {"material_scaling"};
  const EffectRanking r = RankModelEffects(nominal, {d}, options);
  ASSERT_FALSE(r.classes.empty());
  ASSERT_EQ(r.form_errors.size(), 1u);
  const RankedClass& none = r.classes[0];
  EXPECT_EQ(none.kind, "none");
  EXPECT_NE(std::find(none.equivalent.begin(), none.equivalent.end(),
                      "material_scaling at all elements"),
            none.equivalent.end());
  double sum = none.probability, total = 0;
  for (const RankedClass& c : r.classes) {
    total += c.probability;
    const std::string label = c.region.empty() ? c.kind : c.kind + " at " + c.region;
    const bool named = std::find(none.equivalent.begin(), none.equivalent.end(), label) !=
                       none.equivalent.end();
    const bool back =
        std::find(c.equivalent.begin(), c.equivalent.end(), "none") != c.equivalent.end();
    EXPECT_EQ(named, back) << label;
    if (named) sum += c.probability;
  }
  EXPECT_NEAR(total, 1.0, 1e-9);
  EXPECT_NEAR(none.group_probability, sum, 1e-12);
  EXPECT_TRUE(std::any_of(r.notes.begin(), r.notes.end(), [](const std::string& n) {
    return n.find("the data cannot tell them from none") != std::string::npos;
  }));

  // Six modes with shapes tell them apart: no class is named with "none".
  const EffectRanking told = RankModelEffects(nominal, {six}, options);
  ASSERT_FALSE(told.classes.empty());
  EXPECT_EQ(told.classes[0].kind, "none");
  EXPECT_TRUE(told.classes[0].equivalent.empty());
}

// Large models search each start on a Ritz basis and finish on the full model
// (options.ritz_min_dofs). Forced on this 576-DOF frame, the ranking ends in
// the full-model search's optima wherever the probability is: the same
// classes first, the same chi2 and parameters to the solvers' tolerance for
// every class within a chi2 of 1000 of the best, the same probabilities. Far
// worse fits (chi2 50 to 100 times the best: a loss of a leg group asked to
// explain a damaged brace) sit on rough misfits with several local optima,
// and there a search on either model may end in a different one, better or
// worse (measured: 8 of the 23 classes, all with chi2 above 4.8e4 against a
// best of 165, 5 of them worse with the basis, by 3 % to 46 %); their
// probability is 0 either way. Which optimum such a search ends in turns on
// the last bits of every solve: these counts were 7 to 9 (worse 5 or 6), run
// to run, while METIS orderings on two threads at once could take each
// other's random draws (internal::MetisMutex); now they are the same on any
// number of threads. With the attached masses' rotary inertia (session 40, on
// an AMD EPYC; which of the two moved it was not measured apart) 10 ended
// elsewhere, 7 worse; with equal pairs of modes turned to the measured shapes
// before pairing (session 41, an Intel Xeon: this jacket is square) 12, 3
// worse; with the point-mass start (session 61) on one AMD EPYC machine 11
// of 24 ended elsewhere, 9 worse, with OpenBLAS's Haswell kernels (its choice
// there), and 12, 7 worse, with its SkylakeX kernels (OPENBLAS_CORETYPE). So
// the counts are bounded by a fraction of the classes (two thirds ending
// elsewhere, two fifths worse), the probabilities and the near classes held
// exactly.
TEST(EffectRanking, RitzSearchEndsInTheFullModelsOptima) {
  const Structure nominal = BuildSpaceFrameStructure(SmallJacket());
  const ModalData d = JacketMeasured("l1:braces1", 0.5, 6, 3);
  EffectRankingOptions full = Options(), ritz = Options();
  full.ritz_min_dofs = -1;
  ritz.ritz_min_dofs = 0;
  full.max_members = ritz.max_members = 0;  // the groups (the classes measured above)
  const EffectRanking a = RankModelEffects(nominal, {d}, full);
  const EffectRanking b = RankModelEffects(nominal, {d}, ritz);
  ASSERT_EQ(a.classes.size(), b.classes.size());
  ASSERT_GT(a.classes.size(), 5u);
  EXPECT_EQ(a.kind_probabilities, b.kind_probabilities);
  std::map<std::string, const RankedClass*> by_name;
  for (const RankedClass& c : b.classes) by_name[c.kind + " at " + c.region] = &c;
  const double best = a.classes.front().chi2;
  int different = 0, worse = 0;
  for (const RankedClass& c : a.classes) {
    const std::string name = c.kind + " at " + c.region;
    SCOPED_TRACE(name);
    ASSERT_EQ(by_name.count(name), 1u);
    const RankedClass& r = *by_name[name];
    const bool same = std::abs(c.chi2 - r.chi2) <= 1e-6 * c.chi2;
    if (!same) ++different;
    if (r.chi2 > c.chi2 * (1 + 1e-6)) ++worse;
    EXPECT_NEAR(c.probability, r.probability, 1e-9);
    if (c.chi2 > best + 1000) continue;
    EXPECT_TRUE(same) << c.chi2 << " against " << r.chi2;
    if (c.theta.size() > 0) {
      EXPECT_LT((c.theta - r.theta).lpNorm<Eigen::Infinity>(), 1e-4);
    }
  }
  EXPECT_EQ(a.classes.front().kind, b.classes.front().kind);
  EXPECT_EQ(a.classes.front().region, b.classes.front().region);
  EXPECT_LE(different, 2 * static_cast<int>(a.classes.size()) / 3);
  EXPECT_LE(worse, 2 * static_cast<int>(a.classes.size()) / 5);
  std::cout << "classes " << a.classes.size() << ", best chi2 " << best
            << ", ending elsewhere " << different << " (worse " << worse << ")\n";
}

// femup diagnose runs on a space_frame study (it refused them before the
// generator built a Structure of its groups).
// A space frame's base springs from a study file (model.base), and their
// errors named by field.
TEST(StructureDiagnosis, SpaceFrameBaseSpringsFromAStudyFile) {
  const std::string frame =
      "name: jacket\nmodel:\n  type: space_frame\n  bays_x: 1\n  bays_y: 1\n"
      "  levels: 2\n  elements_per_member: 1\n";
  const Study study =
      ParseStudyModel(frame + "  base: {vertical: 2e9, rocking: 4e9}\n", "jacket.yaml");
  ASSERT_EQ(study.structure.supports.size(), 4u * 3u);
  EXPECT_EQ(study.structure.supports[0].name, "base vertical at b1");
  EXPECT_EQ(study.structure.supports[0].stiffness, 2e9);
  EXPECT_EQ(study.model.dof_labels(), study.structure.dof_labels);
  EXPECT_EQ(study.model.dof_labels().back(), "b4:ry");
  for (const auto& [base, field] : {std::pair<std::string, std::string>{
                                        "  base: {rocking: -1}\n", "model.base.rocking"},
                                    {"  base: {}\n", "model.base"},
                                    {"  base: {rotation: 1}\n", "rotation"}}) {
    const std::string bad = base;  // a lambda may not read a structured binding (C++17)
    femup::testing::ExpectError([&] { ParseStudyModel(frame + bad, "jacket.yaml"); },
                                {field});
  }
}

TEST(StructureDiagnosis, RunsOnASpaceFrame) {
  const ModalData d = JacketMeasured("l2:braces1", 0.5, 4, 5);
  std::ostringstream hz;
  for (int j = 0; j < d.num_modes(); ++j)
    hz << (j ? ", " : "") << std::setprecision(10) << d.frequencies_hz[j];
  const Study study = ParseStudy(R"(
name: small_jacket
model:
  type: space_frame
  bays_x: 1
  bays_y: 1
  levels: 3
  level_height: 10
  bay_width_x: 12
  bay_width_y: 12
  elements_per_member: 2
  blocks_per_level: 1
  bracing: x
measurements:
  - {state: air, frequencies_hz: [)" +
                                     hz.str() + R"(]}
diagnosis:
  noise: {frequency: 0.002, shape: 0.02}
)",
                                 "jacket.yaml");
  EXPECT_EQ(study.structure.elements.size(), 9u);  // 3 levels x legs, braces, horizontals
  const StructureDiagnosisResult r = RunStructureDiagnosis(study);
  EXPECT_EQ(r.model_type, "space_frame");
  ASSERT_FALSE(r.ranking.classes.empty());
  // Frequencies only: the verdict is weaker; every family was fitted.
  std::set<std::string> kinds;
  for (const RankedClass& c : r.ranking.classes) kinds.insert(c.kind);
  for (const char* k : {"none", "stiffness_loss", "material_scaling", "attached_mass"})
    EXPECT_TRUE(kinds.count(k)) << k;
  EXPECT_NE(StructureDiagnosisReport(r).find("space_frame model"), std::string::npos);
}

// The bundled example examples/diagnosis/jacket.yaml: its "measured" modes are
// the generator's with Timoshenko elements, 4 per member (the model: Euler-
// Bernoulli, 2), and the braces of level 2 softened by 40 % through the
// generator's own factor; 6 modes, ux and uy at the leg joints, noise 0.2 % /
// 2 % from a portable draw (mt19937, Box-Muller). Written by
//   FEMUP_WRITE_JACKET_EXAMPLE=examples/diagnosis/jacket.yaml
//   build/tests/femup_tests --gtest_filter=JacketExample.*
// (the variable set on the command).
// (FEMUP_WRITE_LARGE_JACKET=FILE writes the same for the 10,560-DOF frame of
// examples/space_frame/jacket.yaml, for timing). Without them the test checks
// that the example's frequencies are those modes within 5 sigma.
struct JacketCase {
  SpaceFrameSpec model;
  int truth_elements_per_member = 4;
  std::string damaged = "l2:braces1";
  double loss = 0.4;
  int num_modes = 6;
};

JacketCase SmallJacketCase() {
  JacketCase c;
  c.model = SmallJacket();
  c.model.water_depth = 12;
  return c;
}

JacketCase LargeJacketCase() {
  JacketCase c;
  c.model.levels = 10;
  c.model.bays_x = 2;
  c.model.bays_y = 2;
  c.model.elements_per_member = 4;
  c.model.blocks_per_level = 2;
  c.model.water_depth = 30;
  c.truth_elements_per_member = 6;
  c.damaged = "l2:braces1";
  return c;
}

Modes TruthModes(const JacketCase& c, ParametrisedModel* truth_out) {
  SpaceFrameSpec t = c.model;
  t.theory = BeamTheory::kTimoshenko;
  t.elements_per_member = c.truth_elements_per_member;
  ParametrisedModel truth = BuildSpaceFrame(t);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(truth.num_parameters());
  d[truth.FindParameter("stiffness[" + c.damaged + "]")] = -c.loss;
  EigenOptions o;
  o.num_modes = c.num_modes;
  const Modes modes = SolveModes(truth.UpdatedStiffness(d), truth.UpdatedDryMass(d), o);
  *truth_out = std::move(truth);
  return modes;
}

std::string JacketYaml(const JacketCase& c, const std::string& name) {
  ParametrisedModel truth;
  const Modes modes = TruthModes(c, &truth);
  const int joints = (c.model.bays_x + 1) * (c.model.bays_y + 1) * c.model.levels;
  std::vector<std::string> sensors;
  for (int node = 1; node <= joints; ++node)
    for (const char* comp : {":ux", ":uy"})
      sensors.push_back("n" + std::to_string(node) + comp);
  std::mt19937 rng(20261126);
  auto normal = [&rng]() {  // Box-Muller on mt19937's own (portable) output
    const double u1 = (rng() + 1.0) / 4294967297.0, u2 = (rng() + 1.0) / 4294967297.0;
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
  };
  std::ostringstream y;
  y << std::setprecision(10);
  const SpaceFrameSpec& m = c.model;
  y << "name: " << name << "\ndescription: \"Jacket, braces of " << c.damaged.substr(0, 2)
    << " damaged\"\nmodel:\n  type: space_frame\n  bays_x: " << m.bays_x
    << "\n  bays_y: " << m.bays_y << "\n  levels: " << m.levels
    << "\n  level_height: " << m.level_height << "\n  bay_width_x: " << m.bay_width_x
    << "\n  bay_width_y: " << m.bay_width_y
    << "\n  elements_per_member: " << m.elements_per_member
    << "\n  blocks_per_level: " << m.blocks_per_level
    << "\n  bracing: x\n  water_depth: " << m.water_depth
    << "\n  legs: {diameter: 1.2, wall: 0.03}\n  braces: {diameter: 0.6, wall: "
       "0.015}\n  horizontals: {diameter: 0.6, wall: 0.015}\nmeasurements:\n  - state: "
       "test\n    frequencies_hz: [";
  for (int j = 0; j < c.num_modes; ++j)
    y << (j ? ", " : "") << modes.FrequenciesHz()[j] * (1 + 0.002 * normal());
  y << "]\n    sensors: [";
  for (std::size_t i = 0; i < sensors.size(); ++i)
    y << (i ? ", " : "") << '"' << sensors[i] << '"';
  y << "]\n    shapes:\n";
  for (int j = 0; j < c.num_modes; ++j) {
    Eigen::VectorXd s(sensors.size());
    for (std::size_t i = 0; i < sensors.size(); ++i)
      s[static_cast<Eigen::Index>(i)] = modes.shapes(truth.FindDof(sensors[i]), j);
    const double peak = s.cwiseAbs().maxCoeff();
    y << "      - [";
    for (Eigen::Index i = 0; i < s.size(); ++i)
      y << (i ? ", " : "") << (s[i] + 0.02 * peak * normal()) / peak;
    y << "]\n";
  }
  y << "diagnosis:\n  noise: {frequency: 0.002, shape: 0.02}\n";
  return y.str();
}

TEST(JacketExample, DataAreTheTimoshenkoGeneratorsModes) {
  if (const char* path = std::getenv("FEMUP_WRITE_LARGE_JACKET")) {
    std::ofstream(path) << JacketYaml(LargeJacketCase(), "jacket_10560_dof");
  }
  const JacketCase c = SmallJacketCase();
  const std::string example = std::string(FEMUP_EXAMPLES_DIR) + "/diagnosis/jacket.yaml";
  if (const char* path = std::getenv("FEMUP_WRITE_JACKET_EXAMPLE")) {
    std::ifstream in(example);
    std::string header, line;
    while (std::getline(in, line) && line.rfind("#", 0) == 0) header += line + "\n";
    const std::string text = header + JacketYaml(c, "diagnosis_jacket");
    std::ofstream(path) << text;
  }
  const Study study = LoadStudy(example);
  ParametrisedModel truth;
  const Modes modes = TruthModes(c, &truth);
  ASSERT_EQ(study.measurements.size(), 1u);
  const Eigen::VectorXd& hz = study.measurements[0].data.frequencies_hz;
  ASSERT_EQ(hz.size(), c.num_modes);
  for (int j = 0; j < c.num_modes; ++j)
    EXPECT_NEAR(hz[j] / modes.FrequenciesHz()[j], 1.0, 5 * 0.002) << j;
  // The model is the truth's coarser Euler-Bernoulli sibling.
  EXPECT_EQ(study.model.num_dofs(), BuildSpaceFrame(c.model).num_dofs());
}

// With no gap beyond the noise nothing is named: a chain measured as its
// model is (seeds 19 and 32 of the noise, none's chi2 22.3 and 22.0 against
// the noise's 24) where, with gap_explained 0, the most probable family is
// one whose places each fit a little of that noise (attached_mass at P 0.15,
// stiffness_loss at 0.22: every family holds effects too small to tell from
// none). By default none is the verdict, every class explains none of the
// gap, the probabilities are as they were, and the report says why.
TEST(EffectRanking, NamesNoEffectWhereTheMisfitIsWithinTheNoise) {
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  for (const unsigned seed : {19u, 32u}) {
    const std::vector<ModalData> data = {Measured(ShearBuilding(), seed)};
    EffectRankingOptions o = Options();
    const EffectRanking r = RankModelEffects(nominal, data, o);
    o.gap_explained = 0;
    const EffectRanking any = RankModelEffects(nominal, data, o);
    ASSERT_NE(any.classes[0].kind, "none") << seed;
    EXPECT_TRUE(any.gap_within_noise);
    EXPECT_FALSE(any.gap_unexplained);
    // The definition: 4 frequencies and 4 shapes of 6 entries, each shape
    // scaled to fit.
    ASSERT_EQ(r.num_residuals, 28);
    EXPECT_EQ(r.noise_misfit, 28 - 4);
    EXPECT_TRUE(r.gap_within_noise);
    EXPECT_LE(r.nominal_misfit, r.noise_misfit);
    const RankedClass* none = NoneClass(r);
    ASSERT_NE(none, nullptr);
    EXPECT_DOUBLE_EQ(r.nominal_misfit, none->chi2);
    EXPECT_EQ(r.classes[0].kind, "none") << seed;
    EXPECT_TRUE(r.gap_unexplained);
    EXPECT_EQ(r.classes[1].kind + r.classes[1].region,
              any.classes[0].kind + any.classes[0].region);
    EXPECT_EQ(r.kind_probabilities, any.kind_probabilities);
    for (const RankedClass& c : r.classes)
      EXPECT_EQ(c.explained, 0.0) << c.kind << c.region;
    StructureDiagnosisResult report;
    report.study_name = "s";
    report.model_type = "chain";
    report.ranking = r;
    const std::string text = StructureDiagnosisReport(report);
    EXPECT_NE(
        text.find("verdict: no gap beyond the noise: the nominal model's misfit, chi2 "),
        std::string::npos)
        << text;
    EXPECT_NE(text.find("is within the noise's 24.0; the most probable effect, " +
                        any.classes[0].kind + " at " + any.classes[0].region),
              std::string::npos)
        << text;
  }
}

// A gap in a few rows is not taken for noise: storey 3 of the chain 3 %
// softer, the shapes' noise stated at 6 % where the data have 2 % (seed 2), so
// that none's misfit, 18.3, is within the noise's 24 although the frequencies
// are off: the stiffness loss at the storey gains more than 9 (3 noise
// standard deviations) over none and is named, as it explains the gap.
TEST(EffectRanking, NamesAGapInAFewRowsThatTheNoisesSpreadHides) {
  const Structure nominal = BuildSpringMassChain(ShearBuilding());
  ChainSpec damaged = ShearBuilding();
  damaged.springs[2] *= 0.97;
  EffectRankingOptions o = Options();
  o.shape_sigma = 0.06;
  const EffectRanking r = RankModelEffects(nominal, {Measured(damaged, 2)}, o);
  EXPECT_LE(r.nominal_misfit, r.noise_misfit);
  EXPECT_FALSE(r.gap_within_noise);
  EXPECT_FALSE(r.gap_unexplained);
  ASSERT_EQ(r.classes[0].kind + " at " + r.classes[0].region,
            "stiffness_loss at element 3");
  EXPECT_EQ(r.classes[0].explained, 1.0);
  const RankedClass* none = NoneClass(r);
  ASSERT_NE(none, nullptr);
  EXPECT_GE(none->chi2 - r.classes[0].chi2, 9.0);
}

}  // namespace
}  // namespace femup
