// The named steps of RankModelEffects (effect_ranking_steps.h) on their own:
// the held-out modes' flags, the noise temperatures from the best fit, and
// the ranked classes' order. The whole ranking is tested in
// effect_ranking_test.cc.
#include "effect_ranking_steps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "expect_error.h"

namespace femup::effect_ranking_steps {
namespace {

ModalData Modes(int n) {
  ModalData d;
  d.frequencies_hz = Eigen::VectorXd::LinSpaced(n, 1.0, static_cast<double>(n));
  return d;
}

TEST(HeldOutModes, FlagsTheNamedModesOfEachState) {
  const std::vector<ModalData> states = {Modes(3), Modes(2)};
  const auto held = HeldOutModes(states, {{0, 2}, {1, 0}});
  ASSERT_EQ(held.size(), 2u);
  EXPECT_EQ(held[0], (std::vector<char>{0, 0, 1}));
  EXPECT_EQ(held[1], (std::vector<char>{1, 0}));
  const auto none = HeldOutModes(states, {});
  EXPECT_EQ(none[0], (std::vector<char>{0, 0, 0}));
  EXPECT_EQ(none[1], (std::vector<char>{0, 0}));
}

TEST(HeldOutModes, NamesAModeNotMeasuredAndRefusesToHoldOutEveryMode) {
  const std::vector<ModalData> states = {Modes(2)};
  testing::ExpectInputError(
      [&] {
        HeldOutModes(states, {{0, 2}});
      },
      {"diagnosis.held_out", "state 1 mode 3", "not measured"});
  testing::ExpectInputError(
      [&] {
        HeldOutModes(states, {{1, 0}});
      },
      {"diagnosis.held_out", "state 2 mode 1"});
  testing::ExpectInputError(
      [&] {
        HeldOutModes(states, {{0, 0}, {0, 1}});
      },
      {"diagnosis.held_out", "every measured mode"});
}

// Two degrees of freedom make the chi2 tail exp(-chi2 / 2): the p-values and
// hence the temperatures can be written out. Rows 0-2 are frequencies (one
// parameter fitted: 2 degrees of freedom), rows 3-6 the entries of two shape
// modes (less one scale each: 2 degrees of freedom).
TEST(NoiseTemperaturesOf, ScalesOnlyAnImprobableChi2ByItsDegreesOfFreedom) {
  const std::vector<char> is_frequency = {1, 1, 1, 0, 0, 0, 0};
  Eigen::VectorXd r(7);
  r << 3, 2, 1, 0.5, 0.5, 0.5, 0.5;  // chi2_f 14, chi2_s 1
  const NoiseTemperatures t = NoiseTemperaturesOf(r, 1, is_frequency, 2);
  EXPECT_EQ(t.num_frequencies, 3);
  // p_f = exp(-7) < 0.01: 14 / 2; p_s = exp(-0.5) > 0.01: 1.
  EXPECT_DOUBLE_EQ(t.frequency, 7.0);
  EXPECT_DOUBLE_EQ(t.shape, 1.0);
  // The whole residual: 7 rows less 2 shape scales less 1 parameter = 4
  // degrees of freedom, Q(2, x) = (1 + x) exp(-x) at x = chi2 / 2 = 7.5.
  EXPECT_NEAR(t.best_chi2_p_value, (1 + 7.5) * std::exp(-7.5), 1e-15);

  // Shapes that misfit and frequencies that fit.
  r << 0.1, 0.1, 0.1, 3, 2, 1, 1;  // chi2_s 15
  const NoiseTemperatures s = NoiseTemperaturesOf(r, 1, is_frequency, 2);
  EXPECT_DOUBLE_EQ(s.frequency, 1.0);
  EXPECT_DOUBLE_EQ(s.shape, 7.5);
  // Frequencies only: no shape row, shape temperature 1.
  const NoiseTemperatures f =
      NoiseTemperaturesOf(Eigen::Vector3d(3, 2, 1), 1, {1, 1, 1}, 0);
  EXPECT_DOUBLE_EQ(f.frequency, 7.0);
  EXPECT_DOUBLE_EQ(f.shape, 1.0);
}

RankedClass Class(const std::string& kind, double p, double explained = 1,
                  bool fitted = true) {
  RankedClass c;
  c.kind = kind;
  c.region = kind == "none" ? "" : "e" + std::to_string(static_cast<int>(100 * p));
  c.probability = p;
  c.explained = explained;
  c.fitted = fitted;
  return c;
}

// The family first, then the place: a family of two places at 0.3 each
// outranks a single class at 0.4.
TEST(PutInOrder, RanksFamiliesBeforePlacesAndFittedBeforeScreened) {
  const std::vector<RankedClass> classes = {
      Class("none", 0.0), Class("attached_mass", 0.4), Class("stiffness_loss", 0.25),
      Class("stiffness_loss", 0.3, 1, false), Class("stiffness_loss", 0.05)};
  const std::map<std::string, double> by_kind = {
      {"none", 0.0}, {"attached_mass", 0.4}, {"stiffness_loss", 0.6}};
  EffectRanking out;
  PutInOrder(classes, by_kind, EffectRankingOptions{}, &out);
  ASSERT_EQ(out.classes.size(), 5u);
  EXPECT_EQ(out.classes[0].kind, "stiffness_loss");
  EXPECT_TRUE(out.classes[0].fitted);
  EXPECT_DOUBLE_EQ(out.classes[0].probability, 0.25);
  EXPECT_DOUBLE_EQ(out.classes[1].probability, 0.05);
  EXPECT_FALSE(out.classes[2].fitted);  // screened, after every fitted place
  EXPECT_EQ(out.classes[3].kind, "attached_mass");
  EXPECT_EQ(out.classes[4].kind, "none");
  EXPECT_DOUBLE_EQ(out.gap_probability, 1.0);
  EXPECT_FALSE(out.gap_below_confidence);
  EXPECT_FALSE(out.gap_unexplained);
  // The screened place more probable than every fitted one is said.
  ASSERT_EQ(out.notes.size(), 1u);
  EXPECT_NE(out.notes[0].find("1 screened, unfitted places of stiffness_loss"),
            std::string::npos)
      << out.notes[0];
  ASSERT_EQ(out.kind_probabilities.size(), 3u);
  EXPECT_EQ(out.kind_probabilities[0].first, "stiffness_loss");
}

TEST(PutInOrder, PutsNoneFirstBelowTheConfidenceOrWhereTheGapIsUnexplained) {
  const std::vector<RankedClass> classes = {Class("none", 0.2),
                                            Class("attached_mass", 0.8, 0.9)};
  const std::map<std::string, double> by_kind = {{"none", 0.2}, {"attached_mass", 0.8}};
  EffectRankingOptions options;
  options.gap_confidence = 0.9;  // 0.8 is below it
  EffectRanking below;
  PutInOrder(classes, by_kind, options, &below);
  EXPECT_EQ(below.classes.front().kind, "none");
  EXPECT_NEAR(below.gap_probability, 0.8, 1e-15);
  EXPECT_TRUE(below.gap_below_confidence);

  options.gap_confidence = 0;
  EffectRanking named;
  PutInOrder(classes, by_kind, options, &named);
  EXPECT_EQ(named.classes.front().kind, "attached_mass");

  // An effect that explains 0.2 of the gap (below gap_explained, 1/3).
  EffectRanking unexplained;
  PutInOrder({Class("none", 0.2), Class("attached_mass", 0.8, 0.2)}, by_kind, options,
             &unexplained);
  EXPECT_EQ(unexplained.classes.front().kind, "none");
  EXPECT_TRUE(unexplained.gap_unexplained);
  EXPECT_FALSE(unexplained.gap_below_confidence);
}

}  // namespace
}  // namespace femup::effect_ranking_steps
