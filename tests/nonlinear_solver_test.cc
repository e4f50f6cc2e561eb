// Nonlinear least-squares solvers (solvers/include/femup/solvers/{nonlinear_solver,
// ceres_solver,ipopt_solver,kkt,backend_linear_solvers}.h) and NonlinearProblem
// (problems/include/femup/problems/nonlinear_problem.h). The same suite runs on
// every backend; answers are checked against closed forms, the KKT system
// solved directly, the normal equations in long double, and (bounded problems)
// the enumeration of every active set.
#include "femup/solvers/nonlinear_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "femup/core/errors.h"
#include "femup/problems/linear_problem.h"
#include "femup/problems/nonlinear_problem.h"
#include "femup/solvers/backend_linear_solvers.h"
#include "femup/solvers/ceres_solver.h"
#include "femup/solvers/ipopt_solver.h"
#include "femup/solvers/kkt.h"

namespace femup {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using MatrixLd = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

// r1 = 10 (x2 - x1^2), r2 = 1 - x1: minimum 0 at (1, 1).
NonlinearProblem Rosenbrock() {
  NonlinearProblem p;
  p.num_residuals = 2;
  p.initial = Eigen::Vector2d(-1.2, 1.0);
  p.names = {"x1", "x2"};
  p.evaluate = [](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* j,
                  std::string*) {
    *r = Eigen::Vector2d(10 * (x[1] - x[0] * x[0]), 1 - x[0]);
    if (j != nullptr) {
      j->resize(2, 2);
      *j << -20 * x[0], 10, -1, 0;
    }
    return true;
  };
  return p;
}

// r = A x - b written out directly (independent of AsNonlinear).
NonlinearProblem Linear(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                        const Eigen::VectorXd& start) {
  NonlinearProblem p;
  p.num_residuals = static_cast<int>(a.rows());
  p.initial = start;
  p.evaluate = [a, b](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* j,
                      std::string*) {
    *r = a * x - b;
    if (j != nullptr) *j = a;
    return true;
  };
  return p;
}

// A small system whose unconstrained least-squares solution is (2, 1).
Eigen::MatrixXd SmallA() {
  Eigen::MatrixXd a(3, 2);
  a << 1, 0, 0, 1, 1, 1;
  return a;
}
Eigen::VectorXd SmallB() { return Eigen::Vector3d(2, 1, 3); }

// Solution of min |A x - b|^2 s.t. C x = d from the KKT system, in long double.
Eigen::VectorXd EqualityConstrained(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                    const Eigen::MatrixXd& c, const Eigen::VectorXd& d) {
  const auto n = a.cols(), q = c.rows();
  MatrixLd k = MatrixLd::Zero(n + q, n + q);
  k.topLeftCorner(n, n) = (a.transpose() * a).cast<long double>();
  k.topRightCorner(n, q) = c.transpose().cast<long double>();
  k.bottomLeftCorner(q, n) = c.cast<long double>();
  Eigen::Matrix<long double, Eigen::Dynamic, 1> rhs(n + q);
  rhs << (a.transpose() * b).cast<long double>(), d.cast<long double>();
  return k.fullPivLu().solve(rhs).head(n).cast<double>();
}

Eigen::VectorXd Gradient(const NonlinearSolution& s) {
  return s.jacobian.transpose() * s.residual;
}

// Records the iterations, the error of an answer and its KKT residual in the
// test's XML output (--gtest_output=xml).
void Record(const NonlinearSolution& s, const Eigen::VectorXd& expected) {
  std::ostringstream error, kkt;
  error << (s.x - expected).cwiseAbs().maxCoeff();
  kkt << s.summary.kkt_residual;
  ::testing::Test::RecordProperty("iterations", s.summary.iterations);
  ::testing::Test::RecordProperty("max_error", error.str());
  ::testing::Test::RecordProperty("kkt_residual", kkt.str());
}

// min |A x - b| within lower <= x <= upper by enumerating every active set
// (each unknown free, on its lower or on its upper bound) and keeping the one
// that satisfies the KKT conditions: exact, independent of any solver, and
// fine for a handful of unknowns.
Eigen::VectorXd BoundedByEnumeration(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                     const Eigen::VectorXd& lower,
                                     const Eigen::VectorXd& upper) {
  const int n = static_cast<int>(a.cols());
  int combinations = 1;
  for (int i = 0; i < n; ++i) combinations *= 3;
  for (int code = 0; code < combinations; ++code) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    std::vector<int> state(n), free;
    for (int i = 0, c = code; i < n; ++i, c /= 3) {
      state[i] = c % 3;  // 0 free, 1 lower, 2 upper
      if (state[i] == 0) free.push_back(i);
      if (state[i] == 1) x[i] = lower[i];
      if (state[i] == 2) x[i] = upper[i];
    }
    if (!free.empty()) {
      Eigen::MatrixXd af(a.rows(), free.size());
      for (std::size_t k = 0; k < free.size(); ++k) af.col(k) = a.col(free[k]);
      const Eigen::VectorXd xf = af.colPivHouseholderQr().solve(b - a * x);
      for (std::size_t k = 0; k < free.size(); ++k) x[free[k]] = xf[k];
    }
    const Eigen::VectorXd g = a.transpose() * (a * x - b);
    bool kkt = true;
    for (int i = 0; i < n; ++i) {
      if (state[i] == 0) kkt = kkt && x[i] >= lower[i] && x[i] <= upper[i];
      if (state[i] == 1) kkt = kkt && g[i] >= 0;
      if (state[i] == 2) kkt = kkt && g[i] <= 0;
    }
    if (kkt) return x;
  }
  return Eigen::VectorXd();
}

