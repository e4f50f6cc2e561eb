// Laplace evidence and posterior class probabilities
// (solvers/include/femup/solvers/model_evidence.h), checked against the evidence
// integral computed here by quadrature over the prior box for linear Gaussian
// models (where Laplace's approximation is exact up to the prior's edges), the
// header's closed forms and a softmax by hand.
//
// The header leaves out the constant -n/2 log(2 pi T) of the likelihood, so with
// whitened residuals r(x) = A x - b and a uniform prior on the box (volume V):
//   log Z = log( (1/V) * integral over the box of exp(-chi2(x) / (2 T)) dx ).
#include "femup/solvers/model_evidence.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace {

const double kPi = std::acos(-1.0);
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Composite Simpson weights for `intervals` (even) intervals over [a, b].
void Simpson(double a, double b, int intervals, std::vector<double>* x,
             std::vector<double>* w) {
  const double h = (b - a) / intervals;
  x->resize(intervals + 1);
  w->resize(intervals + 1);
  for (int i = 0; i <= intervals; ++i) {
    (*x)[i] = a + i * h;
    (*w)[i] = h / 3 * (i == 0 || i == intervals ? 1 : (i % 2 == 1 ? 4 : 2));
  }
}

// Least-squares solution and chi2 of r = A x - b (whitened).
struct LinearFit {
  Eigen::VectorXd x;
  double chi2 = 0;
};
LinearFit Fit(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  LinearFit f;
  f.x = a.colPivHouseholderQr().solve(b);
  f.chi2 = (a * f.x - b).squaredNorm();
  return f;
}

// log( (1/V) integral over the box of exp(-||A x - b||^2 / (2 T)) ), by
// composite Simpson (1 or 2 parameters), relative to exp(-chi2_min / (2 T)) to
// avoid underflow, then shifted back.
double LogEvidenceByQuadrature(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                               const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                               double temperature, int intervals) {
  // chi2(x) = chi2_min + (x - x*)' A'A (x - x*) exactly for a linear model.
  const LinearFit fit = Fit(a, b);
  const double chi2_min = fit.chi2;
  const Eigen::MatrixXd h = a.transpose() * a;
  const auto f = [&](const Eigen::VectorXd& x) {
    const Eigen::VectorXd d = x - fit.x;
    return std::exp(-d.dot(h * d) / (2 * temperature));
  };
  std::vector<double> x0, w0, x1, w1;
  Simpson(lower[0], upper[0], intervals, &x0, &w0);
  double integral = 0;
  if (a.cols() == 1) {
    for (std::size_t i = 0; i < x0.size(); ++i)
      integral += w0[i] * f(Eigen::VectorXd::Constant(1, x0[i]));
  } else {
    Simpson(lower[1], upper[1], intervals, &x1, &w1);
    Eigen::VectorXd x(2);
    for (std::size_t i = 0; i < x0.size(); ++i) {
      x[0] = x0[i];
      double inner = 0;
      for (std::size_t j = 0; j < x1.size(); ++j) {
        x[1] = x1[j];
        inner += w1[j] * f(x);
      }
      integral += w0[i] * inner;
    }
  }
  const double volume = (upper - lower).prod();
  return std::log(integral / volume) - chi2_min / (2 * temperature);
}

Eigen::VectorXd Vec(std::initializer_list<double> v) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

// A 1-parameter model: J'J = 14, posterior sigma ~0.27.
Eigen::MatrixXd A1() { return Vec({3.0, -1.0, 2.0}); }
Eigen::VectorXd B1() { return Vec({1.2, 0.3, -0.5}); }

// A 2-parameter model with correlated parameters.
Eigen::MatrixXd A2() {
  Eigen::MatrixXd a(4, 2);
  a << 2.0, 1.0,  //
      1.0, 1.5,   //
      -0.5, 2.0,  //
      1.0, -0.3;
  return a;
}
Eigen::VectorXd B2() { return Vec({0.7, -1.1, 2.0, 0.4}); }

// ----------------------------------------------------------------------------

