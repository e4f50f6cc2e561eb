// Every linear solver on one shared problem suite (solvers/include/femup/
// solvers/linear_solver.h), each against an independent reference: normal or
// KKT equations solved in long double, a brute-force enumeration of active sets
// for bounded problems, and the paper's preset factors.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
#include "femup/evaluation/nist_strd.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/paper_chain.h"
#include "femup/solvers/linear_solver.h"
#include "solver_problems.h"

namespace femup {
namespace {

using MatrixLd = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
using VectorLd = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::MatrixXd Random(int rows, int cols, unsigned seed) {
  return fixtures::RandomGaussian(rows, cols, seed);
}

// The correction system of the paper's chain from the modes 1-2 of its preset
// factors in air and in water; no factor fixed.
LinearProblem PaperChainSystem(const PaperChainScenario& sc) {
  const Modes fem = SolveModes(sc.model.stiffness(), sc.model.mass());
  const std::vector<ModalData> states = {
      PredictModes(sc.model, sc.preset, Immersion::kDry, 2, "air"),
      PredictModes(sc.model, sc.preset, Immersion::kWet, 2, "water")};
  return BuildCorrectionSystem(sc.model, fem, states, {});
}

// min ||A x - b|| s.t. C x = d by the KKT system in long double.
Eigen::VectorXd KktReference(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                             const Eigen::MatrixXd& c, const Eigen::VectorXd& d) {
  const int n = static_cast<int>(a.cols()), q = static_cast<int>(c.rows());
  MatrixLd k = MatrixLd::Zero(n + q, n + q);
  const MatrixLd al = a.cast<long double>(), cl = c.cast<long double>();
  k.topLeftCorner(n, n) = al.transpose() * al;
  k.topRightCorner(n, q) = cl.transpose();
  k.bottomLeftCorner(q, n) = cl;
  VectorLd rhs(n + q);
  rhs.head(n) = al.transpose() * b.cast<long double>();
  rhs.tail(q) = d.cast<long double>();
  return Eigen::FullPivLU<MatrixLd>(k).solve(rhs).head(n).cast<double>();
}

// Bounded least squares by enumerating every assignment of each unknown to its
// lower bound, its upper bound or free (3^n least-squares solves, long double):
// the feasible candidate with the least cost. Independent of any active-set logic.
Eigen::VectorXd BruteForceBounded(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                  const Eigen::VectorXd& l, const Eigen::VectorXd& u) {
  const int n = static_cast<int>(a.cols());
  int combos = 1;
  for (int j = 0; j < n; ++j) combos *= 3;
  Eigen::VectorXd best;
  long double best_cost = std::numeric_limits<long double>::infinity();
  for (int c = 0; c < combos; ++c) {
    std::vector<int> state(n);
    int code = c;
    bool ok = true;
    for (int j = 0; j < n; ++j) {
      state[j] = code % 3 - 1;  // -1 lower, 0 free, 1 upper
      code /= 3;
      if ((state[j] < 0 && !std::isfinite(l[j])) ||
          (state[j] > 0 && !std::isfinite(u[j])))
        ok = false;
    }
    if (!ok) continue;
    VectorLd x = VectorLd::Zero(n);
    std::vector<int> free;
    for (int j = 0; j < n; ++j) {
      if (state[j] < 0) x[j] = l[j];
      if (state[j] > 0) x[j] = u[j];
      if (state[j] == 0) free.push_back(j);
    }
    const MatrixLd al = a.cast<long double>();
    VectorLd rhs = b.cast<long double>() - al * x;
    if (!free.empty()) {
      MatrixLd af(a.rows(), free.size());
      for (std::size_t k = 0; k < free.size(); ++k) af.col(k) = al.col(free[k]);
      const VectorLd xf = (af.transpose() * af).ldlt().solve(af.transpose() * rhs);
      for (std::size_t k = 0; k < free.size(); ++k) x[free[k]] = xf[k];
    }
    bool feasible = true;
    for (int j = 0; j < n; ++j) {
      if (x[j] < l[j] - 1e-12L || x[j] > u[j] + 1e-12L) feasible = false;
    }
    if (!feasible) continue;
    const long double cost = (al * x - b.cast<long double>()).squaredNorm();
    if (cost < best_cost) best_cost = cost, best = x.cast<double>();
  }
  return best;
}

LinearProblem Make(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  return fixtures::NamedProblem(a, b);
}

LinearSolverOptions Unregularised(const std::string& name) {
  LinearSolverOptions o;
  if (name == "tikhonov") {
    o.regularisation.parameter_choice = "fixed";
    o.regularisation.lambda = 0.0;
  }
  if (name == "tsvd") o.truncation = 1000;  // all singular values
  return o;
}

class EverySolver : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<LinearSolver> Solver() const {
    return CreateLinearSolver(GetParam(), Unregularised(GetParam()));
  }
};

TEST_P(EverySolver, OverdeterminedMatchesNormalEquations) {
  const LinearProblem p = Make(Random(40, 6, 11), Random(40, 1, 12));
  const LinearSolution s = Solver()->Solve(p);
  ASSERT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  const Eigen::VectorXd ref =
      KktReference(p.A, p.b, Eigen::MatrixXd(0, 6), Eigen::VectorXd());
  EXPECT_LT((s.x - ref).cwiseAbs().maxCoeff(), 1e-8 * ref.cwiseAbs().maxCoeff());
  EXPECT_NEAR(s.summary.cost, 0.5 * (p.A * ref - p.b).squaredNorm(), 1e-10);
}

TEST_P(EverySolver, WeightsAndCovarianceMatchWeightedNormalEquations) {
  LinearProblem p = Make(Random(30, 4, 21), Random(30, 1, 22));
  p.row_weights = Random(30, 1, 23).cwiseAbs().array() + 0.5;
  const LinearSolution s = Solver()->Solve(p);
  ASSERT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  const Eigen::MatrixXd aw = p.row_weights.asDiagonal() * p.A;
  const Eigen::VectorXd bw = p.row_weights.cwiseProduct(p.b);
  const Eigen::VectorXd ref =
      KktReference(aw, bw, Eigen::MatrixXd(0, 4), Eigen::VectorXd());
  EXPECT_LT((s.x - ref).cwiseAbs().maxCoeff(), 1e-8 * ref.cwiseAbs().maxCoeff());
  // Weights state the noise: covariance (A' W^2 A)^-1, no residual scaling.
  EXPECT_FALSE(s.noise_estimated);
  ASSERT_EQ(s.covariance.rows(), 4);
  const Eigen::MatrixXd cov = (aw.transpose() * aw).inverse();
  EXPECT_LT((s.covariance - cov).cwiseAbs().maxCoeff(), 1e-6 * cov.cwiseAbs().maxCoeff());
  for (int j = 0; j < 4; ++j) {
    EXPECT_LE(s.interval_lower[j], s.x[j]);
    EXPECT_GE(s.interval_upper[j], s.x[j]);
  }
}

TEST_P(EverySolver, FixedValueAndEquality) {
  LinearProblem p = Make(Random(25, 5, 31), Random(25, 1, 32));
  p.Fix("x2", 0.25);
  p.equality_matrix = Eigen::MatrixXd::Zero(1, 5);
  p.equality_matrix << 1, 0, 1, 1, 0;  // x1 + x3 + x4 = 1
  p.equality_rhs = Eigen::VectorXd::Ones(1);
  const LinearSolution s = Solver()->Solve(p);
  ASSERT_TRUE(s.summary.status == SolverStatus::kSolved) << s.summary.message;
  // Reference: x2 = 0.25 as one more equality row.
  Eigen::MatrixXd c(2, 5);
  c << 1, 0, 1, 1, 0, 0, 1, 0, 0, 0;
  Eigen::VectorXd d(2);
  d << 1, 0.25;
  const Eigen::VectorXd ref = KktReference(p.A, p.b, c, d);
  EXPECT_LT((s.x - ref).cwiseAbs().maxCoeff(), 1e-8) << s.x.transpose() << "\n"
                                                     << ref.transpose();
  EXPECT_DOUBLE_EQ(s.x[1], 0.25);
  EXPECT_NEAR(s.x[0] + s.x[2] + s.x[3], 1.0, 1e-9);
}

TEST_P(EverySolver, PaperChainWithMass4FixedRecoversThePresetFactors) {
  const PaperChainScenario sc = PaperChain(3);
  LinearProblem p = PaperChainSystem(sc);
  p.Fix(sc.fixed_parameter, sc.preset[sc.model.FindParameter(sc.fixed_parameter)]);
  const LinearSolution s = Solver()->Solve(p);
  ASSERT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_LT((s.x - sc.preset).cwiseAbs().maxCoeff(), 1e-8) << s.summary.message;
}

TEST_P(EverySolver, RejectsBadInputBeforeWork) {
  LinearProblem p = Make(Random(6, 2, 41), Random(6, 1, 42));
  p.lower = Eigen::Vector2d(0.0, 2.0);
  p.upper = Eigen::Vector2d(1.0, 1.0);
  try {
    Solver()->Solve(p);
    FAIL() << "lower > upper accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds its upper bound"), std::string::npos)
        << e.what();
  }
  LinearProblem q = Make(Random(6, 2, 41), Random(6, 1, 42));
  q.b[3] = std::nan("");
  EXPECT_THROW(Solver()->Solve(q), InputError);
  LinearProblem r = Make(Random(6, 3, 41), Random(6, 1, 42));
  r.equality_matrix = Eigen::MatrixXd::Zero(2, 3);
  r.equality_matrix << 1, 1, 0, 1, 1, 0;
  r.equality_rhs = Eigen::Vector2d(1.0, 2.0);  // x1 + x2 = 1 and = 2
  try {
    Solver()->Solve(r);
    FAIL() << "inconsistent equalities accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inconsistent"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Linear, EverySolver,
                         ::testing::ValuesIn(AvailableLinearSolvers()));