class NonlinearSolverTest : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<NonlinearSolver> Solver(
      const NonlinearSolverOptions& options = {}) const {
    return CreateNonlinearSolver(GetParam(), options);
  }
};

TEST_P(NonlinearSolverTest, RosenbrockFromTheClassicStart) {
  const auto solver = Solver();
  EXPECT_EQ(solver->name(), GetParam());
  const NonlinearSolution s = solver->Solve(Rosenbrock());
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], 1.0, 1e-8);
  EXPECT_NEAR(s.x[1], 1.0, 1e-8);
  EXPECT_LE(s.summary.cost, 1e-16);
  EXPECT_GT(s.summary.iterations, 0);
  EXPECT_GE(s.summary.time_seconds, 0);
  EXPECT_TRUE(std::isnan(s.summary.kkt_residual));  // unconstrained: not checked
  EXPECT_FALSE(s.summary.message.empty());
  // Residual and Jacobian are those of the returned x.
  EXPECT_NEAR(s.residual[1], 1 - s.x[0], 1e-15);
  EXPECT_NEAR(s.jacobian(0, 0), -20 * s.x[0], 1e-12);
  Record(s, Eigen::Vector2d(1, 1));
}

TEST_P(NonlinearSolverTest, OtherTrustRegionAndHessianStillSolveRosenbrock) {
  NonlinearSolverOptions options;
  options.trust_region = "dogleg";     // Ceres
  options.hessian = "limited_memory";  // Ipopt
  const NonlinearSolution s = Solver(options)->Solve(Rosenbrock());
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], 1.0, 1e-6);
  EXPECT_NEAR(s.x[1], 1.0, 1e-6);
}

TEST_P(NonlinearSolverTest, ExponentialFitRecoversExactParameters) {
  // y_i = 2 exp(-1.5 t_i), exact data: the least-squares answer is (2, -1.5).
  const int m = 12;
  Eigen::VectorXd t(m), y(m);
  for (int i = 0; i < m; ++i) {
    t[i] = 0.25 * i;
    y[i] = 2.0 * std::exp(-1.5 * t[i]);
  }
  NonlinearProblem p;
  p.num_residuals = m;
  p.initial = Eigen::Vector2d(1.0, 0.0);
  p.evaluate = [t, y](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* j,
                      std::string*) {
    const Eigen::VectorXd e = (x[1] * t.array()).exp().matrix();
    *r = x[0] * e - y;
    if (j != nullptr) {
      j->resize(t.size(), 2);
      j->col(0) = e;
      j->col(1) = x[0] * t.cwiseProduct(e);
    }
    return true;
  };
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], 2.0, 1e-8);
  EXPECT_NEAR(s.x[1], -1.5, 1e-8);
  Record(s, Eigen::Vector2d(2, -1.5));
}

TEST_P(NonlinearSolverTest, BoundedLinearWithOneActiveUpperBound) {
  // Unconstrained optimum (2, 1); with x1 <= 1.5 the optimum is (1.5, 1.25):
  // min over x2 of (x2 - 1)^2 + (x2 - 1.5)^2. There g = A'(A x - b) = (-0.75, 0),
  // so the upper-bound multiplier of x1 is -0.75 (negative at an upper bound).
  NonlinearProblem p = Linear(SmallA(), SmallB(), Eigen::Vector2d(0, 0));
  p.lower = Eigen::Vector2d(-kInf, 0);
  p.upper = Eigen::Vector2d(1.5, 10);
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], 1.5, 1e-8);
  EXPECT_NEAR(s.x[1], 1.25, 1e-8);
  EXPECT_LE(s.x[0], 1.5);  // never outside the bound
  EXPECT_LE(s.summary.kkt_residual, 1e-6);
  const KktReport kkt = CheckKkt(s.x, Gradient(s), p.lower, p.upper, {}, {}, {}, 1.0);
  ASSERT_EQ(kkt.active_upper, std::vector<int>{0});
  EXPECT_TRUE(kkt.active_lower.empty());
  EXPECT_NEAR(kkt.bound_multipliers[0], -0.75, 1e-7);
  EXPECT_LT(kkt.bound_multipliers[0], 0);
  Record(s, Eigen::Vector2d(1.5, 1.25));
}

TEST_P(NonlinearSolverTest, ActiveLowerBoundOnANonlinearModel) {
  // Rosenbrock with x1 >= 1.2: at x1 = 1.2 the best x2 is 1.44; the gradient in
  // x1 is then 0.2 > 0, the lower-bound multiplier.
  NonlinearProblem p = Rosenbrock();
  p.initial = Eigen::Vector2d(2.0, 1.0);
  p.lower = Eigen::Vector2d(1.2, -kInf);
  p.upper = Eigen::Vector2d(kInf, kInf);
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], 1.2, 1e-8);
  EXPECT_NEAR(s.x[1], 1.44, 1e-8);
  Record(s, Eigen::Vector2d(1.2, 1.44));
  const KktReport kkt = CheckKkt(s.x, Gradient(s), p.lower, p.upper, {}, {}, {}, 1.0);
  EXPECT_EQ(kkt.active_lower, std::vector<int>{0});
  EXPECT_NEAR(kkt.bound_multipliers[0], 0.2, 1e-7);
}

