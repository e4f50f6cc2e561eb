// Two effects at once (model_effect_pair.h): a beam's water and material error
// together against their closed form (every bending eigenvalue times
// s / (1 + r)), derivatives against central differences, and what the pair
// says and refuses.
#include "femup/problems/model_effect_pair.h"

#include <gtest/gtest.h>

#include <cmath>

#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/linalg/modal.h"
#include "paper_beam.h"
#include "structure_specs.h"
#include "vector_of.h"

namespace femup {
namespace {

std::shared_ptr<const ModelEffect> First(const std::string& kind, const Structure& s,
                                         const ModelEffectOptions& options = {}) {
  auto all = CreateModelEffects(kind, s, options);
  EXPECT_FALSE(all.empty()) << kind;
  return all.empty() ? nullptr : std::shared_ptr<const ModelEffect>(std::move(all[0]));
}

Structure Beam() {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 10));
  spec.support_rotation = 4e5;
  spec.support_transverse = 5e7;
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  return BuildCantilever(spec);
}

// Water over the whole bar (transverse mass r times the bar's, on bending
// modes (1 + r) times their mass) and E times s: every bending eigenvalue
// times s / (1 + r) in water and s in air, where the water acts in wet
// states only.
TEST(ModelEffectPair, WaterAndAMaterialErrorScaleABeamsModesAsTheirClosedForm) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 10));
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  const Structure s = BuildCantilever(spec);
  ModelEffectOptions wet_only;
  wet_only.wet_only_added_mass = true;
  const auto pair =
      PairOfModelEffects(First("added_mass", s, wet_only), First("material_scaling", s));
  ASSERT_EQ(pair->Parameters().size(), 3u);  // ratio, level, E factor
  const double r = 0.8, factor = 0.95;
  const Eigen::VectorXd theta = fixtures::VectorOf({std::log(r), 2.0, std::log(factor)});
  const Eigen::VectorXd before = SolveModes(s.stiffness, s.mass).eigenvalues;
  for (const Immersion state : {Immersion::kWet, Immersion::kDry}) {
    SparseMatrix k, m;
    ApplyModelEffects(s, {pair.get()}, {theta}, state, &k, &m);
    const Eigen::VectorXd after = SolveModes(k, m).eigenvalues;
    const double expected = state == Immersion::kWet ? factor / (1 + r) : factor;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(after[i] / before[i], expected, 1e-9) << i;
  }
}

TEST(ModelEffectPair, DerivativesMatchCentralDifferences) {
  const Structure s = Beam();
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"added_mass", "attached_mass"}, {"support_flexibility", "stiffness_loss"}};
  for (const auto& [a, b] : pairs) {
    const auto pair = PairOfModelEffects(First(a, s), First(b, s));
    const auto params = pair->Parameters();
    Eigen::VectorXd theta(static_cast<Eigen::Index>(params.size()));
    for (std::size_t i = 0; i < params.size(); ++i)
      theta[static_cast<Eigen::Index>(i)] =
          params[i].lower + 0.37 * (params[i].upper - params[i].lower);
    for (int i = 0; i < theta.size(); ++i) {
      const std::size_t p = static_cast<std::size_t>(i);
      const double h = 1e-6 * (params[p].upper - params[p].lower);
      Eigen::VectorXd up = theta, down = theta;
      up[i] += h;
      down[i] -= h;
      const ModelChange d = pair->Derivative(theta, i, Immersion::kWet);
      const ModelChange x = pair->Change(up, Immersion::kWet);
      const ModelChange y = pair->Change(down, Immersion::kWet);
      // An empty matrix is a change of zero.
      auto dense = [&](const SparseMatrix& q) {
        return q.size() == 0
                   ? Eigen::MatrixXd::Zero(s.stiffness.rows(), s.stiffness.cols())
                   : Eigen::MatrixXd(q);
      };
      for (const bool stiffness : {true, false}) {
        const Eigen::MatrixXd fd = (dense(stiffness ? x.stiffness : x.mass) -
                                    dense(stiffness ? y.stiffness : y.mass)) /
                                   (2 * h);
        const Eigen::MatrixXd an = dense(stiffness ? d.stiffness : d.mass);
        const double scale = std::max(fd.cwiseAbs().maxCoeff(), an.cwiseAbs().maxCoeff());
        if (scale == 0) continue;
        EXPECT_LT((an - fd).cwiseAbs().maxCoeff() / scale, 1e-6)
            << a << "+" << b << (stiffness ? " stiffness" : " mass") << " parameter "
            << i;
      }
    }
  }
}