class BoundedSolver : public ::testing::TestWithParam<std::string> {};

TEST_P(BoundedSolver, MatchesBruteForceActiveSetEnumeration) {
  const auto solver = CreateLinearSolver(GetParam());
  for (unsigned seed = 0; seed < 12; ++seed) {
    const int n = 3 + seed % 4;
    LinearProblem p =
        Make(Random(3 * n, n, 100 + seed), 3.0 * Random(3 * n, 1, 200 + seed));
    p.lower = -0.5 * Eigen::VectorXd::Ones(n);
    p.upper = 0.5 * Eigen::VectorXd::Ones(n);
    if (seed % 3 == 0) p.upper[0] = kInf;  // one-sided
    const Eigen::VectorXd ref = BruteForceBounded(p.A, p.b, p.lower, p.upper);
    const LinearSolution s = solver->Solve(p);
    ASSERT_EQ(s.summary.status, SolverStatus::kSolved)
        << "seed " << seed << ": " << s.summary.message;
    EXPECT_LT((s.x - ref).cwiseAbs().maxCoeff(), 1e-7) << "seed " << seed;
    EXPECT_LT(s.summary.kkt_residual, 1e-6) << "seed " << seed;
    for (int j = 0; j < n; ++j) {
      EXPECT_GE(s.x[j], p.lower[j]);
      EXPECT_LE(s.x[j], p.upper[j]);
    }
  }
}