// r(x) = 2 + cos x on [0.5, 7]: the least misfit, 1/2, is at x = pi, inside,
// where r' = 0, so the Gauss-Newton curvature r'^2 vanishes and the diagonal
// step that picks the bounds to hold runs to one of them; the upper one is a
// worse local minimum (its cost 3.8, the gradient pointing out of the box).
// The answer stays at pi: a polish is kept only when it does not raise the
// cost.
TEST_P(NonlinearSolverTest, AnInteriorMinimumWhereTheJacobianVanishesIsKept) {
  NonlinearProblem p;
  p.num_residuals = 1;
  p.initial = Eigen::VectorXd::Constant(1, 2.0);
  p.lower = Eigen::VectorXd::Constant(1, 0.5);
  p.upper = Eigen::VectorXd::Constant(1, 7.0);
  p.evaluate = [](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* j,
                  std::string*) {
    r->resize(1);
    (*r)[0] = 2 + std::cos(x[0]);
    if (j != nullptr) *j = Eigen::MatrixXd::Constant(1, 1, -std::sin(x[0]));
    return true;
  };
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_NE(s.summary.status, SolverStatus::kFailed) << s.summary.message;
  EXPECT_NEAR(s.x[0], M_PI, 1e-3) << s.summary.message;
  EXPECT_NEAR(s.summary.cost, 0.5, 1e-6);
}

TEST_P(NonlinearSolverTest, FixedValueIsHeldAndHasNoVariance) {
  // x1 = 0.5: min over x2 of (x2 - 1)^2 + (x2 - 2.5)^2 gives x2 = 1.75.
  NonlinearProblem p = Linear(SmallA(), SmallB(), Eigen::Vector2d(0, 0));
  p.fixed = {{0, 0.5}};
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_EQ(s.x[0], 0.5);
  EXPECT_NEAR(s.x[1], 1.75, 1e-8);
  Record(s, Eigen::Vector2d(0.5, 1.75));
  ASSERT_EQ(s.covariance.rows(), 2);
  EXPECT_EQ(s.covariance(0, 0), 0);
  EXPECT_EQ(s.covariance(0, 1), 0);
  // Free part: (a2'a2)^-1 s^2 with a2 = (0, 1, 1), s^2 = |r|^2 / (3 - 1).
  EXPECT_NEAR(s.covariance(1, 1), 0.5 * s.residual.squaredNorm() / 2, 1e-12);
}

TEST_P(NonlinearSolverTest, LinearEquality) {
  Eigen::MatrixXd c(1, 2);
  c << 1, 1;
  const Eigen::VectorXd d = Eigen::VectorXd::Constant(1, 1.0);
  NonlinearProblem p = Linear(SmallA(), SmallB(), Eigen::Vector2d(0, 0));
  p.equality_matrix = c;
  p.equality_rhs = d;
  const NonlinearSolution s = Solver()->Solve(p);
  const Eigen::VectorXd ref = EqualityConstrained(SmallA(), SmallB(), c, d);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(ref[0], 1.0, 1e-15);  // the closed form: x = (1, 0)
  EXPECT_NEAR(s.x[0], ref[0], 1e-8);
  EXPECT_NEAR(s.x[1], ref[1], 1e-8);
  EXPECT_NEAR(s.x.sum(), 1.0, 1e-10);
  EXPECT_LE(s.summary.kkt_residual, 1e-8);
  // The multiplier: g = C' mu with g = A'(A x - b) = (-3, -3).
  const KktReport kkt = CheckKkt(s.x, Gradient(s), {}, {}, c, d, {}, 1.0);
  EXPECT_NEAR(kkt.equality_multipliers[0], -3.0, 1e-7);
  // Covariance on the constraint: var(x1 + x2) = 0.
  ASSERT_EQ(s.covariance.rows(), 2);
  EXPECT_NEAR(Eigen::RowVector2d(1, 1) * s.covariance * Eigen::Vector2d(1, 1), 0, 1e-12);
  Record(s, ref);
}

TEST_P(NonlinearSolverTest, RandomBoundedLeastSquaresMatchesEnumeration) {
  // 15 x 5, unconstrained solution of order 1 in a box of half-width 0.3, so
  // that several bounds are active at the optimum.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd a(15, 5);
  Eigen::VectorXd b(15);
  for (int i = 0; i < a.size(); ++i) a.data()[i] = g(rng);
  for (int i = 0; i < b.size(); ++i) b[i] = 3 * g(rng);
  const Eigen::VectorXd lower = Eigen::VectorXd::Constant(5, -0.3);
  const Eigen::VectorXd upper = Eigen::VectorXd::Constant(5, 0.3);
  const Eigen::VectorXd ref = BoundedByEnumeration(a, b, lower, upper);
  ASSERT_EQ(ref.size(), 5);
  const int on_bounds = static_cast<int>(
      ((ref - lower).array().abs() < 1e-12 || (ref - upper).array().abs() < 1e-12)
          .count());
  ASSERT_GE(on_bounds, 2);
  ASSERT_LE(on_bounds, 4);

  NonlinearProblem p = Linear(a, b, Eigen::VectorXd::Zero(5));
  p.lower = lower;
  p.upper = upper;
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_LE((s.x - ref).cwiseAbs().maxCoeff(), 1e-8) << s.summary.message;
  EXPECT_LE(s.summary.kkt_residual, 1e-8);
  Record(s, ref);
}

