// Tikhonov regularisation and its parameter choice (solvers/include/femup/
// solvers/regularisation.h, tikhonov.h), checked against the regularised normal
// equations, explicit influence matrices, finite-difference curvature and dense
// grid searches; and on Hansen's ill-posed test problems.
#include "femup/solvers/regularisation.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "femup/core/errors.h"
#include "femup/evaluation/ill_posed.h"
#include "femup/solvers/linear_solver.h"
#include "solver_problems.h"

namespace femup {
namespace {

Eigen::MatrixXd Random(int rows, int cols, unsigned seed) {
  return fixtures::RandomGaussian(rows, cols, seed);
}

// (A'A + lambda^2 L'L) x = A'b + lambda^2 L'L x0, in long double.
Eigen::VectorXd NormalEquations(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                const Eigen::MatrixXd& l, const Eigen::VectorXd& x0,
                                double lambda) {
  using M = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  using V = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
  const M al = a.cast<long double>(), ll = l.cast<long double>();
  const long double l2 = static_cast<long double>(lambda) * lambda;
  const M lhs = al.transpose() * al + l2 * ll.transpose() * ll;
  const V rhs = al.transpose() * b.cast<long double>() +
                l2 * ll.transpose() * (ll * x0.cast<long double>());
  return Eigen::FullPivLU<M>(lhs).solve(rhs).cast<double>();
}

TEST(TikhonovPath, StandardFormMatchesNormalEquations) {
  const Eigen::MatrixXd a = Random(20, 8, 1);
  const Eigen::VectorXd b = Random(20, 1, 2);
  const TikhonovPath path(a, b);
  for (double lambda : {1e-3, 0.1, 1.0, 10.0}) {
    const Eigen::VectorXd ref = NormalEquations(a, b, Eigen::MatrixXd::Identity(8, 8),
                                                Eigen::VectorXd::Zero(8), lambda);
    const Eigen::VectorXd x = path.Solve(lambda);
    EXPECT_LT((x - ref).norm(), 1e-11 * ref.norm()) << lambda;
    EXPECT_NEAR(path.ResidualNorm(lambda), (a * x - b).norm(), 1e-12);
    EXPECT_NEAR(path.SolutionNorm(lambda), x.norm(), 1e-12);
  }
}

TEST(TikhonovPath, GeneralFormWithPriorMatchesNormalEquations) {
  const Eigen::MatrixXd a = Random(15, 10, 3);
  const Eigen::VectorXd b = Random(15, 1, 4);
  const Eigen::VectorXd x0 = Random(10, 1, 5);
  for (int order : {1, 2}) {
    const Eigen::MatrixXd l = DifferenceOperator(10, order);
    const TikhonovPath path(a, b, l, x0);
    EXPECT_EQ(path.null_space_dimension(), order);
    for (double lambda : {1e-2, 0.5, 5.0}) {
      const Eigen::VectorXd ref = NormalEquations(a, b, l, x0, lambda);
      const Eigen::VectorXd x = path.Solve(lambda);
      EXPECT_LT((x - ref).norm(), 1e-10 * ref.norm()) << order << " " << lambda;
      EXPECT_NEAR(path.SolutionNorm(lambda), (l * (x - x0)).norm(), 1e-10);
      EXPECT_NEAR(path.ResidualNorm(lambda), (a * x - b).norm(), 1e-10);
    }
  }
}

TEST(TikhonovPath, GcvAndInfluenceMatrixTrace) {
  const Eigen::MatrixXd a = Random(25, 9, 6);
  const Eigen::VectorXd b = Random(25, 1, 7);
  const Eigen::MatrixXd l = DifferenceOperator(9, 1);
  const TikhonovPath path(a, b, l);
  for (double lambda : {0.05, 0.7, 3.0}) {
    // Influence matrix from the explicit regularised inverse.
    const Eigen::MatrixXd h = a * path.Inverse(lambda);
    EXPECT_NEAR(path.EffectiveParameters(lambda), h.trace(), 1e-10);
    const Eigen::VectorXd x = path.Solve(lambda);
    const double r = (a * x - b).norm();
    const double dof = 25 - h.trace();
    EXPECT_NEAR(path.Gcv(lambda), r * r / (dof * dof), 1e-12);
    EXPECT_LT((path.Inverse(lambda) * b - x).norm(), 1e-10 * x.norm());
  }
}

TEST(TikhonovPath, CurvatureMatchesFiniteDifferences) {
  const IllPosedProblem shaw = Shaw(32);
  const Eigen::VectorXd b = AddRelativeNoise(shaw.b, 1e-3, 7);
  const TikhonovPath path(shaw.A, b);
  for (double lambda : {1e-3, 1e-2, 0.1}) {
    // (x(t), y(t)) = (log rho, log eta), t = log lambda; kappa = (x'y'' - x''y') / |.|^3.
    const double h = 1e-3, t = std::log(lambda);
    auto x = [&](double s) { return std::log(path.ResidualNorm(std::exp(s))); };
    auto y = [&](double s) { return std::log(path.SolutionNorm(std::exp(s))); };
    const double x1 = (x(t + h) - x(t - h)) / (2 * h),
                 y1 = (y(t + h) - y(t - h)) / (2 * h);
    const double x2 = (x(t + h) - 2 * x(t) + x(t - h)) / (h * h);
    const double y2 = (y(t + h) - 2 * y(t) + y(t - h)) / (h * h);
    const double kappa = (x1 * y2 - x2 * y1) / std::pow(x1 * x1 + y1 * y1, 1.5);
    EXPECT_NEAR(path.Curvature(lambda), kappa, 1e-4 * (1 + std::abs(kappa))) << lambda;
  }
}

// The rule's lambda against a dense grid (1e5 points) over the same range.
void ExpectBeatsDenseGrid(const TikhonovPath& path,
                          const std::function<double(double)>& f, double chosen,
                          double lo, double hi) {
  const int k = 100000;
  double best = std::numeric_limits<double>::infinity(), arg = 0;
  for (int i = 0; i < k; ++i) {
    const double lambda = lo * std::pow(hi / lo, double(i) / (k - 1));
    const double v = f(lambda);
    if (v < best) best = v, arg = lambda;
  }
  EXPECT_LE(f(chosen), best * (1 + 1e-12) + 1e-300);
  const double step = std::pow(hi / lo, 1.0 / (k - 1)) - 1;
  EXPECT_LT(std::abs(chosen / arg - 1), 2 * step) << chosen << " vs grid " << arg;
  (void)path;
}

TEST(ChooseLambda, GcvLcurveQuasiRefinedBeyondTheGrid) {
  const IllPosedProblem p = Shaw(64);
  const Eigen::VectorXd b = AddRelativeNoise(p.b, 1e-3, 11);
  const TikhonovPath path(p.A, b);
  RegularisationOptions o;
  RegularisationReport rep;
  ChooseLambda(path, o, &rep);
  const double lo = path.DefaultLambdaMin(), hi = path.DefaultLambdaMax();
  EXPECT_FALSE(rep.at_range_end) << rep.note;
  ExpectBeatsDenseGrid(
      path, [&](double l) { return path.Gcv(l); }, rep.lambda_gcv, lo, hi);
  ExpectBeatsDenseGrid(
      path, [&](double l) { return -path.Curvature(l); }, rep.lambda_lcurve, lo, hi);
  ExpectBeatsDenseGrid(
      path, [&](double l) { return path.Quasi(l); }, rep.lambda_quasi, lo, hi);
  EXPECT_EQ(rep.grid_lambda.size(), 200u);
}

TEST(ChooseLambda, DiscrepancyHitsTheTargetResidual) {
  const IllPosedProblem p = Phillips(64);
  const Eigen::VectorXd b = AddRelativeNoise(p.b, 1e-3, 12);
  const double noise = (b - p.b).norm();
  const TikhonovPath path(p.A, b);
  RegularisationOptions o;
  o.parameter_choice = "discrepancy";
  o.noise_norm = noise;
  RegularisationReport rep;
  const double lambda = ChooseLambda(path, o, &rep);
  EXPECT_NEAR(path.ResidualNorm(lambda), noise, 1e-12 * noise);
  EXPECT_FALSE(rep.at_range_end);
  // A target below what any lambda reaches is reported, not hidden.
  Eigen::VectorXd inconsistent = Eigen::VectorXd::Zero(3);
  inconsistent << 1, 1, 1;
  Eigen::MatrixXd a(3, 1);
  a << 1, 0, 0;
  const TikhonovPath small(a, inconsistent);
  o.noise_norm = 0.1;  // the residual is at least sqrt(2)
  ChooseLambda(small, o, &rep);
  EXPECT_TRUE(rep.at_range_end);
  EXPECT_NE(rep.note.find("noise level is smaller"), std::string::npos) << rep.note;
}

TEST(ChooseLambda, SaysSoWhenTheOptimumIsAnEndPoint) {
  // Noise-free, well conditioned: GCV keeps falling as lambda -> 0.
  const Eigen::MatrixXd a = Random(30, 3, 13);
  const Eigen::VectorXd b = a * Eigen::Vector3d(1, 2, 3);
  const TikhonovPath path(a, b);
  RegularisationReport rep;
  ChooseLambda(path, RegularisationOptions(), &rep);
  EXPECT_TRUE(rep.at_range_end);
  EXPECT_NE(rep.note.find("no interior optimum"), std::string::npos) << rep.note;
}

TEST(ChooseLambda, BadOptionsNameTheField) {
  const TikhonovPath path(Random(5, 2, 1), Random(5, 1, 2));
  RegularisationOptions o;
  o.parameter_choice = "magic";
  try {
    ChooseLambda(path, o, nullptr);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("parameter_choice"), std::string::npos);
  }
  o = RegularisationOptions();
  o.parameter_choice = "discrepancy";  // without a noise norm
  EXPECT_THROW(ChooseLambda(path, o, nullptr), InputError);
  o = RegularisationOptions();
  o.grid_points = 2;
  EXPECT_THROW(ChooseLambda(path, o, nullptr), InputError);
}

TEST(DifferenceOperator, RespectsGroups) {
  const Eigen::MatrixXd l = DifferenceOperator(5, 1, {"k", "k", "k", "m", "m"});
  ASSERT_EQ(l.rows(), 3);
  Eigen::MatrixXd expected(3, 5);
  expected << -1, 1, 0, 0, 0, 0, -1, 1, 0, 0, 0, 0, 0, -1, 1;
  EXPECT_EQ(l, expected);
  EXPECT_EQ(DifferenceOperator(4, 2).row(0), Eigen::RowVector4d(1, -2, 1, 0));
  EXPECT_THROW(DifferenceOperator(3, 3), InputError);
  EXPECT_THROW(DifferenceOperator(2, 2), InputError);
}

TEST(TikhonovSolver, ResolutionAndCovarianceOfTheRegularisedEstimator) {
  const Eigen::MatrixXd a = Random(20, 6, 21);
  const Eigen::VectorXd b = Random(20, 1, 22);
  LinearProblem p;
  p.A = a;
  p.b = b;
  p.row_weights = Eigen::VectorXd::Constant(20, 1.0 / 0.1);  // sigma = 0.1
  LinearSolverOptions o;
  o.regularisation.parameter_choice = "fixed";
  o.regularisation.lambda = 3.0;
  const LinearSolution s = CreateLinearSolver("tikhonov", o)->Solve(p);
  const Eigen::MatrixXd aw = 10.0 * a;
  const Eigen::MatrixXd x =
      (aw.transpose() * aw + 9.0 * Eigen::MatrixXd::Identity(6, 6)).inverse() *
      aw.transpose();
  EXPECT_LT((s.resolution - x * aw).norm(), 1e-10);
  EXPECT_LT((s.covariance - x * x.transpose()).norm(),
            1e-10 * (x * x.transpose()).norm());
  EXPECT_LT((s.bias_estimate - (x * aw - Eigen::MatrixXd::Identity(6, 6)) * s.x).norm(),
            1e-10);
}

// Hansen's test problems (n = 64, relative noise 1e-3): every rule lands an
// interior lambda whose error is within a modest factor of the best Tikhonov
// solution on a fine grid.
class HansenProblem : public ::testing::TestWithParam<std::string> {};

TEST_P(HansenProblem, RulesFindInteriorLambdaNearTheBest) {
  const IllPosedProblem p = MakeIllPosedProblem(GetParam(), 64);
  const Eigen::VectorXd b = AddRelativeNoise(p.b, 1e-3, 2024);
  const TikhonovPath path(p.A, b);
  RegularisationOptions o;
  o.noise_norm = (b - p.b).norm();
  RegularisationReport rep;
  ChooseLambda(path, o, &rep);
  auto err = [&](double l) {
    return (path.Solve(l) - p.x_exact).norm() / p.x_exact.norm();
  };
  double best = 1e300;
  for (int i = 0; i < 2000; ++i) {
    const double l = 1e-8 * std::pow(1e8, i / 1999.0);
    best = std::min(best, err(l));
  }
  for (double l : {rep.lambda_gcv, rep.lambda_lcurve, rep.lambda_discrepancy}) {
    EXPECT_GT(l, path.DefaultLambdaMin() * 1.01) << GetParam();
    EXPECT_LT(l, path.DefaultLambdaMax() * 0.99) << GetParam();
  }
  EXPECT_LT(err(rep.lambda_gcv), 4 * best) << GetParam();
  EXPECT_LT(err(rep.lambda_discrepancy), 4 * best) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Regtools, HansenProblem,
                         ::testing::Values("phillips", "shaw", "baart", "deriv2",
                                           "foxgood"));

}  // namespace
}  // namespace femup