TEST(LaplaceEvidence, OneParameterLinearGaussianMatchesQuadrature) {
  const Eigen::MatrixXd a = A1();
  const Eigen::VectorXd b = B1();
  const LinearFit fit = Fit(a, b);
  // Box ~1700 posterior sigmas wide.
  const Eigen::VectorXd lower = Vec({-200}), upper = Vec({250});
  const ModelEvidence e = LaplaceEvidence(fit.chi2, a, fit.x, lower, upper);
  const double reference = LogEvidenceByQuadrature(a, b, lower, upper, 1.0, 40000);
  EXPECT_NEAR(e.log_evidence, reference, 1e-3);
  // The closed form for an unbounded Gaussian, as a cross-check of the quadrature.
  const double gaussian =
      -0.5 * fit.chi2 + 0.5 * std::log(2 * kPi / 14.0) - std::log(450.0);
  EXPECT_NEAR(reference, gaussian, 1e-9);
  EXPECT_DOUBLE_EQ(e.chi2, fit.chi2);
  EXPECT_EQ(e.num_parameters, 1);
  EXPECT_NEAR(e.log_evidence, -0.5 * fit.chi2 + e.log_occam, 1e-12);
  ASSERT_EQ(e.sigma.size(), 1);
  EXPECT_NEAR(e.sigma[0], 1 / std::sqrt(14.0), 1e-6);
}

TEST(LaplaceEvidence, TwoParameterLinearGaussianMatchesQuadrature) {
  const Eigen::MatrixXd a = A2();
  const Eigen::VectorXd b = B2();
  const LinearFit fit = Fit(a, b);
  const Eigen::VectorXd lower = Vec({-60, -40}), upper = Vec({70, 90});
  const ModelEvidence e = LaplaceEvidence(fit.chi2, a, fit.x, lower, upper);
  // Step 130 / 2000 = 0.065, a sixth of the smallest conditional sigma (~0.37).
  const double reference = LogEvidenceByQuadrature(a, b, lower, upper, 1.0, 2000);
  EXPECT_NEAR(e.log_evidence, reference, 1e-3);
  const Eigen::Matrix2d h = a.transpose() * a;
  const double gaussian = -0.5 * fit.chi2 +
                          0.5 * std::log((2 * kPi) * (2 * kPi) / h.determinant()) -
                          std::log(130.0 * 130.0);
  EXPECT_NEAR(reference, gaussian, 1e-8);
  EXPECT_EQ(e.num_parameters, 2);
}

TEST(LaplaceEvidence, TemperatureTempersTheLikelihood) {
  // T: the stated variances times T, so the data enter as exp(-chi2 / (2 T)) and
  // H = J'J / T + 2 pi / range^2; chi2 is reported as given.
  const Eigen::MatrixXd a = A2();
  const Eigen::VectorXd b = B2();
  const LinearFit fit = Fit(a, b);
  // Boxes 400 wide: still > 300 posterior sigmas at T = 9.
  const Eigen::VectorXd lower = Vec({-200, -150}), upper = Vec({200, 250});
  for (double t : {1.0, 2.5, 9.0}) {
    SCOPED_TRACE(t);
    const ModelEvidence e = LaplaceEvidence(fit.chi2, a, fit.x, lower, upper, t);
    EXPECT_NEAR(e.log_evidence, LogEvidenceByQuadrature(a, b, lower, upper, t, 3000),
                1e-3);
    EXPECT_DOUBLE_EQ(e.chi2, fit.chi2);
    EXPECT_NEAR(e.log_evidence, -0.5 * fit.chi2 / t + e.log_occam, 1e-12);
    Eigen::Matrix2d h = a.transpose() * a / t;
    h(0, 0) += 2 * kPi / (400.0 * 400.0);
    h(1, 1) += 2 * kPi / (400.0 * 400.0);
    const Eigen::Vector2d sigma = h.inverse().diagonal().cwiseSqrt();
    EXPECT_NEAR(e.sigma[0], sigma[0], 1e-12 * sigma[0]);
    EXPECT_NEAR(e.sigma[1], sigma[1], 1e-12 * sigma[1]);
  }
  // Hotter noise: weaker data, smaller Occam penalty (wider posterior).
  const ModelEvidence cold = LaplaceEvidence(fit.chi2, a, fit.x, lower, upper, 1.0);
  const ModelEvidence hot = LaplaceEvidence(fit.chi2, a, fit.x, lower, upper, 4.0);
  // det(2 pi H^-1) grows by T^2 (up to the small prior term).
  EXPECT_NEAR(hot.log_occam - cold.log_occam, std::log(4.0), 1e-3);
}

