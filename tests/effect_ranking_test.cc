// Ranking unmodelled effects on a structure that is not a cantilever: a
// six-storey shear building whose "measured" modes come from a chain built
// directly with the change (the builder, not the effect's code), with noise
// drawn at the stated level from a fixed seed.
#include "femup/studies/effect_ranking.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "femup/builders.h"
#include "femup/errors.h"
#include "femup/modal.h"
#include "femup/studies/structure_diagnosis.h"
#include "scratch_dir.h"

namespace femup {
namespace {

ChainSpec ShearBuilding() {
  ChainSpec spec;
  spec.masses.assign(6, 1e5);
  spec.springs.assign(6, 2e8);
  return spec;
}

// The lowest four modes with shapes at every floor, noise 0.2 % on frequencies
// and 2 % of the largest entry on shapes.
ModalData Measured(const ChainSpec& truth, unsigned seed) {
  const Structure s = BuildSpringMassChain(truth);
  const Modes modes = SolveModes(s.stiffness, s.mass);
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  ModalData d;
  d.state = "air";
  d.frequencies_hz = modes.FrequenciesHz().head(4);
  for (int j = 0; j < 4; ++j) d.frequencies_hz[j] *= 1 + 0.002 * normal(rng);
  d.shapes = modes.shapes.leftCols(4);
  for (int j = 0; j < 4; ++j) {
    const double peak = d.shapes.col(j).cwiseAbs().maxCoeff();
    for (int i = 0; i < 6; ++i) d.shapes(i, j) += 0.02 * peak * normal(rng);
  }
  return d;
}

EffectRankingOptions Options() {
  EffectRankingOptions o;
  o.frequency_sigma = 0.002;
  o.shape_sigma = 0.02;
  return o;
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
  const EffectRanking r = RankModelEffects(BuildSpringMassChain(ShearBuilding()),
                                           {Measured(ShearBuilding(), 3)}, Options());
  EXPECT_EQ(r.kind_probabilities[0].first, "none");
  EXPECT_DOUBLE_EQ(r.temperature, 1.0);
}

TEST(EffectRanking, RefusesBadOptionsAndFamiliesThatDoNotApply) {
  const Structure s = BuildSpringMassChain(ShearBuilding());
  const ModalData d = Measured(ShearBuilding(), 1);
  EffectRankingOptions o = Options();
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

}  // namespace
}  // namespace femup