TEST_P(NonlinearSolverTest, EqualityAndActiveBoundTogether) {
  // With x1 + x2 = 1 the optimum (1, 0) violates x2 >= 0.25, so x = (0.75, 0.25).
  NonlinearProblem p = Linear(SmallA(), SmallB(), Eigen::Vector2d(0.5, 0.5));
  p.equality_matrix = Eigen::RowVector2d(1, 1);
  p.equality_rhs = Eigen::VectorXd::Constant(1, 1.0);
  p.lower = Eigen::Vector2d(-kInf, 0.25);
  p.upper = Eigen::Vector2d(kInf, kInf);
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], 0.75, 1e-8);
  EXPECT_NEAR(s.x[1], 0.25, 1e-8);
  EXPECT_LE(s.summary.kkt_residual, 1e-6);
  Record(s, Eigen::Vector2d(0.75, 0.25));
}

TEST_P(NonlinearSolverTest, InfeasibleBoxAndEqualityIsNotSolved) {
  // 0 <= x <= 1 and x1 + x2 = 3 have no common point.
  NonlinearProblem p = Linear(SmallA(), SmallB(), Eigen::Vector2d(0.5, 0.5));
  p.equality_matrix = Eigen::RowVector2d(1, 1);
  p.equality_rhs = Eigen::VectorXd::Constant(1, 3.0);
  p.lower = Eigen::Vector2d(0, 0);
  p.upper = Eigen::Vector2d(1, 1);
  NonlinearSolution s;
  ASSERT_NO_THROW(s = Solver()->Solve(p));
  EXPECT_EQ(s.summary.status, SolverStatus::kInfeasible) << s.summary.message;
  EXPECT_FALSE(s.summary.usable());
  EXPECT_GT(s.summary.kkt_residual, 1e-6);
  // Never outside the box, whatever the outcome.
  EXPECT_GE(s.x.minCoeff(), 0.0);
  EXPECT_LE(s.x.maxCoeff(), 1.0);
}

TEST_P(NonlinearSolverTest, EvaluateFailingEverywhereIsFailedNotThrown) {
  NonlinearProblem p = Rosenbrock();
  p.evaluate = [](const Eigen::VectorXd&, Eigen::VectorXd*, Eigen::MatrixXd*,
                  std::string* why) {
    *why = "model blew up";
    return false;
  };
  NonlinearSolution s;
  ASSERT_NO_THROW(s = Solver()->Solve(p));
  EXPECT_EQ(s.summary.status, SolverStatus::kFailed);
  EXPECT_NE(s.summary.message.find("model blew up"), std::string::npos)
      << s.summary.message;
}

TEST_P(NonlinearSolverTest, EvaluateReturningWrongSizeIsFailed) {
  NonlinearProblem p = Rosenbrock();
  p.num_residuals = 3;
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kFailed);
  EXPECT_NE(s.summary.message.find("expected 3"), std::string::npos) << s.summary.message;
}

TEST_P(NonlinearSolverTest, EvaluateFailingInARegionStillSolves) {
  // r = log(x) - log(2), defined for x > 0 only. From x = 10 the first
  // Gauss-Newton step lands at x = -6.1, where evaluation fails.
  NonlinearProblem p;
  p.num_residuals = 1;
  p.initial = Eigen::VectorXd::Constant(1, 10.0);
  int failures = 0;
  p.evaluate = [&failures](const Eigen::VectorXd& x, Eigen::VectorXd* r,
                           Eigen::MatrixXd* j, std::string* why) {
    if (x[0] <= 0) {
      ++failures;
      *why = "log of a non-positive number";
      return false;
    }
    *r = Eigen::VectorXd::Constant(1, std::log(x[0]) - std::log(2.0));
    if (j != nullptr) *j = Eigen::MatrixXd::Constant(1, 1, 1 / x[0]);
    return true;
  };
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], 2.0, 1e-8);
  EXPECT_GT(failures, 0);  // the region was visited and rejected
  Record(s, Eigen::VectorXd::Constant(1, 2.0));
}

// NIST's BoxBOD, y = b1 (1 - exp(-b2 x)), started on the plateau where Ceres's
// Levenberg-Marquardt ends from NIST's start 1: with b2 = 84 the exponential is
// below rounding at every x, so the model is the constant b1 and does not depend
// on b2, and with b1 the mean of y the gradient is zero. Certified values from
// NIST's BoxBOD.dat.
NonlinearProblem BoxBodOnItsPlateau() {
  const Eigen::VectorXd x = (Eigen::VectorXd(6) << 1, 2, 3, 5, 7, 10).finished();
  const Eigen::VectorXd y =
      (Eigen::VectorXd(6) << 109, 149, 149, 191, 213, 224).finished();
  NonlinearProblem p;
  p.num_residuals = 6;
  p.initial = Eigen::Vector2d(y.mean(), 84);
  p.evaluate = [x, y](const Eigen::VectorXd& b, Eigen::VectorXd* r, Eigen::MatrixXd* j,
                      std::string*) {
    const Eigen::ArrayXd e = (-b[1] * x.array()).exp();
    *r = (b[0] * (1 - e) - y.array()).matrix();
    if (j != nullptr) {
      j->resize(6, 2);
      j->col(0) = (1 - e).matrix();
      j->col(1) = (b[0] * x.array() * e).matrix();
    }
    return true;
  };
  return p;
}