TEST_P(BoundedSolver, BoundsWithEqualityMatchEnumerationOnTheNullSpace) {
  // x1 + x2 + x3 = 1 with 0 <= x <= 0.6: the optimum of a problem whose
  // unconstrained answer lies far outside the box.
  LinearProblem p =
      Make(Eigen::MatrixXd::Identity(3, 3), Eigen::Vector3d(2.0, -1.0, 0.1));
  p.equality_matrix = Eigen::RowVector3d(1, 1, 1);
  p.equality_rhs = Eigen::VectorXd::Ones(1);
  p.lower = Eigen::Vector3d::Zero();
  p.upper = 0.6 * Eigen::Vector3d::Ones();
  // Projection of (2, -1, 0.1) on {sum = 1} within the box: x1 = 0.6, x2 = 0,
  // then x3 = 0.4 (by hand: the KKT conditions hold with these multipliers).
  const LinearSolution s = CreateLinearSolver(GetParam())->Solve(p);
  ASSERT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], 0.6, 1e-8);
  EXPECT_NEAR(s.x[1], 0.0, 1e-8);
  EXPECT_NEAR(s.x[2], 0.4, 1e-8);
}

// x in the unit box [0, 1]^2 with x1 + x2 = 5: no x satisfies both.
LinearProblem InfeasibleBoxAndEquality() {
  LinearProblem p = Make(Eigen::MatrixXd::Identity(2, 2), Eigen::Vector2d(1.0, 1.0));
  p.equality_matrix = Eigen::RowVector2d(1, 1);
  p.equality_rhs = Eigen::VectorXd::Constant(1, 5.0);
  p.lower = Eigen::Vector2d::Zero();
  p.upper = Eigen::Vector2d::Ones();
  return p;
}

