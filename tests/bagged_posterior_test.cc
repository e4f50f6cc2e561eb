// Bagged posterior probabilities (solvers/include/femup/solvers/bagged_posterior.h),
// checked against closed forms: the multinomial law of the bootstrap counts
// for a verdict that rests on one residual, and the Laplace posterior where
// every residual supports the verdict alike or a stratum of one row carries it.
#include "femup/solvers/bagged_posterior.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "femup/solvers/model_evidence.h"

namespace femup {
namespace {

ClassFit Fit(const Eigen::VectorXd& residual, double log_evidence) {
  ClassFit f;
  f.residual = residual;
  f.log_evidence = log_evidence;
  return f;
}

// Two classes equal in evidence, one of which (A) explains residual 0 (6
// standard deviations) that the other (B) leaves: B's log evidence is
// -chi2/2 = -18 on the data, A's the same through an Occam penalty of 18. On
// a copy that draws residual 0 k times, B scores -18 k and A -18: B wins
// when k = 0, they tie when k = 1, A wins when k >= 2 (by e^18). With n
// residuals, k ~ Binomial(n, 1/n):
//   P(B) = (1 - 1/n)^n + 1/2 (1 - 1/n)^(n - 1)   (to 1e-7).
TEST(BaggedPosterior, AVerdictThatRestsOnOneResidualFollowsTheBootstrapCounts) {
  const int n = 10;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b[0] = 6;
  const ClassFit fit_b = Fit(b, -18);
  const ClassFit fit_a = Fit(Eigen::VectorXd::Zero(n), -18);
  BaggingOptions options;
  options.copies = 40000;
  const Eigen::VectorXd p = BaggedPosteriorProbabilities({fit_a, fit_b}, options);
  const double q = 1.0 - 1.0 / n;
  const double expected_b = std::pow(q, n) + 0.5 * std::pow(q, n - 1);
  // Monte Carlo: the standard error of a mean of values in [0, 1] over 40000
  // copies is below 0.0025.
  EXPECT_NEAR(p[1], expected_b, 0.01);
  EXPECT_NEAR(p.sum(), 1.0, 1e-12);
  // The Laplace posterior splits them evenly (equal evidence).
  EXPECT_NEAR(PosteriorProbabilities(Eigen::Vector2d(-18, -18), Eigen::Vector2d(1, 1))[1],
              0.5, 1e-12);
}

// Where every residual supports the verdict alike, the bagged posterior is
// Laplace's: 40 residuals each 1 standard deviation off under B and fitted by
// A (chi2 40), A's Occam penalty 5. A copy draws 40 rows: B's misfit is 40 on
// every copy.
TEST(BaggedPosterior, AVerdictEveryResidualSupportsStaysCertain) {
  const int n = 40;
  const ClassFit fit_b = Fit(Eigen::VectorXd::Ones(n), -20);
  const ClassFit fit_a = Fit(Eigen::VectorXd::Zero(n), -5);
  const Eigen::VectorXd laplace =
      PosteriorProbabilities(Eigen::Vector2d(-5, -20), Eigen::Vector2d(1, 1));
  const Eigen::VectorXd p =
      BaggedPosteriorProbabilities({fit_a, fit_b}, BaggingOptions());
  EXPECT_GT(laplace[0], 1 - 1e-6);
  EXPECT_NEAR(p[0], laplace[0], 1e-12);
}

// Strata keep the design: a row alone in its stratum (one measured frequency
// among shape entries) is drawn exactly once on every copy, so a verdict that
// rests on it is judged as the data judge it (the Laplace posterior's
// probabilities), while unstratified copies split it as above.
TEST(BaggedPosterior, ARowAloneInItsStratumIsOnEveryCopy) {
  const int n = 10;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b[0] = 3;
  const ClassFit fit_b = Fit(b, -4.5);
  const ClassFit fit_a = Fit(Eigen::VectorXd::Zero(n), -3);
  std::vector<int> strata(n, 1);
  strata[0] = 0;
  const Eigen::VectorXd laplace =
      PosteriorProbabilities(Eigen::Vector2d(-3, -4.5), Eigen::Vector2d(1, 1));
  const Eigen::VectorXd p =
      BaggedPosteriorProbabilities({fit_a, fit_b}, BaggingOptions(), strata);
  EXPECT_NEAR(p[0], laplace[0], 1e-12);
  EXPECT_GT(std::abs(BaggedPosteriorProbabilities({fit_a, fit_b}, BaggingOptions())[0] -
                     laplace[0]),
            0.05);
}

TEST(BaggedPosterior, SameNumbersForASeedAndPriorsCount) {
  const int n = 8;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b[3] = 4;
  const std::vector<ClassFit> fits = {Fit(Eigen::VectorXd::Zero(n), -8), Fit(b, -8)};
  const Eigen::VectorXd p1 = BaggedPosteriorProbabilities(fits, BaggingOptions());
  const Eigen::VectorXd p2 = BaggedPosteriorProbabilities(fits, BaggingOptions());
  EXPECT_EQ(p1, p2);
  // A class three times as probable a priori gains on every copy.
  std::vector<ClassFit> weighted = fits;
  weighted[1].prior = 3;
  EXPECT_GT(BaggedPosteriorProbabilities(weighted, BaggingOptions())[1], p1[1]);
  // One class: certain.
  EXPECT_DOUBLE_EQ(BaggedPosteriorProbabilities({fits[0]}, BaggingOptions())[0], 1.0);
}

TEST(BaggedPosterior, BadInputIsAnInputErrorNamingIt) {
  const ClassFit good = Fit(Eigen::VectorXd::Ones(3), -1);
  auto message = [](const std::vector<ClassFit>& c, const BaggingOptions& o,
                    const std::vector<int>& strata = {}) {
    try {
      BaggedPosteriorProbabilities(c, o, strata);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  BaggingOptions none;
  none.copies = 0;
  EXPECT_NE(message({good}, none).find("copies"), std::string::npos);
  EXPECT_NE(message({}, BaggingOptions()).find("at least one class"), std::string::npos);
  const ClassFit shorter = Fit(Eigen::VectorXd::Ones(2), -1);
  EXPECT_NE(message({good, shorter}, BaggingOptions()).find("classes[1].residual"),
            std::string::npos);
  ClassFit bad_prior = good;
  bad_prior.prior = 0;
  EXPECT_NE(message({good, bad_prior}, BaggingOptions()).find("classes[1].prior"),
            std::string::npos);
  ClassFit nan = good;
  nan.residual[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message({nan}, BaggingOptions()).find("finite"), std::string::npos);
  EXPECT_NE(message({good}, BaggingOptions(), {0, 1}).find("strata"), std::string::npos);
  EXPECT_EQ(message({good}, BaggingOptions(), {0, 1, 1}), "no error");
}

}  // namespace
}  // namespace femup