TEST_P(NonlinearSolverTest, CovarianceOfALinearRegression) {
  // y = c0 + c1 t + noise (fixed seed); covariance (A'A)^-1 s^2, s^2 = |r|^2/(m-2).
  const int m = 20;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.1);
  Eigen::MatrixXd a(m, 2);
  Eigen::VectorXd b(m);
  for (int i = 0; i < m; ++i) {
    a(i, 0) = 1;
    a(i, 1) = 0.5 * i;
    b[i] = 1.0 + 0.3 * a(i, 1) + noise(rng);
  }
  const MatrixLd ata_inv = (a.transpose() * a).cast<long double>().inverse();
  const Eigen::VectorXd ref =
      (ata_inv * (a.transpose() * b).cast<long double>()).cast<double>();
  const double s2 = (a * ref - b).squaredNorm() / (m - 2);
  const Eigen::MatrixXd expected = ata_inv.cast<double>() * s2;

  NonlinearProblem p = Linear(a, b, Eigen::Vector2d(0, 0));
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_LE((s.x - ref).cwiseAbs().maxCoeff(), 1e-8);
  ASSERT_EQ(s.covariance.rows(), 2);
  EXPECT_LE((s.covariance - expected).cwiseAbs().maxCoeff(),
            1e-8 * expected.cwiseAbs().maxCoeff());

  // Whitened residuals: no variance estimate, (A'A)^-1 itself.
  p.residuals_whitened = true;
  const NonlinearSolution w = Solver()->Solve(p);
  EXPECT_LE((w.covariance - ata_inv.cast<double>()).cwiseAbs().maxCoeff(), 1e-10);
}

TEST_P(NonlinearSolverTest, SingularJacobianGivesNoCovariance) {
  Eigen::MatrixXd a(3, 2);
  a << 1, 2, 2, 4, 3, 6;  // rank 1
  NonlinearProblem p = Linear(a, Eigen::Vector3d(1, 2, 3), Eigen::Vector2d(0, 0));
  const NonlinearSolution s = Solver()->Solve(p);
  EXPECT_EQ(s.covariance.size(), 0);
  EXPECT_NEAR((a * s.x - Eigen::Vector3d(1, 2, 3)).norm(), 0, 1e-8);
}

TEST_P(NonlinearSolverTest, IterationLimitIsNoConvergence) {
  NonlinearSolverOptions options;
  options.max_iterations = 2;
  const NonlinearSolution s = Solver(options)->Solve(Rosenbrock());
  EXPECT_EQ(s.summary.status, SolverStatus::kNoConvergence) << s.summary.message;
  EXPECT_LE(s.summary.iterations, 2);
}

TEST_P(NonlinearSolverTest, BadOptionsNameTheField) {
  const auto where = [this](const NonlinearSolverOptions& options) -> std::string {
    try {
      Solver(options);
    } catch (const InputError& e) {
      return e.where() + " | " + e.what();
    }
    return "no error";
  };
  NonlinearSolverOptions o;
  o.max_iterations = -3;
  EXPECT_EQ(where(o),
            "solver.max_iterations | solver.max_iterations: must be positive, got -3");
  o = {};
  o.trust_region = "newton";
  EXPECT_NE(where(o).find("solver.trust_region | "), std::string::npos);
  EXPECT_NE(where(o).find("levenberg_marquardt, dogleg"), std::string::npos);
  o = {};
  o.hessian = "bfgs";
  EXPECT_NE(where(o).find("solver.hessian | "), std::string::npos);
  EXPECT_NE(where(o).find("gauss_newton, limited_memory"), std::string::npos);
  o = {};
  o.gradient_tolerance = std::nan("");
  EXPECT_EQ(where(o).rfind("solver.gradient_tolerance | ", 0), 0u);
  o = {};
  o.kkt_tolerance = 0;
  EXPECT_EQ(where(o).rfind("solver.kkt_tolerance | ", 0), 0u);
  o = {};
  o.equality_tolerance = -1;
  EXPECT_EQ(where(o).rfind("solver.equality_tolerance | ", 0), 0u);
  o = {};
  o.max_outer_iterations = 0;
  EXPECT_EQ(where(o).rfind("solver.max_outer_iterations | ", 0), 0u);
  o = {};
  o.initial_trust_region = 0;
  EXPECT_EQ(where(o).rfind("solver.initial_trust_region | ", 0), 0u);
  o = {};
  o.max_restarts = -1;
  EXPECT_EQ(where(o).rfind("solver.max_restarts | ", 0), 0u);
}

TEST_P(NonlinearSolverTest, InvalidProblemThrowsBeforeAnyEvaluation) {
  int calls = 0;
  NonlinearProblem p = Rosenbrock();
  const auto inner = p.evaluate;
  p.evaluate = [&calls, inner](const Eigen::VectorXd& x, Eigen::VectorXd* r,
                               Eigen::MatrixXd* j, std::string* why) {
    ++calls;
    return inner(x, r, j, why);
  };
  NonlinearProblem crossed = p;
  crossed.lower = Eigen::Vector2d(0, 0);
  crossed.upper = Eigen::Vector2d(-1, 1);
  crossed.initial = Eigen::Vector2d(0, 0);
  try {
    Solver()->Solve(crossed);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "nonlinear problem");
    EXPECT_NE(std::string(e.what()).find("lower bound 0 > upper bound -1"),
              std::string::npos)
        << e.what();
  }
  NonlinearProblem nan_start = p;
  nan_start.initial[1] = std::nan("");
  EXPECT_THROW(Solver()->Solve(nan_start), InputError);
  EXPECT_EQ(calls, 0);
}