TEST(LaplaceEvidence, SigmaIsTheLaplacePosteriorStandardDeviation) {
  // sigma = sqrt(diag(H^-1)), H = J'J + diag(2 pi / range^2) as the header has it
  // (12 / range^2, the prior's variance, before d990446). Ranges small enough for
  // the prior term to matter.
  std::mt19937 rng(20240611);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 1 + trial % 4, m = n + 3;
    Eigen::MatrixXd j(m, n);
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < n; ++c) j(r, c) = normal(rng);
    Eigen::VectorXd lower(n), upper(n);
    for (int i = 0; i < n; ++i) {
      lower[i] = normal(rng);
      upper[i] = lower[i] + 0.2 + std::abs(normal(rng));
    }
    const Eigen::VectorXd x = 0.5 * (lower + upper);
    const ModelEvidence e = LaplaceEvidence(1.5, j, x, lower, upper);
    Eigen::MatrixXd h = j.transpose() * j;
    for (int i = 0; i < n; ++i) h(i, i) += 2 * kPi / std::pow(upper[i] - lower[i], 2);
    const Eigen::VectorXd sigma = h.inverse().diagonal().cwiseSqrt();
    ASSERT_EQ(e.sigma.size(), n);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(e.sigma[i], sigma[i], 1e-10 * sigma[i]);
  }
}

TEST(LaplaceEvidence, BestFitAtABoundSubtractsLogTwo) {
  // With the best fit on the lower bound, only half of the Gaussian lies in the
  // box: the evidence integral halves.
  const Eigen::MatrixXd a = A1();
  const Eigen::VectorXd b = B1();
  const LinearFit fit = Fit(a, b);
  const double x = fit.x[0];
  const Eigen::VectorXd at = Vec({x});
  const ModelEvidence inside =
      LaplaceEvidence(fit.chi2, a, at, Vec({x - 200}), Vec({x + 250}));
  // Same width, best fit on the lower bound.
  const ModelEvidence lower_edge =
      LaplaceEvidence(fit.chi2, a, at, Vec({x}), Vec({x + 450}));
  const ModelEvidence upper_edge =
      LaplaceEvidence(fit.chi2, a, at, Vec({x - 450}), Vec({x}));
  EXPECT_NEAR(lower_edge.log_occam, inside.log_occam - std::log(2.0), 1e-12);
  EXPECT_NEAR(upper_edge.log_occam, inside.log_occam - std::log(2.0), 1e-12);
  EXPECT_NEAR(lower_edge.log_evidence,
              LogEvidenceByQuadrature(a, b, Vec({x}), Vec({x + 450}), 1.0, 40000), 1e-3);

  // Two parameters, both at bounds: log 2 each.
  const Eigen::MatrixXd a2 = A2();
  const LinearFit f2 = Fit(a2, B2());
  const ModelEvidence in2 = LaplaceEvidence(
      f2.chi2, a2, f2.x, (f2.x.array() - 50).matrix(), (f2.x.array() + 50).matrix());
  Eigen::VectorXd lo = (f2.x.array() - 100).matrix(), hi = f2.x;
  lo[1] = f2.x[1];
  hi[1] = f2.x[1] + 100;
  const ModelEvidence both = LaplaceEvidence(f2.chi2, a2, f2.x, lo, hi);
  EXPECT_NEAR(both.log_occam, in2.log_occam - 2 * std::log(2.0), 1e-12);
}

// The one-column design `a1` with a second parameter the data do not see.
Eigen::MatrixXd WithUnseenParameter(const Eigen::MatrixXd& a1) {
  Eigen::MatrixXd a2(a1.rows(), 2);
  a2.col(0) = a1.col(0);
  a2.col(1).setZero();
  return a2;
}

TEST(LaplaceEvidence, AParameterTheDataDoNotSeeCostsNothing) {
  // The exact evidence integral of a likelihood flat along a parameter is the
  // same with or without that parameter: flat over its range, divided by its
  // range. (Until d990446 the prior term was 12 / range^2, a Gaussian with the
  // prior's variance, which integrates to sqrt(2 pi / 12) range: each unseen
  // parameter cost log sqrt(pi / 6) = -0.3235. The header now uses 2 pi / range^2,
  // the Gaussian with the prior's peak density: Occam factor exactly 1.)
  const Eigen::MatrixXd a1 = A1();
  const Eigen::VectorXd b = B1();
  const LinearFit fit = Fit(a1, b);
  const Eigen::MatrixXd a2 = WithUnseenParameter(a1);
  const Eigen::VectorXd x2 = Vec({fit.x[0], 0.3});
  const ModelEvidence one = LaplaceEvidence(fit.chi2, a1, fit.x, Vec({-200}), Vec({250}));
  const ModelEvidence two =
      LaplaceEvidence(fit.chi2, a2, x2, Vec({-200, -5}), Vec({250, 5}));
  EXPECT_NEAR(two.log_occam - one.log_occam, 0.0, 1e-3);
  EXPECT_NEAR(two.log_evidence,
              LogEvidenceByQuadrature(a2, b, Vec({-200, -5}), Vec({250, 5}), 1.0, 4000),
              1e-3);
  // Its Laplace sigma is that Gaussian's: range / sqrt(2 pi).
  EXPECT_NEAR(two.sigma[1], 10 / std::sqrt(2 * kPi), 1e-12);
  // A class whose only parameter is unseen costs exactly nothing.
  const ModelEvidence blind = LaplaceEvidence(fit.chi2, Eigen::MatrixXd::Zero(3, 1),
                                              Vec({0.3}), Vec({-5}), Vec({5}));
  EXPECT_NEAR(blind.log_occam, 0.0, 1e-12);
  EXPECT_NEAR(blind.log_evidence, -0.5 * fit.chi2, 1e-12);
}

