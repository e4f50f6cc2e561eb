// Discrete ill-posed test problems (evaluation/include/femup/evaluation/ill_posed.h),
// checked against facts of the continuous problems rather than stored output:
// integrals known in closed form, consistency A x_exact ~ b to the order of the
// discretisation, kernel symmetries, the known spectrum of the Green's function
// in deriv2, the singular value decay that makes them ill-posed, and the noise
// convention. Fixed seeds throughout.
#include "femup/evaluation/ill_posed.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace {

const double kPi = 3.14159265358979323846;

double RelativeResidual(const IllPosedProblem& p) {
  return (p.A * p.x_exact - p.b).norm() / p.b.norm();
}

// Singular values, largest first.
Eigen::VectorXd SingularValues(const Eigen::MatrixXd& A) {
  return Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
}

// Composite Simpson's rule with 2m subintervals.
double Simpson(const std::function<double(double)>& f, double a, double b, int m) {
  const double h = (b - a) / (2 * m);
  double sum = f(a) + f(b);
  for (int k = 1; k < 2 * m; ++k) sum += (k % 2 == 1 ? 4 : 2) * f(a + k * h);
  return sum * h / 3;
}

double MaxAbs(const Eigen::MatrixXd& M) { return M.cwiseAbs().maxCoeff(); }

// max |A(i,j) - A(n-1-j, n-1-i)|: zero when K(s,t) = K(c-t, c-s) on the grid.
double PersymmetryError(const Eigen::MatrixXd& A) {
  const int n = static_cast<int>(A.rows());
  double err = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      err = std::max(err, std::abs(A(i, j) - A(n - 1 - j, n - 1 - i)));
    }
  }
  return err;
}

// Runs `make` and returns the InputError's message, or "" if nothing is thrown.
std::string ErrorOf(const std::function<void()>& make) {
  try {
    make();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "ill-posed problem");
    return e.what();
  }
  return "";
}

TEST(IllPosed, NamesAndFactoryGiveSquareProblemsOfOrderN) {
  const std::vector<std::string> names = IllPosedProblemNames();
  ASSERT_EQ(names.size(), 5u);
  for (const std::string& name : names) {
    const IllPosedProblem p = MakeIllPosedProblem(name, 16);
    EXPECT_EQ(p.name, name);
    EXPECT_EQ(p.A.rows(), 16);
    EXPECT_EQ(p.A.cols(), 16);
    EXPECT_EQ(p.b.size(), 16);
    EXPECT_EQ(p.x_exact.size(), 16);
    EXPECT_TRUE(p.A.allFinite() && p.b.allFinite() && p.x_exact.allFinite()) << name;
  }
}

// Galerkin with box functions of width h on [-6, 6]: sqrt(h) * (sum of entries)
// is the integral of the function, and h * sum(A) is the double integral of
// K(s,t) = phi(s - t), all exact: int phi = 6, int g = (int phi)^2 = 36 (g is the
// convolution phi * phi, whose support lies inside [-6, 6]) and
// int int phi(s - t) = int_{-3}^{3} (12 - |w|) phi(w) dw = 63 + 36 / pi^2.
TEST(IllPosed, PhillipsIntegralsAreExact) {
  const int n = 64;
  const double h = 12.0 / n;
  const IllPosedProblem p = Phillips(n);
  EXPECT_NEAR(p.x_exact.sum() * std::sqrt(h), 6.0, 1e-13);
  EXPECT_NEAR(p.b.sum() * std::sqrt(h), 36.0, 1e-12);
  EXPECT_NEAR(p.A.sum() * h, 63.0 + 36.0 / (kPi * kPi), 1e-12);
}

