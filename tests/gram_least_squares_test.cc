// lstsq's Gram route for large compressed problems (solvers/src/
// gram_least_squares.h, LinearSolverOptions::gram_min_unknowns): the same
// answer, covariance and identifiability report as the SVD route on the
// M^-1-weighted correction system of a frame, the preset factors on
// noise-free data, the minimum-norm answer and the null direction when the
// common scaling is left free, and the rank threshold at the Gram matrix's
// rounding. The threshold is lowered to 1 here so that small models take it.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "femup/core/errors.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/linalg/modal.h"
#include "femup/problems/normal_correction_system.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/linear_solver.h"
#include "structure_specs.h"

namespace femup {
namespace {

constexpr int kSvdOnly = std::numeric_limits<int>::max();

LinearSolution Lstsq(const LinearProblem& problem, int gram_min_unknowns) {
  LinearSolverOptions options;
  options.gram_min_unknowns = gram_min_unknowns;
  return CreateLinearSolver("lstsq", options)->Solve(problem);
}

struct Frame {
  ParametrisedModel model;
  Eigen::VectorXd truth;
};

// A two-storey, two-bay plane frame with a wet storey (mass, stiffness and
// added-mass factors), preset factors drawn with a fixed seed.
Frame WetFrame() {
  PlaneFrameSpec spec = fixtures::PlaneFrame(3, 2, 2);
  spec.blocks_per_storey = 2;
  spec.wet_storeys = 1;
  Frame f{BuildPlaneFrame(spec), {}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  f.truth = Eigen::VectorXd(f.model.num_parameters());
  for (Eigen::Index i = 0; i < f.truth.size(); ++i) f.truth[i] = u(rng);
  for (int k : f.model.ParametersOfKind(ParameterKind::kAddedMass)) f.truth[k] = 0.3;
  return f;
}

// The frame's modes in air and in water; with `noise` > 0 each frequency is
// multiplied by 1 + noise * r, r ~ N(0, 1) (fixed seed).
std::vector<ModalData> States(const Frame& f, double noise) {
  std::vector<ModalData> states = {
      PredictModes(f.model, f.truth, Immersion::kDry, 6, "air"),
      PredictModes(f.model, f.truth, Immersion::kWet, 6, "water")};
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  for (ModalData& s : states) {
    for (Eigen::Index i = 0; i < s.frequencies_hz.size(); ++i)
      s.frequencies_hz[i] *= 1 + noise * normal(rng);
  }
  return states;
}

TEST(LstsqGramRoute, PresetFactorsFromNoiseFreeData) {
  const Frame f = WetFrame();
  LinearProblem problem = BuildNormalCorrectionSystem(f.model, States(f, 0));
  problem.fixed = {{0, f.truth[0]}};  // the common scaling
  const LinearSolution s = Lstsq(problem, 1);
  EXPECT_NE(s.summary.message.find("Gram matrix"), std::string::npos)
      << s.summary.message;
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved);
  EXPECT_LT((s.x - f.truth).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(LstsqGramRoute, SameAnswerCovarianceAndReportAsTheSvdOnNoisyData) {
  const Frame f = WetFrame();
  LinearProblem problem = BuildNormalCorrectionSystem(f.model, States(f, 0.01));
  problem.fixed = {{0, f.truth[0]}};
  ASSERT_GT(problem.num_unknowns(), 10);
  const LinearSolution gram = Lstsq(problem, 1);
  const LinearSolution svd = Lstsq(problem, kSvdOnly);
  EXPECT_NE(gram.summary.message.find("Gram matrix"), std::string::npos);
  EXPECT_NE(svd.summary.message.find("by SVD"), std::string::npos);
  EXPECT_EQ(gram.identifiability.rank, svd.identifiability.rank);
  EXPECT_EQ(gram.identifiability.rank, problem.num_unknowns() - 1);
  EXPECT_LT((gram.x - svd.x).norm(), 1e-9 * svd.x.norm());
  ASSERT_EQ(gram.covariance.rows(), svd.covariance.rows());
  EXPECT_GT(svd.covariance.norm(), 0);
  EXPECT_LT((gram.covariance - svd.covariance).norm(), 1e-7 * svd.covariance.norm());
  const Eigen::VectorXd& sg = gram.identifiability.singular_values;
  const Eigen::VectorXd& ss = svd.identifiability.singular_values;
  ASSERT_EQ(sg.size(), ss.size());
  EXPECT_LT((sg - ss).cwiseAbs().maxCoeff(), 1e-7 * ss[0]);
  // The condition numbers agree where they are resolved (below 1/sqrt(eps)).
  EXPECT_NEAR(gram.identifiability.condition_number, svd.identifiability.condition_number,
              1e-5 * svd.identifiability.condition_number);
  EXPECT_NEAR(gram.identifiability.condition_number_unscaled,
              svd.identifiability.condition_number_unscaled,
              1e-5 * svd.identifiability.condition_number_unscaled);
  EXPECT_LT(svd.identifiability.condition_number_unscaled, 1e6);
  EXPECT_LT((gram.standard_error - svd.standard_error).norm(),
            1e-7 * svd.standard_error.norm());
}

// Without a fixed factor, on noise-free data, K and M scaled together change no
// residual: both routes give rank n - 1, the minimum-norm answer and the
// common scaling as the null direction.
TEST(LstsqGramRoute, CommonScalingLeftFreeGivesTheSvdsMinimumNormAndDirection) {
  const Frame f = WetFrame();
  const LinearProblem problem = BuildNormalCorrectionSystem(f.model, States(f, 0));
  const LinearSolution gram = Lstsq(problem, 1);
  const LinearSolution svd = Lstsq(problem, kSvdOnly);
  EXPECT_EQ(gram.summary.status, SolverStatus::kMinimumNorm);
  EXPECT_EQ(svd.summary.status, SolverStatus::kMinimumNorm);
  EXPECT_NE(gram.summary.message.find("Gram matrix"), std::string::npos);
  EXPECT_EQ(gram.identifiability.rank, problem.num_unknowns() - 1);
  EXPECT_EQ(svd.identifiability.rank, gram.identifiability.rank);
  EXPECT_LT((gram.x - svd.x).norm(), 1e-8 * svd.x.norm());
  ASSERT_EQ(gram.identifiability.null_directions.size(), 1u);
  ASSERT_EQ(svd.identifiability.null_directions.size(), 1u);
  const NullDirection& g = gram.identifiability.null_directions[0];
  const NullDirection& s = svd.identifiability.null_directions[0];
  EXPECT_TRUE(g.common_scaling);
  EXPECT_EQ(g.best_to_fix, s.best_to_fix);
  EXPECT_GT(std::abs(g.coefficients.dot(s.coefficients)), 1 - 1e-10);
}

// A compressed matrix with a singular value below sqrt(n eps) s_max: the SVD
// resolves it (its threshold is 1e-10), the Gram route counts it as rounding.
TEST(LstsqGramRoute, RankThresholdIsTheGramMatrixsRounding) {
  const int n = 12;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd x(n, n), y(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) x(i, j) = normal(rng), y(i, j) = normal(rng);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(x).householderQ();
  const Eigen::MatrixXd v = Eigen::HouseholderQR<Eigen::MatrixXd>(y).householderQ();
  Eigen::VectorXd sigma(n);
  for (int i = 0; i < n; ++i) sigma[i] = std::pow(10.0, -0.4 * i);  // 1 ... 4e-5
  sigma[n - 1] = 1e-9;
  LinearProblem problem;
  problem.A = q * sigma.asDiagonal() * v.transpose();
  problem.b = Eigen::VectorXd::Ones(n);
  problem.source_rows = 100;
  LinearSolverOptions options;
  options.scale_columns = false;  // keep sigma as the singular values
  options.gram_min_unknowns = 1;
  const LinearSolution gram = CreateLinearSolver("lstsq", options)->Solve(problem);
  options.gram_min_unknowns = kSvdOnly;
  const LinearSolution svd = CreateLinearSolver("lstsq", options)->Solve(problem);
  EXPECT_EQ(svd.identifiability.rank, n);
  EXPECT_EQ(gram.identifiability.rank, n - 1);
  EXPECT_NEAR(gram.identifiability.tolerance,
              std::sqrt(n * std::numeric_limits<double>::epsilon()), 1e-12);
  EXPECT_TRUE(std::isinf(gram.identifiability.condition_number));
  ASSERT_EQ(gram.identifiability.null_directions.size(), 1u);
  EXPECT_GT(
      std::abs(gram.identifiability.null_directions[0].coefficients.dot(v.col(n - 1))),
      1 - 1e-6);
  for (int i = 0; i < n - 1; ++i)
    EXPECT_NEAR(gram.identifiability.singular_values[i], sigma[i], 1e-12);
  // The minimum-norm answer on the kept directions: V_k S_k^-1 Q_k' b.
  const Eigen::VectorXd kept = v.leftCols(n - 1) *
                               sigma.head(n - 1).cwiseInverse().asDiagonal() *
                               (q.leftCols(n - 1).transpose() * problem.b);
  // 1e-8 as the comparison with the SVD route above: on an AMD EPYC, whose
  // OpenBLAS runs its Zen kernels, the difference is 2.2e-9 of the answer.
  EXPECT_LT((gram.x - kept).norm(), 1e-8 * kept.norm());
}

TEST(LstsqGramRoute, OrdinaryProblemsKeepTheSvd) {
  const Frame f = WetFrame();
  LinearProblem problem = BuildNormalCorrectionSystem(f.model, States(f, 0.01));
  problem.fixed = {{0, f.truth[0]}};
  problem.source_rows = 0;  // as if A were the data themselves
  problem.residual_offset = 0;
  EXPECT_NE(Lstsq(problem, 1).summary.message.find("by SVD"), std::string::npos);
  LinearSolverOptions options;
  options.gram_min_unknowns = 0;
  const Invalid invalid = options.Validate();
  EXPECT_EQ(invalid.field, "gram_min_unknowns");
  EXPECT_THROW(CreateLinearSolver("lstsq", options), InputError);
}

// The identifiability overload that takes the singular values and the
// trailing vectors only reports what the SVD-based one does.
TEST(AnalyseIdentifiability, FromTheSpectrumAndTrailingVectorsSameAnalysis) {
  Eigen::MatrixXd a(5, 4);
  // clang-format off
  a << -2.0,  2.0, 1.0, 0.5,
       -1.0,  1.0, 0.0, 0.2,
        3.0, -3.0, 2.0, 0.1,
        0.5, -0.5, 1.0, 0.0,
        1.0, -1.0, 4.0, 0.3;
  // clang-format on
  const std::vector<std::string> names = {"mass[1]", "stiffness[1]", "added_mass[1]",
                                          "mass[2]"};
  const std::vector<std::string> groups = {"mass", "stiffness", "added_mass", "mass"};
  const Eigen::VectorXd scale = IdentifiabilityScale(a, true);
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(a * scale.cwiseInverse().asDiagonal(),
                                           Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Identifiability full = AnalyseIdentifiability(a, svd, names, groups, 1e-10);
  ASSERT_EQ(full.rank, 3);
  const Identifiability part =
      AnalyseIdentifiability(a, svd.singularValues(), svd.matrixV().rightCols(1),
                             full.condition_number_unscaled, names, groups, 1e-10);
  EXPECT_EQ(part.rank, full.rank);
  EXPECT_EQ(part.singular_values, full.singular_values);
  EXPECT_EQ(part.condition_number_unscaled, full.condition_number_unscaled);
  ASSERT_EQ(part.null_directions.size(), 1u);
  EXPECT_EQ(part.null_directions[0].description, full.null_directions[0].description);
  EXPECT_EQ(part.warnings, full.warnings);
  // Vectors that stop before the rank threshold, sizes that do not fit, a
  // negative condition number: refused by name.
  const Eigen::MatrixXd none(4, 0);
  EXPECT_THROW(
      AnalyseIdentifiability(a, svd.singularValues(), none, 1.0, names, groups, 1e-10),
      InputError);
  EXPECT_THROW(AnalyseIdentifiability(a, svd.singularValues(), svd.matrixV().topRows(3),
                                      1.0, names, groups, 1e-10),
               InputError);
  EXPECT_THROW(AnalyseIdentifiability(a, svd.singularValues(), svd.matrixV(), -1.0, names,
                                      groups, 1e-10),
               InputError);
}

}  // namespace
}  // namespace femup