TEST(LaplaceEvidence, AnUnseenParameterLeavesTheSeenOnesAlone) {
  // The unseen parameter's cost does not depend on its range, its sigma is the
  // prior term's, and the seen one's sigma is unchanged.
  const Eigen::MatrixXd a1 = A1();
  const LinearFit fit = Fit(a1, B1());
  const Eigen::MatrixXd a2 = WithUnseenParameter(a1);
  const Eigen::VectorXd x2 = Vec({fit.x[0], 0.3});
  const ModelEvidence one = LaplaceEvidence(fit.chi2, a1, fit.x, Vec({-200}), Vec({250}));
  const ModelEvidence two =
      LaplaceEvidence(fit.chi2, a2, x2, Vec({-200, -5}), Vec({250, 5}));
  const ModelEvidence two_wide =
      LaplaceEvidence(fit.chi2, a2, x2, Vec({-200, -500}), Vec({250, 500}));
  EXPECT_NEAR(two.log_occam, two_wide.log_occam, 1e-12);  // independent of its range
  EXPECT_NEAR(two.sigma[0], one.sigma[0], 1e-12);
  EXPECT_NEAR(two.sigma[1], 10 / std::sqrt(2 * kPi), 1e-12);
  EXPECT_NEAR(two.log_occam, one.log_occam, 1e-12);
}

TEST(LaplaceEvidence, LogOccamNeverPositive) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 5, m = 1 + trial % 7;
    // From nearly no information to very strong data, narrow to wide boxes.
    const double scale = std::pow(10.0, -4 + 8 * unit(rng));
    Eigen::MatrixXd j(m, n);
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < n; ++c) j(r, c) = scale * normal(rng);
    Eigen::VectorXd lower(n), upper(n), x(n);
    for (int i = 0; i < n; ++i) {
      lower[i] = normal(rng);
      upper[i] = lower[i] + std::pow(10.0, -3 + 6 * unit(rng));
      x[i] = lower[i] + unit(rng) * (upper[i] - lower[i]);
    }
    const double t = 1 + 10 * unit(rng);
    const double chi2 = 10 * unit(rng);
    const ModelEvidence e = LaplaceEvidence(chi2, j, x, lower, upper, t);
    EXPECT_LE(e.log_occam, 0.0) << trial;
    EXPECT_TRUE(std::isfinite(e.log_evidence)) << trial;
    EXPECT_NEAR(e.log_evidence, -0.5 * chi2 / t + e.log_occam,
                1e-9 * (1 + std::abs(e.log_evidence)));
  }
}

TEST(LaplaceEvidence, NoParameters) {
  const ModelEvidence e = LaplaceEvidence(3.5, Eigen::MatrixXd(), Eigen::VectorXd(),
                                          Eigen::VectorXd(), Eigen::VectorXd(), 2.0);
  EXPECT_EQ(e.num_parameters, 0);
  EXPECT_DOUBLE_EQ(e.log_occam, 0.0);
  EXPECT_DOUBLE_EQ(e.log_evidence, -3.5 / 4.0);
  EXPECT_DOUBLE_EQ(e.chi2, 3.5);
}