// K(s,t) = phi(s - t) on a uniform grid: symmetric Toeplitz, and zero beyond
// |i - j| = n/4 since phi vanishes for |s - t| >= 3 = (n/4) h. f = phi vanishes
// outside [-3, 3], i.e. outside the middle n/2 cells.
TEST(IllPosed, PhillipsIsSymmetricToeplitzAndBanded) {
  const int n = 32;
  const IllPosedProblem p = Phillips(n);
  EXPECT_LE(MaxAbs(p.A - p.A.transpose()), 1e-15 * MaxAbs(p.A));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int m = std::abs(i - j);
      if (m > n / 4) {
        EXPECT_EQ(p.A(i, j), 0.0) << i << "," << j;
      } else {
        EXPECT_NEAR(p.A(i, j), p.A(0, m), 1e-15) << i << "," << j;
        EXPECT_GT(p.A(i, j), 0.0) << i << "," << j;
      }
    }
    const bool inside = i >= n / 4 && i < 3 * n / 4;
    EXPECT_EQ(p.x_exact[i] > 0, inside) << i;
  }
}

// A x_exact differs from b by <phi_i, K (f - P f)>, P the projection on box
// functions: O(h^2) for a smooth K. Measured 3.9e-3 at n = 32 and 9.7e-4 at
// n = 64; assert the size and the second-order rate.
TEST(IllPosed, PhillipsResidualIsSecondOrder) {
  const double r32 = RelativeResidual(Phillips(32)), r64 = RelativeResidual(Phillips(64));
  EXPECT_LT(r64, 2e-3);
  EXPECT_GT(r32 / r64, 3.5);
  EXPECT_LT(r32 / r64, 4.5);
}

// Mildly ill-posed: ill-conditioned but, unlike shaw or baart, of full
// numerical rank. Measured cond = 4.4e5 at n = 64, growing like n^4.
TEST(IllPosed, PhillipsIsMildlyIllConditioned) {
  const Eigen::VectorXd s64 = SingularValues(Phillips(64).A);
  const Eigen::VectorXd s128 = SingularValues(Phillips(128).A);
  const double cond64 = s64[0] / s64[63], cond128 = s128[0] / s128[127];
  EXPECT_GT(cond64, 1e4);
  EXPECT_LT(cond64, 1e7);
  EXPECT_GT(cond128 / cond64, 8.0);
}

// Midpoint rule: x_exact samples f at t_i = -pi/2 + (i + 1/2) pi/n, and the
// toolbox defines b = A x_exact.
TEST(IllPosed, ShawSamplesTheSolutionAtMidpoints) {
  const int n = 64;
  const IllPosedProblem p = Shaw(n);
  for (int i = 0; i < n; ++i) {
    const double t = -kPi / 2 + (i + 0.5) * kPi / n;
    const double f =
        2 * std::exp(-6 * (t - 0.8) * (t - 0.8)) + std::exp(-2 * (t + 0.5) * (t + 0.5));
    EXPECT_NEAR(p.x_exact[i], f, 1e-14) << i;
  }
  EXPECT_LE(RelativeResidual(p), 1e-15);
}

// K(s,t) = (cos s + cos t)^2 (sin u / u)^2, u = pi (sin s + sin t), is symmetric
// and unchanged by (s,t) -> (-t,-s); on the anti-diagonal u = 0 and
// K = (2 cos s)^2.
TEST(IllPosed, ShawKernelSymmetries) {
  const int n = 32;
  const double h = kPi / n;
  const IllPosedProblem p = Shaw(n);
  EXPECT_LE(MaxAbs(p.A - p.A.transpose()), 1e-15 * MaxAbs(p.A));
  EXPECT_LE(PersymmetryError(p.A), 1e-15 * MaxAbs(p.A));
  for (int i = 0; i < n; ++i) {
    const double c = std::cos(-kPi / 2 + (i + 0.5) * h);
    EXPECT_NEAR(p.A(i, n - 1 - i), h * 4 * c * c, 1e-14) << i;
  }
}