TEST_P(BoundedSolver, InfeasibleBoxAndEqualityIsAStatus) {
  const LinearProblem p = InfeasibleBoxAndEquality();
  const LinearSolution s = CreateLinearSolver(GetParam())->Solve(p);
  EXPECT_FALSE(s.summary.status == SolverStatus::kSolved) << s.summary.message;
}

INSTANTIATE_TEST_SUITE_P(Linear, BoundedSolver,
                         ::testing::Values("bvls", "ceres", "ipopt"));

TEST(Bvls, InfeasibleIsReportedAsInfeasible) {
  const LinearProblem p = InfeasibleBoxAndEquality();
  const LinearSolution s = CreateLinearSolver("bvls")->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kInfeasible);
  EXPECT_NE(s.summary.message.find("no x within the bounds"), std::string::npos);
}

TEST(Bvls, StartsFromTheClippedLeastSquaresAnswer) {
  // Half of x_true far outside the box [-1, 1], half well inside, little noise:
  // the unconstrained answer clipped to the box already has the optimum's active
  // set, so a few iterations confirm it (starting from x = 0 with every unknown
  // free took one iteration per active bound, and more).
  for (unsigned seed = 0; seed < 4; ++seed) {
    const int n = 8;
    const Eigen::MatrixXd a = Random(20 * n, n, 300 + seed);
    Eigen::VectorXd x_true(n);
    x_true << 3.0, 0.2, -2.5, -0.3, 4.0, 0.1, -3.5, 0.4;
    LinearProblem p = Make(a, a * x_true + 0.01 * Random(20 * n, 1, 400 + seed));
    p.lower = -Eigen::VectorXd::Ones(n);
    p.upper = Eigen::VectorXd::Ones(n);
    const Eigen::VectorXd ref = BruteForceBounded(p.A, p.b, p.lower, p.upper);
    const Eigen::VectorXd clipped =
        KktReference(p.A, p.b, Eigen::MatrixXd(0, n), Eigen::VectorXd())
            .cwiseMax(p.lower)
            .cwiseMin(p.upper);
    for (int j = 0; j < n; ++j) {  // the premise: same active set
      ASSERT_EQ(std::abs(clipped[j]) == 1.0, std::abs(ref[j]) > 1.0 - 1e-12)
          << "seed " << seed << ", unknown " << j;
    }
    const LinearSolution s = CreateLinearSolver("bvls")->Solve(p);
    ASSERT_EQ(s.summary.status, SolverStatus::kSolved)
        << "seed " << seed << ": " << s.summary.message;
    EXPECT_LE(s.summary.iterations, 2) << "seed " << seed << ": " << s.summary.message;
    EXPECT_LT((s.x - ref).cwiseAbs().maxCoeff(), 1e-9) << "seed " << seed;
  }
}