TEST_P(NonlinearSolverTest, ConcurrentSolvesBothSucceed) {
  NonlinearSolution first, second;
  const auto solver = Solver();
  std::thread a([&] { first = solver->Solve(Rosenbrock()); });
  std::thread b([&] { second = solver->Solve(Rosenbrock()); });
  a.join();
  b.join();
  EXPECT_EQ(first.summary.status, SolverStatus::kSolved);
  EXPECT_EQ(second.summary.status, SolverStatus::kSolved);
  EXPECT_NEAR((first.x - second.x).norm(), 0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Backends, NonlinearSolverTest,
                         ::testing::ValuesIn(AvailableNonlinearSolvers()),
                         [](const ::testing::TestParamInfo<std::string>& backend) {
                           return backend.param;
                         });

// The restart is shared by both backends; Ceres is the one that stops on this
// plateau (Ipopt's first, objective-scaled step leaves it).
TEST(NonlinearSolverRestart, CeresLeavesADegenerateStationaryPoint) {
  const Eigen::Vector2d certified(2.1380940889E+02, 5.4723748542E-01);
  NonlinearSolverOptions no_restarts;
  no_restarts.max_restarts = 0;
  const NonlinearSolution plateau =
      CreateNonlinearSolver("ceres", no_restarts)->Solve(BoxBodOnItsPlateau());
  EXPECT_GT(plateau.summary.cost, 4000) << plateau.summary.message;
  const NonlinearSolution s = CreateNonlinearSolver("ceres")->Solve(BoxBodOnItsPlateau());
  EXPECT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_NEAR(s.x[0], certified[0], 1e-6 * certified[0]) << s.summary.message;
  EXPECT_NEAR(s.x[1], certified[1], 1e-6 * certified[1]);
  EXPECT_NE(s.summary.message.find("degenerate stationary point"), std::string::npos)
      << s.summary.message;
  EXPECT_LT(s.summary.cost, 600);
}

TEST(NonlinearSolverFactory, UnknownNameListsTheAvailableOnes) {
  try {
    CreateNonlinearSolver("lbfgs");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "solver.name");
    EXPECT_EQ(std::string(e.what()),
              "solver.name: unknown solver 'lbfgs' (available: ceres, ipopt)");
  }
  EXPECT_EQ(AvailableNonlinearSolvers(), (std::vector<std::string>{"ceres", "ipopt"}));
}

TEST(NonlinearSolverFactory, DirectlyConstructedBackendsCheckTheirOptions) {
  NonlinearSolverOptions o;
  o.max_iterations = 0;
  EXPECT_THROW(CeresSolver(o).Solve(Rosenbrock()), InputError);
  EXPECT_THROW(IpoptSolver(o).Solve(Rosenbrock()), InputError);
}

// CheckKkt on hand-made points of min 0.5 |A x - b|^2 (SmallA, SmallB).

TEST(CheckKkt, OptimalPointWithActiveUpperBound) {
  const Eigen::Vector2d x(1.5, 1.25), g(-0.75, 0);
  const KktReport r = CheckKkt(x, g, Eigen::Vector2d(-kInf, 0), Eigen::Vector2d(1.5, 10),
                               {}, {}, {}, 2.0);
  EXPECT_EQ(r.residual(), 0);
  EXPECT_EQ(r.active_upper, std::vector<int>{0});
  EXPECT_TRUE(r.active_lower.empty());
  EXPECT_EQ(r.bound_multipliers[0], -0.75);
  EXPECT_EQ(r.bound_multipliers[1], 0);
  EXPECT_NE(r.Describe().find("KKT residual 0"), std::string::npos) << r.Describe();
}

TEST(CheckKkt, WrongSignMultiplierIsReportedRelativeToScale) {
  // The gradient pushes x1 further up: decreasing x1 would lower the cost.
  const Eigen::Vector2d x(1.5, 1.25), g(0.75, 0);
  const KktReport r = CheckKkt(x, g, Eigen::Vector2d(-kInf, 0), Eigen::Vector2d(1.5, 10),
                               {}, {}, {}, 2.0);
  EXPECT_DOUBLE_EQ(r.sign, 0.375);
  EXPECT_EQ(r.stationarity, 0);
  EXPECT_DOUBLE_EQ(r.residual(), 0.375);
}

TEST(CheckKkt, NonzeroGradientOffTheBoundsIsStationarityError) {
  const Eigen::Vector2d x(1.0, 1.25), g(-0.75, 0.5);
  const KktReport r = CheckKkt(x, g, Eigen::Vector2d(-kInf, 0), Eigen::Vector2d(1.5, 10),
                               {}, {}, {}, 0.0);  // scale <= 0 means 1
  EXPECT_DOUBLE_EQ(r.stationarity, 0.75);
  EXPECT_TRUE(r.active_upper.empty());
}

TEST(CheckKkt, InfeasiblePointIsReportedAbsolutely) {
  const Eigen::Vector2d x(2.0, -0.1), g(0, 0);
  const KktReport r =
      CheckKkt(x, g, Eigen::Vector2d(-kInf, 0), Eigen::Vector2d(1.5, 10),
               Eigen::RowVector2d(1, 1), Eigen::VectorXd::Constant(1, 1.0), {}, 100.0);
  EXPECT_DOUBLE_EQ(r.feasibility, 0.9);  // x1 + x2 - 1; the bounds are off by 0.5, 0.1
  EXPECT_DOUBLE_EQ(r.residual(), 0.9);
}