// b_i is the midpoint rule for g(s_i) = int K(s_i,t) f(t) dt, so it differs from
// g (here by Simpson's rule on 4096 intervals, error far below 1e-10) by O(h^2).
// Measured max error 3.0e-5 at n = 32 and 7.6e-6 at n = 64 (relative to max |b|).
TEST(IllPosed, ShawRightHandSideApproximatesTheIntegral) {
  auto g_error = [](int n) {
    const IllPosedProblem p = Shaw(n);
    double worst = 0;
    for (int i = 0; i < n; ++i) {
      const double s = -kPi / 2 + (i + 0.5) * kPi / n;
      auto integrand = [s](double t) {
        const double u = kPi * (std::sin(s) + std::sin(t));
        const double sinc = u == 0 ? 1.0 : std::sin(u) / u;
        const double k = (std::cos(s) + std::cos(t)) * sinc;
        return k * k *
               (2 * std::exp(-6 * (t - 0.8) * (t - 0.8)) +
                std::exp(-2 * (t + 0.5) * (t + 0.5)));
      };
      const double g = Simpson(integrand, -kPi / 2, kPi / 2, 2048);
      worst = std::max(worst, std::abs(p.b[i] - g) / p.b.cwiseAbs().maxCoeff());
    }
    return worst;
  };
  const double e32 = g_error(32), e64 = g_error(64);
  EXPECT_LT(e64, 2e-5);
  EXPECT_GT(e32 / e64, 3.5);
  EXPECT_LT(e32 / e64, 4.5);
}

// Severely ill-posed: the singular values fall geometrically to rounding level,
// so at n = 64 the matrix is numerically singular (Hansen 1994 uses shaw and
// baart as examples of this). Measured s_16/s_1 = 1.6e-11, s_32/s_1 = 1.6e-17.
TEST(IllPosed, ShawIsNumericallySingular) {
  const Eigen::VectorXd s = SingularValues(Shaw(64).A);
  EXPECT_LT(s[16] / s[0], 1e-9);
  EXPECT_LT(s[32] / s[0], 1e-15);
}

// Galerkin, box functions: sqrt(ht) * sum(x) = int_0^pi sin t dt = 2 exactly,
// and x_j / sqrt(ht) is the cell mean of sin, sin(t_mid) (1 + O(ht^2)).
TEST(IllPosed, BaartSolutionIsSineCellMeans) {
  const int n = 64;
  const double ht = kPi / n;
  const IllPosedProblem p = Baart(n);
  EXPECT_NEAR(p.x_exact.sum() * std::sqrt(ht), 2.0, 1e-13);
  for (int j = 0; j < n; ++j) {
    const double sin_mid = std::sin((j + 0.5) * ht);
    EXPECT_NEAR(p.x_exact[j] / std::sqrt(ht), sin_mid, ht * ht / 24 * sin_mid + 1e-15)
        << j;
  }
}

// Totals against closed forms (series). sqrt(hs) * sum(b) is composite Simpson
// for int_0^{pi/2} 2 sinh(s)/s ds = 2 Shi(pi/2), error O(hs^4) (measured 1.0e-10).
// sqrt(hs ht) * sum(A) integrates exactly in s and by composite Simpson in t,
// for int_0^{pi/2} int_0^pi exp(s cos t) dt ds = pi int_0^{pi/2} I0(s) ds; the
// t-integrand is even and 2 pi-periodic, so Simpson over [0, pi] is accurate to
// rounding (measured 4e-15).
TEST(IllPosed, BaartIntegralsMatchClosedForms) {
  const int n = 64;
  const double hs = kPi / (2 * n), ht = kPi / n, a = kPi / 2;
  const IllPosedProblem p = Baart(n);
  double shi = 0, bessel = 0, term_fact = 1;  // term_fact = (2k+1)! or (k!)^2
  for (int k = 0; k < 30; ++k) {
    term_fact = k == 0 ? 1 : term_fact * (2 * k) * (2 * k + 1);
    shi += std::pow(a, 2 * k + 1) / ((2 * k + 1) * term_fact);
  }
  term_fact = 1;
  for (int k = 0; k < 30; ++k) {
    term_fact = k == 0 ? 1 : term_fact * k * k;
    bessel += std::pow(a / 2, 2 * k) * a / ((2 * k + 1) * term_fact);
  }
  EXPECT_NEAR(p.b.sum() * std::sqrt(hs), 2 * shi, 1e-9);
  EXPECT_NEAR(p.A.sum() * std::sqrt(hs * ht), kPi * bessel, 1e-12);
}

// Galerkin errors O(h^2); measured 3.0e-4 at n = 32 and 7.6e-5 at n = 64.
TEST(IllPosed, BaartResidualIsSecondOrder) {
  const double r32 = RelativeResidual(Baart(32)), r64 = RelativeResidual(Baart(64));
  EXPECT_LT(r64, 2e-4);
  EXPECT_GT(r32 / r64, 3.5);
  EXPECT_LT(r32 / r64, 4.5);
}