TEST(LaplaceEvidence, BadInputThrows) {
  const Eigen::MatrixXd j = A2();
  const Eigen::VectorXd x = Vec({0.1, 0.2}), lo = Vec({-1, -1}), hi = Vec({1, 1});
  EXPECT_NO_THROW(LaplaceEvidence(1.0, j, x, lo, hi));
  // Sizes.
  EXPECT_THROW(LaplaceEvidence(1.0, j, Vec({0.1}), lo, hi), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, Vec({-1}), hi), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, Vec({1, 1, 1})), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, A1(), x, lo, hi), InputError);
  // Empty, inverted or infinite box.
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, Vec({1, -1})), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, Vec({1, -2})), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, Vec({1, kInf})), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, Vec({kNaN, -1}), hi), InputError);
  // Temperature below 1 or not finite.
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, 0.5), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, 0.0), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, kNaN), InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, kInf), InputError);
  // chi2 negative or not finite.
  EXPECT_THROW(LaplaceEvidence(-1.0, j, x, lo, hi), InputError);
  EXPECT_THROW(LaplaceEvidence(kNaN, j, x, lo, hi), InputError);
  EXPECT_THROW(LaplaceEvidence(kInf, j, x, lo, hi), InputError);
  // NaN in the Jacobian.
  Eigen::MatrixXd bad = j;
  bad(2, 1) = kNaN;
  EXPECT_THROW(LaplaceEvidence(1.0, bad, x, lo, hi), InputError);
}

// Gaussian priors: for a linear model r = A x - b (whitened) with the prior
// x ~ N(mu, diag(s^2)), the data are Gaussian, b ~ N(A mu, I + A diag(s^2) A'),
// so the evidence is known in closed form; Laplace's approximation at the
// posterior's mode is exact there.
TEST(LaplaceEvidence, GaussianPriorsMatchTheLinearGaussianClosedForm) {
  const Eigen::MatrixXd a = A2();
  const Eigen::VectorXd b = B2();
  const Eigen::VectorXd mu = Vec({0.3, -0.2}), s = Vec({0.4, 1.5});
  const Eigen::MatrixXd prior_cov = s.array().square().matrix().asDiagonal();
  // The mode: (A'A + diag(1/s^2)) x = A'b + diag(1/s^2) mu.
  const Eigen::MatrixXd precision =
      a.transpose() * a +
      Eigen::MatrixXd(s.array().square().inverse().matrix().asDiagonal());
  const Eigen::VectorXd x = precision.ldlt().solve(
      a.transpose() * b + Eigen::VectorXd(s.array().square().inverse() * mu.array()));
  const double chi2 = (a * x - b).squaredNorm();
  const Eigen::MatrixXd cov =
      Eigen::MatrixXd::Identity(4, 4) + a * prior_cov * a.transpose();
  const Eigen::VectorXd d = b - a * mu;
  const double exact =
      -0.5 * d.dot(cov.ldlt().solve(d)) - 0.5 * std::log(cov.determinant());
  // The box only bounds the fit.
  const ModelEvidence e =
      LaplaceEvidence(chi2, a, x, Vec({-5, -5}), Vec({5, 5}), 1.0, mu, s);
  EXPECT_NEAR(e.log_evidence, exact, 1e-10);
  EXPECT_NEAR(e.log_evidence, -0.5 * chi2 + e.log_occam, 1e-12);
  EXPECT_LT(e.log_occam, 0.0);
  // The posterior covariance is (A'A + diag(1/s^2))^-1.
  EXPECT_LT((e.covariance - precision.inverse()).cwiseAbs().maxCoeff(), 1e-12);
  // The box plays no part: another one gives the same evidence, and a mode on
  // its edge costs no log 2.
  const ModelEvidence other =
      LaplaceEvidence(chi2, a, x, Vec({x[0], -50}), Vec({40, x[1]}), 1.0, mu, s);
  EXPECT_NEAR(other.log_evidence, e.log_evidence, 1e-12);
}

