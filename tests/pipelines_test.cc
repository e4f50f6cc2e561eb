// The study pipelines on the bundled examples: the paper's section-4 figures,
// checked against method.md's values, and the noise study's reproducibility.
#include <gtest/gtest.h>

#include <filesystem>

#include "femup/problems/paper_chain.h"
#include "femup/reporting/output_dir.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/modes_study.h"
#include "femup/studies/noise_study.h"
#include "femup/studies/update_study.h"

namespace femup {
namespace {

std::string Example(const std::string& name) {
  return std::string(FEMUP_EXAMPLES_DIR) + "/" + name;
}

TEST(UpdatePipeline, PaperFig2BothForms) {
  for (const char* file :
       {"paper_chain_masses_1-3_wet.yaml", "paper_chain_masses_1-3_wet_stacked.yaml"}) {
    const Study study = LoadStudy(Example(file));
    const UpdateResult r = RunUpdate(study);
    EXPECT_EQ(r.problem.num_rows(), 20) << file;
    EXPECT_EQ(r.problem.num_unknowns(), 13);
    EXPECT_EQ(r.identifiability_unconstrained.rank, 12);
    ASSERT_EQ(r.identifiability_unconstrained.null_directions.size(), 1u);
    EXPECT_TRUE(r.identifiability_unconstrained.null_directions[0].common_scaling);
    EXPECT_EQ(r.solution.summary.status, SolverStatus::kSolved);
    for (int i = 0; i < 13; ++i) {
      EXPECT_NEAR(r.solution.x[i], (*study.truth)[i], 1e-10) << r.parameters[i].name;
    }
    // The updated model reproduces the measured frequencies and shapes.
    for (const auto& st : r.states) {
      for (Eigen::Index k = 0; k < st.measured_hz.size(); ++k) {
        EXPECT_NEAR(st.updated_hz[k], st.measured_hz[k], 1e-8 * st.measured_hz[k]);
        EXPECT_NEAR(st.updated_mac[k], 1.0, 1e-12);
      }
    }
  }
}

TEST(UpdatePipeline, PaperFig3SecondScenario) {
  const Study study = LoadStudy(Example("paper_chain_masses_1-2_wet.yaml"));
  const UpdateResult r = RunUpdate(study);
  EXPECT_EQ(r.problem.num_unknowns(), 12);
  EXPECT_EQ(r.identifiability_unconstrained.rank, 11);
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(r.solution.x[i], (*study.truth)[i], 1e-10);
}

TEST(UpdatePipeline, UnconstrainedReportsTheNullSpace) {
  const Study study = LoadStudy(Example("paper_chain_masses_1-3_wet_unconstrained.yaml"));
  const UpdateResult r = RunUpdate(study);
  EXPECT_EQ(r.solution.summary.status, SolverStatus::kMinimumNorm);
  EXPECT_NE(r.solution.summary.message.find("common scaling"), std::string::npos);
  // The minimum-norm answer differs from the preset along the null direction
  // only: the residual is still zero.
  EXPECT_LT(r.solution.residual.norm(), 1e-9 * r.problem.b.norm());
}

TEST(UpdatePipeline, CantileverAddedMassOnly) {
  const Study study = LoadStudy(Example("cantilever_model_a.yaml"));
  const UpdateResult r = RunUpdate(study);
  EXPECT_EQ(r.num_dofs, 30);
  EXPECT_EQ(r.parameters.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(r.solution.x[i], 0.12, 1e-8);
}

TEST(UpdatePipeline, WritesEverythingOrNothing) {
  const std::string dir = ::testing::TempDir() + "/femup_pipeline_out";
  std::filesystem::remove_all(dir);
  const Study study = LoadStudy(Example("paper_chain_masses_1-3_wet.yaml"));
  const UpdateResult r = RunUpdate(study);
  {
    OutputDir out(dir);
    std::vector<std::string> warnings;
    WriteUpdateOutputs(r, false, &out, &warnings);
    // Not committed: nothing may be visible, not even the folder it created.
  }
  EXPECT_FALSE(std::filesystem::exists(dir));
  OutputDir out(dir);
  std::vector<std::string> warnings;
  WriteUpdateOutputs(r, false, &out, &warnings);
  out.Commit();
  EXPECT_TRUE(std::filesystem::exists(dir + "/result.json"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/added_mass.mtx"));
}

TEST(NoisePipeline, ZeroNoiseIsExactAndSeedsReproduce) {
  Study study = LoadStudy(Example("paper_chain_noise.yaml"));
  study.noise_study->draws = 40;
  study.noise_study->levels = {0.0, 0.01, 0.05};
  const NoiseStudyResult a = RunNoiseStudy(study);
  for (const auto& s : a.rm[0]) EXPECT_LT(s.mean, 1e-8);
  // Rm grows with the corruption level, for every factor.
  for (std::size_t k = 0; k < a.added_mass_indices.size(); ++k) {
    EXPECT_GT(a.rm[1][k].mean, 0.1);
    EXPECT_GT(a.rm[2][k].mean, a.rm[1][k].mean);
  }
  const NoiseStudyResult b = RunNoiseStudy(study);
  EXPECT_EQ(a.rm[2][0].mean, b.rm[2][0].mean);  // same seed, same numbers
  study.noise_study->seed += 1;
  const NoiseStudyResult c = RunNoiseStudy(study);
  EXPECT_NE(a.rm[2][0].mean, c.rm[2][0].mean);
}

TEST(ModesPipeline, PaperFemFrequenciesAndChecks) {
  const Study study = LoadStudy(Example("paper_chain_masses_1-3_wet.yaml"));
  const ModesResult r = RunModes(study, 0);
  const double expected[5] = {34.50, 100.70, 158.75, 203.93, 232.60};
  for (int i = 0; i < 5; ++i)
    EXPECT_NEAR(r.nominal.FrequenciesHz()[i], expected[i], 0.005);
  EXPECT_LT(r.max_residual, 1e-12);
  EXPECT_LT(r.max_orthogonality_error, 1e-12);
}

}  // namespace
}  // namespace femup