// Measured s_16/s_1 = 2.2e-17 at n = 64 (s and t on different intervals, so
// A is not symmetric).
TEST(IllPosed, BaartIsNumericallySingular) {
  const IllPosedProblem p = Baart(64);
  EXPECT_GT(MaxAbs(p.A - p.A.transpose()), 0.1);
  const Eigen::VectorXd s = SingularValues(p.A);
  EXPECT_LT(s[16] / s[0], 1e-15);
}

// K is the Green's function of d^2/ds^2 with zero end values, so (K 1)(s) =
// s (s - 1)/2; a constant is represented exactly by box functions (coefficients
// sqrt(h)), and the Galerkin entries are exact integrals, so
// A (sqrt(h) 1) equals the cell integrals of s (s - 1)/2 over sqrt(h).
TEST(IllPosed, Deriv2IsExactOnConstants) {
  const int n = 40;
  const double h = 1.0 / n;
  const IllPosedProblem p = Deriv2(n);
  const Eigen::VectorXd Ac = p.A * Eigen::VectorXd::Constant(n, std::sqrt(h));
  auto primitive = [](double s) { return s * s * s / 6 - s * s / 4; };
  for (int i = 0; i < n; ++i) {
    const double expected = (primitive((i + 1) * h) - primitive(i * h)) / std::sqrt(h);
    EXPECT_NEAR(Ac[i], expected, 1e-15) << i;
  }
  // Totals: int_0^1 t dt = 1/2 and int_0^1 (s^3 - s)/6 ds = -1/24.
  EXPECT_NEAR(p.x_exact.sum() * std::sqrt(h), 0.5, 1e-14);
  EXPECT_NEAR(p.b.sum() * std::sqrt(h), -1.0 / 24, 1e-15);
}

// For f(t) = t the Galerkin error K (f - P f) vanishes cell-wise on average:
// w = f - P f is a sawtooth with zero cell means, and the solution of v'' = w,
// v(0) = v(1) = 0 is, on each cell, an odd cubic about the midpoint. So the
// toolbox's b equals A x_exact in exact arithmetic; measured 6e-17 at n = 64.
TEST(IllPosed, Deriv2RightHandSideIsExactlyAx) {
  EXPECT_LT(RelativeResidual(Deriv2(64)), 1e-13);
  EXPECT_LT(RelativeResidual(Deriv2(7)), 1e-13);
}

// The Green's operator is symmetric and negative definite with eigenvalues
// -1/(k pi)^2; the Galerkin matrix's largest ones converge to these. It is also
// unchanged by (s,t) -> (1-t, 1-s). Its smallest is O(h^2), so cond = O(n^2)
// (measured at n = 64: lambda_k (k pi)^2 = -0.9998, -0.9992, -0.9982 for
// k = 1..3; smallest |lambda| 2.03e-5; cond 5.0e3 = 1.2 n^2): mildly ill-posed.
TEST(IllPosed, Deriv2SpectrumIsTheGreensFunctions) {
  const int n = 64;
  const IllPosedProblem p = Deriv2(n);
  EXPECT_LE(MaxAbs(p.A - p.A.transpose()), 1e-15 * MaxAbs(p.A));
  EXPECT_LE(PersymmetryError(p.A), 1e-15 * MaxAbs(p.A));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(p.A);
  const Eigen::VectorXd lambda = eig.eigenvalues();  // ascending: most negative first
  EXPECT_LT(lambda[n - 1], 0.0);
  for (int k = 1; k <= 3; ++k) {
    EXPECT_NEAR(lambda[k - 1] * (k * kPi) * (k * kPi), -1.0, 5e-3) << k;
  }
  const double cond = lambda.cwiseAbs().maxCoeff() / lambda.cwiseAbs().minCoeff();
  EXPECT_GT(cond, 0.5 * n * n);
  EXPECT_LT(cond, 2.0 * n * n);
}