// One Gaussian and one uniform parameter: the uniform one (density 1/V over a
// box far wider than the posterior) integrates to the Gaussian integral over
// all values; closed form with the Hessian of the misfit plus the Gaussian's
// precision.
TEST(LaplaceEvidence, MixedGaussianAndUniformPriorsMatchTheClosedForm) {
  const Eigen::MatrixXd a = A2();
  const Eigen::VectorXd b = B2();
  const double mu = -0.4, s = 0.25, volume = 2e4;
  Eigen::MatrixXd h = a.transpose() * a;
  h(0, 0) += 1 / (s * s);
  Eigen::VectorXd g = a.transpose() * b;
  g[0] += mu / (s * s);
  const Eigen::VectorXd x = h.ldlt().solve(g);
  const double chi2 = (a * x - b).squaredNorm();
  const double q = chi2 + (x[0] - mu) * (x[0] - mu) / (s * s);
  // (1/V) (1 / (sqrt(2 pi) s)) exp(-q/2) (2 pi)^(2/2) det(h)^(-1/2)
  const double exact = -std::log(volume) - std::log(std::sqrt(2 * kPi) * s) - 0.5 * q +
                       std::log(2 * kPi) - 0.5 * std::log(h.determinant());
  const ModelEvidence e = LaplaceEvidence(chi2, a, x, Vec({-1e4, -1e4}), Vec({1e4, 1e4}),
                                          1.0, Vec({mu, 0.0}), Vec({s, 0.0}));
  EXPECT_NEAR(e.log_evidence, exact, 1e-6);
  // Uniform priors only (sigma all 0, or both empty): the function without them.
  const Eigen::VectorXd lo = Vec({-3, -4}), hi = Vec({5, 6});
  EXPECT_EQ(
      LaplaceEvidence(chi2, a, x, lo, hi, 1.5, Vec({0, 0}), Vec({0, 0})).log_evidence,
      LaplaceEvidence(chi2, a, x, lo, hi, 1.5).log_evidence);
}

TEST(LaplaceEvidence, BadGaussianPriorsThrow) {
  const Eigen::MatrixXd j = A2();
  const Eigen::VectorXd x = Vec({0.1, 0.2}), lo = Vec({-1, -1}), hi = Vec({1, 1});
  EXPECT_NO_THROW(LaplaceEvidence(1.0, j, x, lo, hi, 1.0, Vec({0, 0}), Vec({0.5, 0})));
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, 1.0, Vec({0}), Vec({0.5, 0})),
               InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, 1.0, Vec({0, 0}), Eigen::VectorXd()),
               InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, 1.0, Vec({0, 0}), Vec({-0.5, 0})),
               InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, 1.0, Vec({kNaN, 0}), Vec({0.5, 0})),
               InputError);
  EXPECT_THROW(LaplaceEvidence(1.0, j, x, lo, hi, 1.0, Vec({0, 0}), Vec({kInf, 0})),
               InputError);
}

// ----------------------------------------------------------------------------

// The held-out rows' predictive density is the evidence of all the data over the
// evidence of the fitted rows: log Z(fit + held) - log Z(fit), each by quadrature
// (the boxes are wide enough that the prior's edges do not matter).
TEST(LogPredictiveDensity, IsTheEvidenceRatioOfALinearGaussianModel) {
  const Eigen::MatrixXd a = A2();
  const Eigen::VectorXd b = B2();
  Eigen::MatrixXd held(2, 2);
  held << 1.5, -0.7,  //
      0.4, 2.2;
  const Eigen::VectorXd held_b = Vec({0.9, -0.6});
  Eigen::MatrixXd all(6, 2);
  all << a, held;
  Eigen::VectorXd all_b(6);
  all_b << b, held_b;
  const LinearFit fit = Fit(a, b);
  const Eigen::VectorXd lower = Vec({-200, -150}), upper = Vec({200, 250});
  for (double t : {1.0, 3.0}) {
    SCOPED_TRACE(t);
    const ModelEvidence e = LaplaceEvidence(fit.chi2, a, fit.x, lower, upper, t);
    const Eigen::VectorXd r = held * fit.x - held_b;
    const double reference = LogEvidenceByQuadrature(all, all_b, lower, upper, t, 3000) -
                             LogEvidenceByQuadrature(a, b, lower, upper, t, 3000);
    EXPECT_NEAR(LogPredictiveDensity(r, held, e.covariance, t), reference, 1e-3);
    // The plug-in likelihood -r'r / (2T) ignores the spread of the fit: it is
    // not this density.
    EXPECT_GT(std::abs(-0.5 * r.squaredNorm() / t - reference), 0.05);
  }
}

TEST(LogPredictiveDensity, NoParametersIsThePlainLikelihood) {
  const Eigen::VectorXd r = Vec({0.5, -1.5, 2.0});
  EXPECT_NEAR(LogPredictiveDensity(r, Eigen::MatrixXd(3, 0), Eigen::MatrixXd(), 2.0),
              -0.5 * r.squaredNorm() / 2.0, 1e-15);
  EXPECT_EQ(LogPredictiveDensity(Eigen::VectorXd(), Eigen::MatrixXd(0, 2),
                                 Eigen::MatrixXd::Identity(2, 2)),
            0.0);
}