TEST(CheckKkt, EqualityMultiplierByLeastSquares) {
  // x = (1, 0) is optimal on x1 + x2 = 1 with g = (-3, -3) = C' mu, mu = -3.
  const KktReport r =
      CheckKkt(Eigen::Vector2d(1, 0), Eigen::Vector2d(-3, -3), {}, {},
               Eigen::RowVector2d(1, 1), Eigen::VectorXd::Constant(1, 1.0), {}, 3.0);
  EXPECT_NEAR(r.equality_multipliers[0], -3, 1e-14);
  EXPECT_LE(r.residual(), 1e-15);
  // A gradient with a component along the constraint is not stationary.
  const KktReport bad =
      CheckKkt(Eigen::Vector2d(1, 0), Eigen::Vector2d(-3, -1), {}, {},
               Eigen::RowVector2d(1, 1), Eigen::VectorXd::Constant(1, 1.0), {}, 1.0);
  EXPECT_NEAR(bad.stationarity, 1.0, 1e-14);
}

TEST(CheckKkt, FixedUnknownsAreExcludedFromStationarity) {
  const KktReport r = CheckKkt(Eigen::Vector2d(0.5, 1.75), Eigen::Vector2d(-1.5, 0), {},
                               {}, {}, {}, {{0, 0.5}}, 1.0);
  EXPECT_EQ(r.residual(), 0);
  const KktReport moved = CheckKkt(Eigen::Vector2d(0.6, 1.75), Eigen::Vector2d(-1.5, 0),
                                   {}, {}, {}, {}, {{0, 0.5}}, 1.0);
  EXPECT_NEAR(moved.feasibility, 0.1, 1e-15);
}

TEST(CheckKkt, EqualBoundsAcceptEitherSign) {
  const KktReport r =
      CheckKkt(Eigen::Vector2d(1, 0), Eigen::Vector2d(-2, 0), Eigen::Vector2d(1, -1),
               Eigen::Vector2d(1, 1), {}, {}, {}, 1.0);
  EXPECT_EQ(r.residual(), 0);
  EXPECT_EQ(r.active_upper, std::vector<int>{0});
}

// NonlinearProblem itself.

TEST(NonlinearProblem, ValidateSaysWhatIsWrong) {
  NonlinearProblem p = Rosenbrock();
  EXPECT_EQ(p.Validate().ToString(), "");
  NonlinearProblem q = p;
  q.lower = Eigen::Vector2d(-2, 0);
  q.upper = Eigen::Vector2d(2, 0.5);
  EXPECT_NE(
      q.Validate().ToString().find("the start 1 of x2 is outside its bounds [0, 0.5]"),
      std::string::npos)
      << q.Validate().ToString();
  q = p;
  q.fixed = {{0, 1.0}, {0, 2.0}};
  EXPECT_EQ(q.Validate().ToString(), "x1 is fixed twice");
  q = p;
  q.fixed = {{0, 1.0}, {1, 2.0}};
  EXPECT_EQ(q.Validate().ToString(), "every parameter is fixed");
  q = p;
  q.fixed = {{5, 1.0}};
  EXPECT_EQ(q.Validate().ToString(), "fixed parameter index 5 is outside 0..1");
  q = p;
  q.lower = Eigen::Vector3d(0, 0, 0);
  EXPECT_NE(q.Validate().ToString().find("bounds have 3 lower"), std::string::npos);
  q = p;
  q.equality_matrix = Eigen::MatrixXd::Ones(1, 3);
  q.equality_rhs = Eigen::VectorXd::Ones(1);
  EXPECT_NE(q.Validate().ToString().find("equality_matrix is 1 x 3"), std::string::npos);
  q = p;
  q.evaluate = nullptr;
  EXPECT_EQ(q.Validate().ToString(), "no evaluate function");
  q = p;
  q.num_residuals = 0;
  EXPECT_EQ(q.Validate().ToString(), "num_residuals must be positive, got 0");
  // A NaN start of a fixed parameter is harmless: the fixed value replaces it.
  q = p;
  q.initial[0] = std::nan("");
  q.fixed = {{0, 1.0}};
  EXPECT_EQ(q.Validate().ToString(), "");
}

TEST(NonlinearProblem, FreeUnknownsAndBounds) {
  NonlinearProblem p = Rosenbrock();
  EXPECT_FALSE(p.has_bounds());
  p.lower = Eigen::Vector2d(-kInf, -kInf);
  p.upper = Eigen::Vector2d(kInf, kInf);
  EXPECT_FALSE(p.has_bounds());  // infinite bounds are no bounds
  p.lower[0] = -5;
  EXPECT_TRUE(p.has_bounds());
  p.fixed = {{0, 1.0}};
  EXPECT_FALSE(p.has_bounds());  // only a fixed parameter is bounded
  EXPECT_TRUE(p.IsFixed(0));
  EXPECT_FALSE(p.IsFixed(1));
  EXPECT_EQ(p.FreeUnknowns(), std::vector<int>{1});
}