TEST(Lstsq, RankDeficientPaperChainNamesTheMissingConstraint) {
  const PaperChainScenario sc = PaperChain(3);
  const LinearProblem p = PaperChainSystem(sc);
  for (const std::string name : {"lstsq", "tsvd"}) {
    const LinearSolution s = CreateLinearSolver(name, Unregularised(name))->Solve(p);
    EXPECT_EQ(s.identifiability.rank, 12) << name;
    EXPECT_NE(s.summary.status, SolverStatus::kFailed) << name;
  }
  const LinearSolution s = CreateLinearSolver("lstsq")->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kMinimumNorm);
  EXPECT_NE(s.summary.message.find("common scaling"), std::string::npos)
      << s.summary.message;
}

TEST(Lstsq, UnscaledRankDecisionWarns) {
  // Columns of very different size: unscaled, the small one falls under the
  // threshold; the solver must say so rather than truncate silently.
  Eigen::MatrixXd a = Random(20, 3, 51);
  a.col(2) *= 1e-12;
  LinearProblem p = Make(a, Random(20, 1, 52));
  LinearSolverOptions o;
  o.scale_columns = false;
  const LinearSolution s = CreateLinearSolver("lstsq", o)->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kMinimumNorm);
  ASSERT_FALSE(s.summary.warnings.empty());
  EXPECT_NE(s.summary.warnings.back().find("not scaled"), std::string::npos);
  const LinearSolution scaled = CreateLinearSolver("lstsq")->Solve(p);
  EXPECT_EQ(scaled.summary.status, SolverStatus::kSolved);
}

TEST(Lstsq, CovarianceFromResidualUsesStudentT) {
  const LinearProblem p = Make(Random(12, 3, 61), Random(12, 1, 62));
  const LinearSolution s = CreateLinearSolver("lstsq")->Solve(p);
  EXPECT_TRUE(s.noise_estimated);
  const double s2 = s.residual.squaredNorm() / (12 - 3);
  const Eigen::MatrixXd cov = s2 * (p.A.transpose() * p.A).inverse();
  EXPECT_LT((s.covariance - cov).cwiseAbs().maxCoeff(),
            1e-10 * cov.cwiseAbs().maxCoeff());
  // t_{0.975, 9} = 2.262157 (tables).
  const double half = s.interval_upper[0] - s.x[0];
  EXPECT_NEAR(half / std::sqrt(cov(0, 0)), 2.262157, 1e-5);
}

// The backends stop on first-order tolerances; on NIST Wampler5 (huge residual)
// Ceres stops with about 1 correct digit and Ipopt keeps none on Filip (condition
// number 5e9). Both must say so instead of reporting "solved".
TEST(BackendLinearSolvers, TooFewCorrectDigitsAreNotSolved) {
  const std::string dir = std::string(FEMUP_TEST_DATA_DIR) + "/nist/linear/";
  const struct {
    const char* dataset;
    const char* solver;
  } cases[] = {{"Wampler5", "ceres"}, {"Filip", "ipopt"}};
  for (const auto& c : cases) {
    const NistLinearDataset data = ReadNistLinear(dir + c.dataset + ".dat");
    const LinearSolution s = CreateLinearSolver(c.solver)->Solve(data.Problem());
    // The measured error behind the status, against the certified values.
    double worst = 0;
    for (int i = 0; i < data.num_parameters(); ++i) {
      const double cert = static_cast<double>(data.certified[i]);
      worst = std::max(worst, std::abs(s.x[i] - cert) / std::abs(cert));
    }
    EXPECT_GT(worst, 1e-4) << c.dataset << " " << c.solver;
    EXPECT_EQ(s.summary.status, SolverStatus::kNoConvergence)
        << c.dataset << " " << c.solver;
    EXPECT_NE(s.summary.message.find("correct digits"), std::string::npos)
        << s.summary.message;
  }
  // Where the backend does reach the minimiser, no such complaint.
  const NistLinearDataset norris = ReadNistLinear(dir + "Norris.dat");
  for (const char* solver : {"ceres", "ipopt"}) {
    const LinearSolution s = CreateLinearSolver(solver)->Solve(norris.Problem());
    EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << solver;
    for (const std::string& w : s.summary.warnings) {
      EXPECT_EQ(w.find("correct digits"), std::string::npos) << solver << ": " << w;
    }
  }
}

