// Effects fitted by the one output-error engine (BuildOutputErrorProblem through
// ModelEffectPencil) on a structure that is not a cantilever: a shear building
// (spring-mass chain) whose "measured" modes come from a chain built directly
// with the changed storey (the builder, not the effect's code), and the analytic
// Jacobian against central differences.
#include "femup/problems/model_effect_pencil.h"

#include <gtest/gtest.h>

#include <cmath>

#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/linalg/modal.h"
#include "femup/solvers/nonlinear_solver.h"
#include "structure_specs.h"

namespace femup {
namespace {

// Six storeys of 1e5 kg and 2e8 N/m, storey 1 at the ground.
ChainSpec ShearBuilding() { return fixtures::UniformChain(6, 1e5, 2e8); }

// The lowest `count` modes of `structure`, shapes at `sensors`.
ModalData Measure(const Structure& structure, int count, const std::vector<int>& sensors,
                  Immersion immersion, const std::string& state) {
  const Modes modes = SolveModes(structure.stiffness, structure.mass);
  ModalData d;
  d.state = state;
  d.immersion = immersion;
  d.frequencies_hz = modes.FrequenciesHz().head(count);
  d.sensor_dofs = sensors;
  d.shapes = modes.shapes(sensors, Eigen::seqN(0, count));
  return d;
}

std::shared_ptr<const ModelEffect> Instance(const std::string& kind,
                                            const Structure& structure,
                                            const std::string& region) {
  for (auto& e : CreateModelEffects(kind, structure)) {
    if (e->region().name == region)
      return std::shared_ptr<const ModelEffect>(std::move(e));
  }
  ADD_FAILURE() << kind << " has no region " << region;
  return nullptr;
}

TEST(ModelEffectFit, RecoversAStoreysStiffnessLossOnAShearBuilding) {
  auto nominal = std::make_shared<const Structure>(BuildSpringMassChain(ShearBuilding()));
  ChainSpec damaged = ShearBuilding();
  damaged.springs[2] *= 0.7;  // storey 3 lost 30 %
  const ModalData measured =
      Measure(BuildSpringMassChain(damaged), 4, {1, 3, 5}, Immersion::kDry, "air");
  EigenSensitivityOptions options;
  options.frequency_sigma = 1e-3;
  options.shape_sigma = 0.01;
  NonlinearProblem problem = BuildModelEffectFitProblem(
      nominal, {Instance("stiffness_loss", *nominal, "element 3")}, {measured}, options);
  ASSERT_EQ(problem.names, std::vector<std::string>{"stiffness_loss[element 3].ln_loss"});
  ASSERT_EQ(problem.lower.size(), 1);
  const NonlinearSolution fit = CreateNonlinearSolver("ceres")->Solve(problem);
  ASSERT_TRUE(fit.summary.usable()) << fit.summary.message;
  EXPECT_NEAR(std::exp(fit.x[0]), 0.3, 1e-7);
  EXPECT_LT(fit.residual.norm(), 1e-6);

  // The wrong storey cannot explain the data.
  NonlinearProblem wrong = BuildModelEffectFitProblem(
      nominal, {Instance("stiffness_loss", *nominal, "element 5")}, {measured}, options);
  const NonlinearSolution miss = CreateNonlinearSolver("ceres")->Solve(wrong);
  EXPECT_GT(miss.residual.squaredNorm(), 100.0);
}

TEST(ModelEffectFit, AddedMassFromAirAndWaterWithIpopt) {
  ChainSpec spec = ShearBuilding();
  spec.wet = {true, true, false, false, false, false};
  auto nominal = std::make_shared<const Structure>(BuildSpringMassChain(spec));
  ChainSpec heavier = spec;
  heavier.masses[0] *= 1.25;  // the wet storeys' masses with 25 % added mass
  heavier.masses[1] *= 1.25;
  const std::vector<ModalData> measured = {
      Measure(*nominal, 3, {0, 2, 4, 5}, Immersion::kDry, "air"),
      Measure(BuildSpringMassChain(heavier), 3, {0, 2, 4, 5}, Immersion::kWet, "water")};
  ModelEffectOptions wet_only;
  wet_only.wet_only_added_mass = true;
  auto water = std::shared_ptr<const ModelEffect>(
      CreateModelEffects("added_mass", *nominal, wet_only).front().release());
  NonlinearProblem problem =
      BuildModelEffectFitProblem(nominal, {water}, measured, EigenSensitivityOptions{});
  const NonlinearSolution fit = CreateNonlinearSolver("ipopt")->Solve(problem);
  ASSERT_TRUE(fit.summary.usable()) << fit.summary.message;
  EXPECT_NEAR(std::exp(fit.x[0]), 0.25, 1e-6);
}

TEST(ModelEffectFit, JacobianMatchesCentralDifferences) {
  auto nominal = std::make_shared<const Structure>(BuildSpringMassChain(ShearBuilding()));
  ChainSpec other = ShearBuilding();
  other.masses[5] += 2e4;
  other.springs[0] *= 0.9;
  const ModalData measured =
      Measure(BuildSpringMassChain(other), 3, {0, 2, 3, 5}, Immersion::kDry, "air");
  NonlinearProblem problem =
      BuildModelEffectFitProblem(nominal,
                                 {Instance("attached_mass", *nominal, "node x6"),
                                  Instance("material_scaling", *nominal, "all elements"),
                                  Instance("support_flexibility", *nominal, "supports")},
                                 {measured}, EigenSensitivityOptions{});
  ASSERT_EQ(problem.num_parameters(), 3);
  Eigen::VectorXd x(3);
  x << std::log(0.05), 0.03, std::log(0.2);
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  std::string why;
  ASSERT_TRUE(problem.evaluate(x, &r, &j, &why)) << why;
  for (int p = 0; p < 3; ++p) {
    const double h = 1e-6;
    Eigen::VectorXd up = x, down = x, ru, rd;
    up[p] += h;
    down[p] -= h;
    ASSERT_TRUE(problem.evaluate(up, &ru, nullptr, &why)) << why;
    ASSERT_TRUE(problem.evaluate(down, &rd, nullptr, &why)) << why;
    const Eigen::VectorXd fd = (ru - rd) / (2 * h);
    EXPECT_LT((j.col(p) - fd).norm(), 1e-5 * std::max(1.0, fd.norm()))
        << "parameter " << p;
  }
}

// What a fit predicts, mode by mode, read back from its residuals
// (PairedModeMisfits), against a direct solve of the changed chain: the paired
// frequencies and the MAC of each model shape with the measured one at the
// sensors; a state without shapes has frequencies alone. With the "entry"
// shape noise and the "unit" scaling as well.
TEST(ModelEffectFit, PairedModeMisfitsMatchADirectSolve) {
  auto nominal = std::make_shared<const Structure>(BuildSpringMassChain(ShearBuilding()));
  ChainSpec other = ShearBuilding();
  other.masses[4] += 3e4;
  other.springs[1] *= 0.8;
  const Structure truth = BuildSpringMassChain(other);
  const std::vector<int> sensors = {0, 2, 3, 5};
  ModalData frequencies_only = Measure(truth, 2, sensors, Immersion::kDry, "b");
  frequencies_only.sensor_dofs.clear();
  frequencies_only.shapes.resize(0, 0);
  const std::vector<ModalData> measured = {
      Measure(truth, 3, sensors, Immersion::kDry, "a"), frequencies_only};
  const auto effect = Instance("stiffness_loss", *nominal, "element 2");
  ModelEffectPencil pencil(nominal, {effect});
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, std::log(0.15));
  SparseMatrix k, m;
  pencil.Assemble(x, false, &k, &m);
  const Modes direct = SolveModes(k, m);
  for (const std::string noise : {"max", "entry"}) {
    EigenSensitivityOptions options;
    options.shape_noise = noise;
    options.shape_scaling = noise == "max" ? "fit" : "unit";
    NonlinearProblem problem =
        BuildModelEffectFitProblem(nominal, {effect}, measured, options);
    Eigen::VectorXd r;
    std::string why;
    ASSERT_TRUE(problem.evaluate(x, &r, nullptr, &why)) << why;
    const std::vector<PairedModeMisfit> got = PairedModeMisfits(measured, options, r);
    ASSERT_EQ(got.size(), 5u);
    for (const PairedModeMisfit& p : got) {
      const ModalData& d = measured[static_cast<std::size_t>(p.state)];
      EXPECT_EQ(p.measured_hz, d.frequencies_hz[p.mode]);
      EXPECT_NEAR(p.model_hz / direct.FrequenciesHz()[p.mode], 1.0, 1e-12) << noise;
      if (!d.HasShapes()) {
        EXPECT_TRUE(std::isnan(p.mac));
        continue;
      }
      const Eigen::VectorXd s = direct.shapes.col(p.mode)(sensors);
      const Eigen::VectorXd t = d.shapes.col(p.mode);
      const double mac = std::pow(s.dot(t), 2) / (s.squaredNorm() * t.squaredNorm());
      EXPECT_NEAR(p.mac, mac, 1e-10) << noise << " mode " << p.mode;
      EXPECT_LT(p.mac, 1.0);
    }
  }
  EXPECT_THROW(
      PairedModeMisfits(measured, EigenSensitivityOptions{}, Eigen::VectorXd::Zero(4)),
      InputError);
}

TEST(ModelEffectFit, RefusesNoEffectAndAWrongSize) {
  auto nominal = std::make_shared<const Structure>(BuildSpringMassChain(ShearBuilding()));
  EXPECT_THROW(ModelEffectPencil(nominal, {}), InputError);
  ModelEffectPencil pencil(nominal, {Instance("stiffness_loss", *nominal, "element 1")});
  SparseMatrix k, m;
  EXPECT_THROW(pencil.Assemble(Eigen::VectorXd::Zero(2), false, &k, &m), InputError);
  // A problem's evaluation reports it rather than throwing.
  const ModalData measured = Measure(*nominal, 2, {0, 1}, Immersion::kDry, "air");
  NonlinearProblem problem = BuildModelEffectFitProblem(
      nominal, {Instance("stiffness_loss", *nominal, "element 1")}, {measured}, {});
  Eigen::VectorXd r;
  std::string why;
  EXPECT_FALSE(problem.evaluate(Eigen::VectorXd::Zero(2), &r, nullptr, &why));
  EXPECT_FALSE(why.empty());
}

}  // namespace
}  // namespace femup