TEST(LogPredictiveDensity, BadInputThrows) {
  const Eigen::VectorXd r = Vec({0.5, -1.5});
  const Eigen::MatrixXd j = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::MatrixXd c = Eigen::MatrixXd::Identity(2, 2);
  EXPECT_NO_THROW(LogPredictiveDensity(r, j, c));
  EXPECT_THROW(LogPredictiveDensity(Vec({1.0}), j, c), InputError);
  EXPECT_THROW(LogPredictiveDensity(r, j, Eigen::MatrixXd::Identity(3, 3)), InputError);
  EXPECT_THROW(LogPredictiveDensity(r, j, c, 0.5), InputError);
  EXPECT_THROW(LogPredictiveDensity(r, j, c, kInf), InputError);
  EXPECT_THROW(LogPredictiveDensity(Vec({kNaN, 0.0}), j, c), InputError);
  EXPECT_THROW(LogPredictiveDensity(r, j, -4 * c), InputError);
}

TEST(PosteriorProbabilities, SoftmaxByHandSumsToOne) {
  const Eigen::VectorXd log_z = Vec({-12.0, -10.5, -11.2, -20.0});
  const Eigen::VectorXd prior = Vec({1, 1, 1, 1});
  const Eigen::VectorXd p = PosteriorProbabilities(log_z, prior);
  ASSERT_EQ(p.size(), 4);
  double total = 0;
  for (int i = 0; i < 4; ++i) total += std::exp(log_z[i]);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(p[i], std::exp(log_z[i]) / total, 1e-14);
  EXPECT_NEAR(p.sum(), 1.0, 1e-14);
}

TEST(PosteriorProbabilities, LargeLogEvidencesDoNotOverflow) {
  // exp(-1000) underflows; the ratios do not.
  const Eigen::VectorXd p =
      PosteriorProbabilities(Vec({-1000, -1001, 800 - 1800}), Vec({1, 1, 1}));
  const double e1 = std::exp(-1.0);
  EXPECT_NEAR(p[0], 1 / (2 + e1), 1e-14);
  EXPECT_NEAR(p[1], e1 / (2 + e1), 1e-14);
  EXPECT_NEAR(p[2], 1 / (2 + e1), 1e-14);
  EXPECT_NEAR(p.sum(), 1.0, 1e-14);
  const Eigen::VectorXd q = PosteriorProbabilities(Vec({5000, 4990}), Vec({1, 1}));
  EXPECT_NEAR(q[0], 1 / (1 + std::exp(-10.0)), 1e-14);
  EXPECT_TRUE(q.allFinite());
}

TEST(PosteriorProbabilities, PriorsWeighTheClasses) {
  // Equal evidence: the normalised priors.
  const Eigen::VectorXd p = PosteriorProbabilities(Vec({-3, -3, -3}), Vec({1, 3, 4}));
  EXPECT_NEAR(p[0], 0.125, 1e-14);
  EXPECT_NEAR(p[1], 0.375, 1e-14);
  EXPECT_NEAR(p[2], 0.5, 1e-14);
  // Unnormalised priors give the same answer as normalised ones.
  const Eigen::VectorXd log_z = Vec({-2.0, -4.0});
  const Eigen::VectorXd a = PosteriorProbabilities(log_z, Vec({2, 6}));
  const Eigen::VectorXd b = PosteriorProbabilities(log_z, Vec({0.25, 0.75}));
  EXPECT_NEAR((a - b).cwiseAbs().maxCoeff(), 0, 1e-15);
  // By hand: prior times evidence, normalised.
  const double w0 = 0.25 * std::exp(-2.0), w1 = 0.75 * std::exp(-4.0);
  EXPECT_NEAR(a[0], w0 / (w0 + w1), 1e-14);
  EXPECT_NEAR(a[1], w1 / (w0 + w1), 1e-14);
  // A single class is certain.
  EXPECT_NEAR(PosteriorProbabilities(Vec({-7}), Vec({0.1}))[0], 1.0, 1e-15);
}

TEST(PosteriorProbabilities, BadInputThrows) {
  EXPECT_THROW(PosteriorProbabilities(Vec({1, 2}), Vec({1})), InputError);
  EXPECT_THROW(PosteriorProbabilities(Eigen::VectorXd(), Eigen::VectorXd()), InputError);
  EXPECT_THROW(PosteriorProbabilities(Vec({1, 2}), Vec({1, 0})), InputError);
  EXPECT_THROW(PosteriorProbabilities(Vec({1, 2}), Vec({1, -1})), InputError);
  EXPECT_THROW(PosteriorProbabilities(Vec({1, 2}), Vec({1, kNaN})), InputError);
  EXPECT_THROW(PosteriorProbabilities(Vec({1, 2}), Vec({1, kInf})), InputError);
  EXPECT_THROW(PosteriorProbabilities(Vec({1, kNaN}), Vec({1, 1})), InputError);
  EXPECT_THROW(PosteriorProbabilities(Vec({1, -kInf}), Vec({1, 1})), InputError);
}