// The paper's form without a fixed factor has the common-scaling null space:
// the backends find a minimiser but must say it is not unique, and which
// direction the data cannot see.
TEST(BackendLinearSolvers, RankDeficiencyIsReported) {
  const PaperChainScenario sc = PaperChain(3);
  const LinearProblem p = PaperChainSystem(sc);
  for (const char* solver : {"ceres", "ipopt"}) {
    const LinearSolution s = CreateLinearSolver(solver)->Solve(p);
    bool reported = false;
    for (const std::string& w : s.summary.warnings) {
      reported =
          reported || (w.find("rank deficient (rank 12 of 13") != std::string::npos &&
                       w.find("common scaling") != std::string::npos);
    }
    EXPECT_TRUE(reported) << solver;
    EXPECT_LT((p.A * s.x - p.b).norm(), 1e-6 * p.b.norm()) << solver;  // a minimiser
  }
}

TEST(Tsvd, MatchesTheTruncatedPseudoInverse) {
  const Eigen::MatrixXd a = Random(15, 6, 71);
  const Eigen::VectorXd b = Random(15, 1, 72);
  LinearSolverOptions o;
  o.truncation = 3;
  const LinearSolution s = CreateLinearSolver("tsvd", o)->Solve(Make(a, b));
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  Eigen::VectorXd ref = Eigen::VectorXd::Zero(6);
  for (int i = 0; i < 3; ++i)
    ref += svd.matrixV().col(i) * svd.matrixU().col(i).dot(b) / svd.singularValues()[i];
  EXPECT_LT((s.x - ref).norm(), 1e-12 * ref.norm());
  EXPECT_EQ(s.regularisation.truncation, 3);
  // Resolution = V_k V_k'.
  const Eigen::MatrixXd vk = svd.matrixV().leftCols(3);
  EXPECT_LT((s.resolution - vk * vk.transpose()).norm(), 1e-12);
}

TEST(Tsvd, RulesChooseSensibleTruncation) {
  // Singular values 1, 1e-1, ..., 1e-7 and a noise floor 1e-4: GCV and the
  // discrepancy principle keep the components above the noise.
  const int n = 8;
  Eigen::MatrixXd u =
      Eigen::HouseholderQR<Eigen::MatrixXd>(Random(20, n, 81)).householderQ() *
      Eigen::MatrixXd::Identity(20, n);
  Eigen::MatrixXd v =
      Eigen::HouseholderQR<Eigen::MatrixXd>(Random(n, n, 82)).householderQ();
  Eigen::VectorXd sv(n);
  for (int i = 0; i < n; ++i) sv[i] = std::pow(10.0, -i);
  const Eigen::MatrixXd a = u * sv.asDiagonal() * v.transpose();
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(n);
  const Eigen::VectorXd e = 1e-4 * Random(20, 1, 83);
  const Eigen::VectorXd b = a * x + e;
  LinearSolverOptions o;
  o.regularisation.parameter_choice = "discrepancy";
  o.regularisation.noise_norm = e.norm();
  const LinearSolution d = CreateLinearSolver("tsvd", o)->Solve(Make(a, b));
  EXPECT_GE(d.regularisation.truncation, 3);
  EXPECT_LE(d.regularisation.truncation, 5);
  o.regularisation.parameter_choice = "gcv";
  const LinearSolution g = CreateLinearSolver("tsvd", o)->Solve(Make(a, b));
  EXPECT_GE(g.regularisation.truncation, 3);
  EXPECT_LE(g.regularisation.truncation, 5);
}

}  // namespace

}  // namespace femup