// Midpoint rule on [0, 1]: x_exact = t at the midpoints, b = g at the midpoints
// with g(s) = int_0^1 sqrt(s^2 + t^2) t dt (checked here by Simpson's rule on
// 8192 intervals; measured agreement 2e-15), and
// A is symmetric since K is.
TEST(IllPosed, FoxgoodSamplesAtMidpoints) {
  const int n = 32;
  const IllPosedProblem p = Foxgood(n);
  EXPECT_LE(MaxAbs(p.A - p.A.transpose()), 1e-15 * MaxAbs(p.A));
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) / n;
    EXPECT_DOUBLE_EQ(p.x_exact[i], s);
    const double g =
        Simpson([s](double t) { return std::sqrt(s * s + t * t) * t; }, 0.0, 1.0, 4096);
    EXPECT_NEAR(p.b[i], g, 1e-12) << i;
    EXPECT_NEAR(p.A(i, i), std::sqrt(2.0) * s / n, 1e-16) << i;
  }
}

// Midpoint-rule error O(h^2); measured 1.4e-4 at n = 32 and 3.5e-5 at n = 64.
// Severely ill-posed: measured s_32/s_1 = 1.8e-17 at n = 64.
TEST(IllPosed, FoxgoodResidualAndDecay) {
  const double r32 = RelativeResidual(Foxgood(32)), r64 = RelativeResidual(Foxgood(64));
  EXPECT_LT(r64, 1e-4);
  EXPECT_GT(r32 / r64, 3.5);
  EXPECT_LT(r32 / r64, 4.5);
  const Eigen::VectorXd s = SingularValues(Foxgood(64).A);
  EXPECT_LT(s[32] / s[0], 1e-15);
}

TEST(IllPosed, BadOrderThrowsNamingValueAndRule) {
  struct Case {
    std::function<void()> make;
    std::string value, rule;
  };
  const std::vector<Case> cases = {
      {[] { Phillips(6); }, "n = 6", "multiple of 4"},
      {[] { Phillips(0); }, "n = 0", "multiple of 4"},
      {[] { Shaw(7); }, "n = 7", "even"},
      {[] { Baart(5); }, "n = 5", "even"},
      {[] { Deriv2(1); }, "n = 1", "at least 2"},
      {[] { Foxgood(-3); }, "n = -3", "at least 2"},
      {[] { MakeIllPosedProblem("phillips", 10); }, "n = 10", "multiple of 4"},
  };
  for (const Case& c : cases) {
    const std::string message = ErrorOf(c.make);
    EXPECT_NE(message.find(c.value), std::string::npos) << message;
    EXPECT_NE(message.find(c.rule), std::string::npos) << message;
  }
}

TEST(IllPosed, UnknownNameThrowsListingTheNames) {
  try {
    MakeIllPosedProblem("heat", 16);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "ill-posed problem");
    const std::string message = e.what();
    EXPECT_NE(message.find("heat"), std::string::npos) << message;
    for (const std::string& name : IllPosedProblemNames()) {
      EXPECT_NE(message.find(name), std::string::npos) << message;
    }
  }
}

TEST(IllPosed, RelativeNoiseHasTheRequestedNorm) {
  const Eigen::VectorXd b = Shaw(64).b;
  for (double level : {1e-3, 1e-2, 0.1}) {
    const Eigen::VectorXd noisy = AddRelativeNoise(b, level, 42);
    EXPECT_NEAR((noisy - b).norm() / (level * b.norm()), 1.0, 1e-12) << level;
  }
  EXPECT_EQ(AddRelativeNoise(b, 0.0, 42), b);
}

TEST(IllPosed, RelativeNoiseIsReproducibleBySeed) {
  const Eigen::VectorXd b = Foxgood(32).b;
  const Eigen::VectorXd first = AddRelativeNoise(b, 0.01, 7);
  EXPECT_EQ(AddRelativeNoise(b, 0.01, 7), first);
  EXPECT_GT((AddRelativeNoise(b, 0.01, 8) - first).norm(), 1e-3 * 0.01 * b.norm());
}

TEST(IllPosed, RelativeNoiseRejectsBadLevels) {
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(4);
  for (double level : {-0.1, std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(AddRelativeNoise(b, level, 1), InputError) << level;
  }
}

}  // namespace
}  // namespace femup