// ----------------------------------------------------------------------------
// CombineBasins: a posterior with two separated modes. The fitted data see
// x^2 (y = a^2 with whitened residual (x^2 - a^2) / s), so x = +a and x = -a
// fit equally well; a held-out datum sees x itself ((x - c) / s_h) and tells the
// two apart. Laplace at each mode, combined, against the evidence and the
// predictive density integrated by Simpson's rule over the prior box.
namespace basins {

constexpr double kA = 2.0, kS = 0.05, kC = 1.5, kSh = 1.0;
constexpr double kLower = -5.0, kUpper = 4.0;

// log( (1/V) integral exp(-chi2(x) / 2) dx ), with or without the held-out datum.
double LogEvidence(bool with_held_out) {
  std::vector<double> x, w;
  Simpson(kLower, kUpper, 400000, &x, &w);
  double integral = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = (x[i] * x[i] - kA * kA) / kS;
    double chi2 = r * r;
    if (with_held_out) chi2 += (x[i] - kC) * (x[i] - kC) / (kSh * kSh);
    integral += w[i] * std::exp(-0.5 * chi2);
  }
  return std::log(integral / (kUpper - kLower));
}

}  // namespace basins

TEST(CombineBasins, TwoModesMatchQuadrature) {
  using namespace basins;
  std::vector<double> log_z, log_p;
  for (double x : {kA, -kA}) {
    const Eigen::MatrixXd j = Eigen::MatrixXd::Constant(1, 1, 2 * x / kS);
    const ModelEvidence e =
        LaplaceEvidence(0.0, j, Vec({x}), Vec({kLower}), Vec({kUpper}));
    log_z.push_back(e.log_evidence);
    log_p.push_back(LogPredictiveDensity(
        Vec({(x - kC) / kSh}), Eigen::MatrixXd::Constant(1, 1, 1 / kSh), e.covariance));
  }
  const double fitted = LogEvidence(false);
  const double held_out = LogEvidence(true) - fitted;
  const BasinMixture m = CombineBasins(log_z, log_p);
  EXPECT_NEAR(m.log_evidence, fitted, 2e-3);
  EXPECT_NEAR(m.log_predictive, held_out, 2e-3);
  // One mode alone is log 2 short of the evidence, and its prediction is not
  // the posterior's: at +a it is far too optimistic, at -a far too pessimistic.
  EXPECT_NEAR(fitted - log_z[0], std::log(2.0), 2e-3);
  EXPECT_GT(log_p[0] - held_out, 0.5);
  EXPECT_LT(log_p[1] - held_out, -2.0);
}

TEST(CombineBasins, OneBasinIsItselfAndWeightsFollowTheEvidence) {
  const BasinMixture one = CombineBasins({-3.5}, {-1.25});
  EXPECT_DOUBLE_EQ(one.log_evidence, -3.5);
  EXPECT_DOUBLE_EQ(one.log_predictive, -1.25);
  // Z = e^-1 + e^-2; p = (e^-1 e^-4 + e^-2 e^-0.5) / Z, by hand; and far from
  // 0 (e^-800) without underflow.
  for (double shift : {0.0, -800.0}) {
    const BasinMixture m = CombineBasins({-1 + shift, -2 + shift}, {-4, -0.5});
    const double z = std::exp(-1.0) + std::exp(-2.0);
    EXPECT_NEAR(m.log_evidence, std::log(z) + shift, 1e-12);
    EXPECT_NEAR(m.log_predictive, std::log((std::exp(-5.0) + std::exp(-2.5)) / z), 1e-12);
  }
}

TEST(CombineBasins, BadInputThrows) {
  EXPECT_THROW(CombineBasins({}, {}), InputError);
  EXPECT_THROW(CombineBasins({1.0, 2.0}, {0.0}), InputError);
  EXPECT_THROW(CombineBasins({1.0, kNaN}, {0.0, 0.0}), InputError);
  EXPECT_THROW(CombineBasins({1.0}, {-kInf}), InputError);
}

}  // namespace
}  // namespace femup
