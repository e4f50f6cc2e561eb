// The blind benchmark's Bayes oracle (studies/include/femup/studies/
// benchmark_oracle.h): its evidence of "none" against the likelihood at the
// nominal truth mesh, and of material_scaling against a quadrature over the
// generator's size prior (an E error scales every frequency by the same factor
// and leaves the shapes alone, so the truth's frequencies for a drawn shift t
// are the nominal ones times 1 +- t, exactly); options and inputs it refuses.
#include "femup/evaluation/benchmark_oracle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <tuple>
#include <vector>

#include "femup/core/errors.h"
#include "femup/problems/effect_fit.h"

namespace femup {
namespace {

std::string Case(const std::string& name) {
  return std::string(FEMUP_TEST_DATA_DIR) + "/benchmark/" + name + ".yaml";
}

BenchmarkOptions SingleSuite() {
  BenchmarkOptions g;
  g.suite = "single";
  return g;
}

// -2 log likelihood of the study's modes for truth frequencies f and shapes
// at the sensors (any scale, any sign), as the header states it.
double Misfit(const Study& study, const Eigen::VectorXd& f,
              const Eigen::MatrixXd& shapes) {
  const ModalData& md = study.measurements[0].data;
  const double sf = study.diagnosis->frequency_noise, ss = study.diagnosis->shape_noise;
  double chi2 = 0;
  for (int k = 0; k < md.num_modes(); ++k) {
    const double r = (md.frequencies_hz[k] / f[k] - 1) / sf;
    chi2 += r * r + 2 * std::log(f[k] / md.frequencies_hz[k]);
    const Eigen::VectorXd t = shapes.col(k) / shapes.col(k).cwiseAbs().maxCoeff();
    const double plus = (md.shapes.col(k) - t).squaredNorm() / (ss * ss);
    const double minus = (md.shapes.col(k) + t).squaredNorm() / (ss * ss);
    chi2 += -2 * std::log(0.5 * std::exp(-0.5 * plus) + 0.5 * std::exp(-0.5 * minus)) -
            2 * std::log(2.0);
  }
  return chi2;
}

// The nominal truth mesh's modes at the study's sensors (dense solver).
void TruthMesh(const Study& study, Eigen::VectorXd* f, Eigen::MatrixXd* shapes) {
  CantileverSpec fine = *study.cantilever;
  fine.node_heights = UniformHeights(fine.node_heights.back(), 60);
  std::vector<std::string> sensors;
  const ModalData& md = study.measurements[0].data;
  for (int dof : md.sensor_dofs) {
    const std::string& label = study.structure.dof_labels[static_cast<std::size_t>(dof)];
    sensors.push_back("n" + std::to_string(3 * std::stoi(label.substr(1))) + ":ux");
  }
  std::string why;
  ASSERT_TRUE(BendingModesAtSensors(fine, sensors, md.num_modes(), f, shapes, &why))
      << why;
}

const OracleClass& Find(const OracleResult& r, const std::string& label) {
  for (const OracleClass& c : r.classes)
    if (c.label == label) return c;
  throw std::runtime_error("no class " + label);
}

class OracleOnMaterialCases : public ::testing::TestWithParam<const char*> {};

TEST_P(OracleOnMaterialCases, EvidenceMatchesQuadrature) {
  const Study study = LoadStudy(Case(GetParam()));
  Eigen::VectorXd f0;
  Eigen::MatrixXd shapes;
  TruthMesh(study, &f0, &shapes);
  OracleOptions options;
  options.samples = 200;
  options.kinds = {"material_scaling"};
  const OracleResult r = BayesOracle(study, SingleSuite(), options);

  ASSERT_EQ(r.classes.size(), 2u);
  double total = 0;
  for (std::size_t i = 0; i < r.classes.size(); ++i) {
    total += r.classes[i].probability;
    if (i > 0) {
      EXPECT_GE(r.classes[i - 1].probability, r.classes[i].probability);
    }
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_LT(r.affine_error, 1e-5);
  EXPECT_NEAR(Find(r, "none").prior, 1.0 / 6, 1e-15);
  EXPECT_NEAR(Find(r, "material_scaling").prior, 1.0 / 6, 1e-15);

  // "none": the likelihood at the nominal truth mesh (banded against dense
  // eigen-solutions: they agree to ~1e-8 of a frequency).
  EXPECT_NEAR(Find(r, "none").log_evidence, -0.5 * Misfit(study, f0, shapes), 1e-3);

  // material_scaling: sign +-1 (1/2 each), shift at the noise level (0.2,
  // log-uniform 1-5 sigma) or above it (0.8, 5-50 sigma); midpoint rule.
  const double sf = study.diagnosis->frequency_noise;
  const double base = -0.5 * Misfit(study, f0, shapes);
  double z = 0;
  const int n = 4000;
  for (double sign : {-1.0, 1.0})
    for (const auto& [w, lo, hi] :
         {std::tuple{0.2, 1.0, 5.0}, std::tuple{0.8, 5.0, 50.0}})
      for (int i = 0; i < n; ++i) {
        const double t = std::exp(std::log(lo) + (i + 0.5) / n * std::log(hi / lo)) * sf;
        const double log_l = -0.5 * Misfit(study, f0 * (1 + sign * t), shapes);
        z += 0.5 * w / n * std::exp(log_l - base);
      }
  const double quadrature = base + std::log(z);
  const OracleClass& m = Find(r, "material_scaling");
  EXPECT_NEAR(m.log_evidence, quadrature, 3 * m.log_standard_error + 0.02)
      << "standard error " << m.log_standard_error;
  EXPECT_GT(m.log_standard_error, 0);
  EXPECT_LT(m.log_standard_error, 0.2);
  EXPECT_GT(r.evaluations, 4 * 200);
  std::cout << GetParam() << ": material_scaling log evidence " << m.log_evidence
            << " +- " << m.log_standard_error << ", quadrature " << quadrature << "\n";
}

INSTANTIATE_TEST_SUITE_P(Cases, OracleOnMaterialCases,
                         ::testing::Values("single_027", "single_029"));

TEST(BayesOracle, StrongMaterialErrorIsNamed) {
  // single_027: E off by 7.5 noise units of frequency shift; against every
  // class, with the fewest draws allowed.
  OracleOptions options;
  options.samples = 50;
  const OracleResult r =
      BayesOracle(LoadStudy(Case("single_027")), SingleSuite(), options);
  EXPECT_EQ(r.classes.front().label, "material_scaling");
  EXPECT_GT(r.classes.front().probability, 0.5);
}

TEST(BayesOracle, RefusesWhatItDoesNotModel) {
  const Study study = LoadStudy(Case("single_029"));
  BenchmarkOptions mixed = SingleSuite();
  mixed.suite = "mixed";
  try {
    BayesOracle(study, mixed);
    FAIL() << "mixed suite accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("single suite"), std::string::npos) << e.what();
  }
  BenchmarkOptions coarse = SingleSuite();
  coarse.diagnosis_elements = 30;
  try {
    BayesOracle(study, coarse);
    FAIL() << "wrong mesh accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model.elements"), std::string::npos)
        << e.what();
  }
  OracleOptions few;
  few.samples = 10;
  EXPECT_NE(few.Validate().ToString().find("samples"), std::string::npos);
  EXPECT_THROW(BayesOracle(study, SingleSuite(), few), InputError);
  OracleOptions unknown;
  unknown.kinds = {"corrosion"};
  EXPECT_NE(unknown.Validate().ToString().find("'corrosion'"), std::string::npos);
}

TEST(BenchmarkOptions, ValidatesTheOracleSettings) {
  BenchmarkOptions o;
  EXPECT_EQ(o.Validate().ToString(), "");  // mixed suite, oracle off
  o.oracle = "weak";
  EXPECT_NE(o.Validate().ToString().find("single suite"), std::string::npos)
      << o.Validate().ToString();
  o.suite = "single";
  EXPECT_EQ(o.Validate().ToString(), "");
  o.oracle = "all";
  EXPECT_EQ(o.Validate().ToString(), "");
  o.oracle = "maybe";
  EXPECT_EQ(o.Validate().field, "oracle") << o.Validate().ToString();
  o.oracle = "weak";
  o.oracle_samples = 10;
  EXPECT_EQ(o.Validate().field, "oracle_samples") << o.Validate().ToString();
}

}  // namespace
}  // namespace femup
