// The noise study's parallel run (studies/include/femup/studies/noise_study.h):
// the same numbers, bit for bit, whatever the thread count; progress reports;
// its options checked before any work.
#include "femup/studies/noise_study.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>

#include "femup/core/errors.h"

namespace femup {
namespace {

std::string Example(const std::string& name) {
  return std::string(FEMUP_EXAMPLES_DIR) + "/" + name;
}

// Every field but the solve times, compared exactly (NaN equals NaN).
void ExpectSameNumbers(double a, double b, const std::string& what) {
  if (std::isnan(a) && std::isnan(b)) return;
  EXPECT_EQ(a, b) << what;
}

void ExpectSameVector(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                      const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    ExpectSameNumbers(a[i], b[i], what + "[" + std::to_string(i) + "]");
}

void ExpectIdentical(const NoiseStudyResult& a, const NoiseStudyResult& b) {
  EXPECT_EQ(a.parameter_names, b.parameter_names);
  EXPECT_EQ(a.added_mass_indices, b.added_mass_indices);
  EXPECT_EQ(a.usable_draws, b.usable_draws);
  ASSERT_EQ(a.rm.size(), b.rm.size());
  for (std::size_t l = 0; l < a.rm.size(); ++l) {
    ASSERT_EQ(a.rm[l].size(), b.rm[l].size());
    for (std::size_t k = 0; k < a.rm[l].size(); ++k) {
      const std::string at =
          " level " + std::to_string(l) + " factor " + std::to_string(k);
      ExpectSameNumbers(a.rm[l][k].mean, b.rm[l][k].mean, "mean" + at);
      ExpectSameNumbers(a.rm[l][k].std_dev, b.rm[l][k].std_dev, "std" + at);
      ExpectSameNumbers(a.rm[l][k].median, b.rm[l][k].median, "median" + at);
      ExpectSameNumbers(a.rm[l][k].p90, b.rm[l][k].p90, "p90" + at);
    }
    ExpectSameNumbers(a.rm_average[l], b.rm_average[l], "rm_average");
  }
  EXPECT_EQ(a.figure_level, b.figure_level);
  ExpectSameVector(a.figure_mean, b.figure_mean, "figure_mean");
  ExpectSameVector(a.figure_std, b.figure_std, "figure_std");
  ExpectSameVector(a.figure_first_draw, b.figure_first_draw, "figure_first_draw");
  ASSERT_EQ(a.comparison.size(), b.comparison.size());
  for (std::size_t v = 0; v < a.comparison.size(); ++v) {
    const SolverScores& x = a.comparison[v];
    const SolverScores& y = b.comparison[v];
    EXPECT_EQ(x.label, y.label);
    EXPECT_EQ(x.usable_draws, y.usable_draws) << x.label;
    ASSERT_EQ(x.rm_average.size(), y.rm_average.size());
    for (std::size_t l = 0; l < x.rm_average.size(); ++l) {
      ExpectSameNumbers(x.rm_average[l], y.rm_average[l], x.label + " average");
      ExpectSameNumbers(x.rm_median[l], y.rm_median[l], x.label + " median");
    }
  }
}

TEST(NoiseStudyThreads, OneAndThreeThreadsGiveIdenticalResults) {
  Study study = LoadStudy(Example("paper_chain_noise.yaml"));
  study.noise_study->draws = 7;  // not a multiple of the thread count
  study.noise_study->levels = {0.0, 0.02, 0.05};
  study.noise_study->figure_level = 0.05;
  NoiseRunOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const NoiseStudyResult a = RunNoiseStudy(study, one);
  const NoiseStudyResult b = RunNoiseStudy(study, three);
  ExpectIdentical(a, b);
  EXPECT_GT(a.rm_average[2], a.rm_average[1]);
  // The default (one thread) too.
  ExpectIdentical(a, RunNoiseStudy(study));
}

TEST(NoiseStudyThreads, SolverComparisonIsIdenticalAcrossThreads) {
  // Linear, regularised and nonlinear (Ceres, Ipopt) solvers on the same draws.
  Study study = LoadStudy(Example("paper_chain_solver_comparison.yaml"));
  study.noise_study->draws = 3;
  study.noise_study->levels = {0.002, 0.005};
  NoiseRunOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const NoiseStudyResult a = RunNoiseStudy(study, one);
  const NoiseStudyResult b = RunNoiseStudy(study, three);
  ASSERT_GT(a.comparison.size(), 2u);
  ExpectIdentical(a, b);
}

// The bounded comparison (examples/paper_chain_bounded_comparison.yaml): with
// noise-free data every solver, bounded or not, recovers the preset factors
// (no bound is active there); with noise the bounded fit is usable on every
// draw on Ipopt and beats the plain linear solve on the same draws.
TEST(NoiseStudy, BoundedComparisonRecoversThePresetAndBeatsTheLinearSolve) {
  Study study = LoadStudy(Example("paper_chain_bounded_comparison.yaml"));
  ASSERT_GT(study.lower.size(), 0);
  study.noise_study->draws = 20;
  study.noise_study->levels = {0.0, 0.002};
  study.noise_study->figure_level = 0.002;
  const NoiseStudyResult r = RunNoiseStudy(study);
  ASSERT_EQ(r.comparison.size(), 4u);
  const std::vector<std::string> labels{"linear", "linear-bvls", "sensitivity-ceres",
                                        "sensitivity-ipopt"};
  for (std::size_t v = 0; v < labels.size(); ++v) {
    const SolverScores& c = r.comparison[v];
    EXPECT_EQ(c.label, labels[v]);
    EXPECT_EQ(c.usable_draws[0], 20) << c.label;
    EXPECT_LT(c.rm_average[0], 1e-6) << c.label;  // percent, noise-free
  }
  const SolverScores& linear = r.comparison[0];
  const SolverScores& ipopt = r.comparison[3];
  EXPECT_EQ(ipopt.usable_draws[1], 20);
  EXPECT_LT(ipopt.rm_average[1], linear.rm_average[1]);
}

// Progress comes per chunk of draws (at least one report per level here), and
// the last report counts every draw.
TEST(NoiseStudyThreads, ReportsProgressUpToEveryDraw) {
  Study study = LoadStudy(Example("paper_chain_noise.yaml"));
  study.noise_study->draws = 5;
  study.noise_study->levels = {0.0, 0.01};
  std::atomic<int> calls{0}, largest{0}, bad_total{0};
  NoiseRunOptions options;
  options.threads = 2;
  options.progress = [&](int done, int total) {
    ++calls;
    if (total != 10) ++bad_total;
    int seen = largest.load();
    while (done > seen && !largest.compare_exchange_weak(seen, done)) {
    }
  };
  RunNoiseStudy(study, options);
  EXPECT_GE(calls.load(), 2);
  EXPECT_LE(calls.load(), 10);
  EXPECT_EQ(largest.load(), 10);
  EXPECT_EQ(bad_total.load(), 0);
}

TEST(NoiseStudyThreads, RejectsZeroThreadsNamingTheField) {
  Study study = LoadStudy(Example("paper_chain_noise.yaml"));
  NoiseRunOptions options;
  options.threads = 0;
  EXPECT_NE(options.Validate().ToString().find("threads"), std::string::npos);
  try {
    RunNoiseStudy(study, options);
    FAIL() << "no error for 0 threads";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("threads"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace femup