TEST(NonlinearProblem, AsNonlinearWeightsTheResiduals) {
  LinearProblem lp;
  lp.A = SmallA();
  lp.b = SmallB();
  lp.names = {"a", "b"};
  lp.row_weights = Eigen::Vector3d(1, 2, 3);
  lp.lower = Eigen::Vector2d(0.5, -kInf);
  lp.upper = Eigen::Vector2d(kInf, 0.25);
  lp.fixed = {};
  const NonlinearProblem p = AsNonlinear(lp, Eigen::Vector2d(0, 1));
  EXPECT_EQ(p.Validate().ToString(), "");
  EXPECT_EQ(p.num_residuals, 3);
  EXPECT_EQ(p.initial, Eigen::Vector2d(0.5, 0.25));  // clipped into the bounds
  EXPECT_TRUE(p.residuals_whitened);
  EXPECT_EQ(p.names, lp.names);
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  ASSERT_TRUE(p.evaluate(Eigen::Vector2d(1, 1), &r, &j, nullptr));
  EXPECT_EQ(r, Eigen::Vector3d(1 * (1 - 2), 2 * (1 - 1), 3 * (2 - 3)));
  EXPECT_EQ(j, lp.row_weights.asDiagonal() * lp.A);

  lp.row_weights.resize(0);
  const NonlinearProblem unweighted = AsNonlinear(lp);
  EXPECT_FALSE(unweighted.residuals_whitened);
  EXPECT_EQ(unweighted.initial, Eigen::Vector2d(0.5, 0));  // zero, clipped
  EXPECT_THROW(AsNonlinear(lp, Eigen::Vector3d(0, 0, 0)), InputError);
}

// The linear adapters: bounded linear least squares on both backends.

LinearProblem BoundedRegression() {
  // 10 rows, 3 unknowns; the unconstrained x3 would be about 0.6, above its bound.
  LinearProblem p;
  const int m = 10;
  p.A.resize(m, 3);
  p.b.resize(m);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (int i = 0; i < m; ++i) {
    const double t = 0.1 * i;
    p.A.row(i) << 1, t, t * t;
    p.b[i] = 1.0 - 0.5 * t + 0.6 * t * t + noise(rng);
  }
  p.names = {"c0", "c1", "c2"};
  p.lower = Eigen::Vector3d(-kInf, -kInf, -kInf);
  p.upper = Eigen::Vector3d(kInf, kInf, 0.3);
  return p;
}

TEST(BackendLinearSolvers, BothBackendsAgreeOnABoundedProblem) {
  const LinearProblem p = BoundedRegression();
  const LinearSolution c = CeresLinearSolver().Solve(p);
  const LinearSolution i = IpoptLinearSolver().Solve(p);
  EXPECT_EQ(c.summary.status, SolverStatus::kSolved) << c.summary.message;
  EXPECT_EQ(i.summary.status, SolverStatus::kSolved) << i.summary.message;
  EXPECT_LE((c.x - i.x).cwiseAbs().maxCoeff(), 1e-8);
  // Reference: x3 on its bound, the rest by least squares on the other columns.
  const Eigen::MatrixXd a12 = p.A.leftCols(2);
  const Eigen::VectorXd x12 = a12.colPivHouseholderQr().solve(p.b - 0.3 * p.A.col(2));
  EXPECT_NEAR(c.x[2], 0.3, 1e-9);
  EXPECT_LE((c.x.head(2) - x12).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LE((c.residual - (p.A * c.x - p.b)).norm(), 1e-14);
  for (const LinearSolution* s : {&c, &i}) {
    ASSERT_EQ(s->standard_error.size(), 3);
    EXPECT_TRUE(s->noise_estimated);
    EXPECT_EQ(s->confidence_level, 0.95);
    EXPECT_TRUE((s->interval_lower.array() < s->x.array()).all());
    EXPECT_TRUE((s->interval_upper.array() > s->x.array()).all());
    ASSERT_EQ(s->summary.warnings.size(), 1u);
    EXPECT_NE(s->summary.warnings[0].find("c2"), std::string::npos);
    EXPECT_EQ(s->identifiability.rank, 0);  // not analysed
  }
}

TEST(BackendLinearSolvers, UnboundedIntervalUsesStudentT) {
  LinearProblem p = BoundedRegression();
  p.lower.resize(0);
  p.upper.resize(0);
  const LinearSolution s = IpoptLinearSolver().Solve(p);
  ASSERT_EQ(s.summary.status, SolverStatus::kSolved) << s.summary.message;
  EXPECT_TRUE(s.summary.warnings.empty());
  // t quantile 0.975 with 10 - 3 = 7 degrees of freedom.
  const double t7 = 2.364624251592785;
  EXPECT_LE(((s.interval_upper - s.x) - t7 * s.standard_error).cwiseAbs().maxCoeff(),
            1e-12);
  // Known noise: normal quantile, covariance (A'W^2A)^-1.
  p.row_weights = Eigen::VectorXd::Constant(10, 20.0);
  const LinearSolution k = CeresLinearSolver().Solve(p);
  EXPECT_FALSE(k.noise_estimated);
  const Eigen::MatrixXd expected = (400.0 * p.A.transpose() * p.A).inverse();
  EXPECT_LE((k.covariance - expected).cwiseAbs().maxCoeff(),
            1e-8 * expected.cwiseAbs().maxCoeff());
  EXPECT_LE(((k.interval_upper - k.x) - 1.959963984540054 * k.standard_error)
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
}

TEST(BackendLinearSolvers, InvalidInputThrows) {
  LinearProblem p = BoundedRegression();
  p.b.resize(3);
  EXPECT_THROW(CeresLinearSolver().Solve(p), InputError);
  LinearSolverOptions o;
  o.confidence_level = 1.5;
  try {
    IpoptLinearSolver(o).Solve(BoundedRegression());
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "solver.confidence_level");
  }
}

}  // namespace
}  // namespace femup