TEST(ModelEffectPair, SaysWhatBothSay) {
  const Structure s = Beam();
  const auto water = First("added_mass", s);
  const auto mass = First("attached_mass", s);
  // Each one's first start, joined.
  const Eigen::VectorXd w0 = water->Starts()[0], m0 = mass->Starts()[0];
  const Eigen::Index nw = w0.size(), nm = m0.size();
  Eigen::VectorXd from(nw + nm);
  from << w0 * 0.5, m0 * 0.5;
  const auto pair = PairOfModelEffects(water, mass, {from});
  EXPECT_EQ(pair->kind(), "added_mass+attached_mass");
  EXPECT_EQ(pair->region().name, water->region().name + " + " + mass->region().name);
  std::vector<std::string> names;
  for (const EffectParameter& p : pair->Parameters()) names.push_back(p.name);
  std::vector<std::string> expected;
  for (const auto& e : {water, mass})
    for (const EffectParameter& p : e->Parameters()) expected.push_back(p.name);
  EXPECT_EQ(names, expected);
  ASSERT_EQ(static_cast<Eigen::Index>(names.size()), from.size());
  // The stated start first, then each of the first's starts beside the
  // second's first, then the first's first beside each of the second's others.
  const auto starts = pair->Starts();
  ASSERT_EQ(starts.size(), 1 + water->Starts().size() + mass->Starts().size() - 1);
  EXPECT_EQ(starts[0], from);
  EXPECT_EQ(starts[1], (Eigen::VectorXd(nw + nm) << w0, m0).finished());
  const auto magnitudes = pair->Magnitudes(from);
  const auto mw = water->Magnitudes(from.head(nw)), mm = mass->Magnitudes(from.tail(nm));
  ASSERT_EQ(magnitudes.size(), mw.size() + mm.size());
  EXPECT_EQ(magnitudes.front().name, mw.front().name);
  EXPECT_EQ(magnitudes.back().name, mm.back().name);
  EXPECT_EQ(magnitudes.back().value, mm.back().value);
  EXPECT_EQ(pair->Location(from).depth, water->Location(from.head(nw)).depth);
}

// Two places of one family: a shear building's second and fifth storeys
// softened by 10 % and 20 % are the chain built with those springs, and the
// pair's parameters are its two places' in order.
TEST(ModelEffectPair, TwoStoreysOfOneChainAreTheChainWithBothSpringsSoftened) {
  const ChainSpec spec = fixtures::UniformChain(6, 1e5, 2e8);
  const Structure s = BuildSpringMassChain(spec);
  std::vector<std::shared_ptr<const ModelEffect>> storeys;
  for (auto& e : CreateModelEffects("stiffness_loss", s, {}))
    storeys.push_back(std::move(e));
  ASSERT_EQ(storeys.size(), 6u);
  const auto pair = PairOfModelEffects(storeys[1], storeys[4]);
  EXPECT_EQ(pair->kind(), "stiffness_loss+stiffness_loss");
  EXPECT_EQ(pair->region().name,
            storeys[1]->region().name + " + " + storeys[4]->region().name);
  EXPECT_EQ(pair->region().elements, (std::vector<int>{1, 4}));
  const Eigen::VectorXd theta = fixtures::VectorOf({std::log(0.1), std::log(0.2)});
  SparseMatrix k, m;
  ApplyModelEffects(s, {pair.get()}, {theta}, Immersion::kDry, &k, &m);
  ChainSpec softened = spec;
  softened.springs[1] *= 0.9;
  softened.springs[4] *= 0.8;
  const Structure truth = BuildSpringMassChain(softened);
  const Eigen::VectorXd expected = SolveModes(truth.stiffness, truth.mass).eigenvalues;
  const Eigen::VectorXd after = SolveModes(k, m).eigenvalues;
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(after[i] / expected[i], 1.0, 1e-10) << i;
  const auto magnitudes = pair->Magnitudes(theta);
  ASSERT_EQ(magnitudes.size(), 2u);
  EXPECT_NEAR(magnitudes[0].value, 0.1, 1e-12);
  EXPECT_NEAR(magnitudes[1].value, 0.2, 1e-12);
  EXPECT_TRUE(RegionsOverlap(storeys[1]->region(), storeys[1]->region()));
  EXPECT_FALSE(RegionsOverlap(storeys[1]->region(), storeys[2]->region()));
  testing::ExpectInputError([&] { PairOfModelEffects(storeys[3], storeys[3]); },
                            {"pair", "stiffness_loss", "share an element or a DOF"});
}

TEST(ModelEffectPair, RefusesWhatIsNotAPair) {
  const Structure s = Beam();
  const auto water = First("added_mass", s);
  testing::ExpectInputError([&] { PairOfModelEffects(water, nullptr); }, {"pair"});
  testing::ExpectInputError([&] { PairOfModelEffects(water, First("added_mass", s)); },
                            {"pair", "added_mass", "share an element or a DOF"});
  testing::ExpectInputError(
      [&] {
        PairOfModelEffects(water, First("material_scaling", s),
                           {fixtures::VectorOf({0.0})});
      },
      {"pair", "start 0 has 1 entries", "3 parameters"});
}

}  // namespace
}  // namespace femup
