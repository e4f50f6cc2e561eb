// Importance-sampled evidence (solvers/include/femup/solvers/sampled_evidence.h),
// checked against closed forms of the evidence integral (Gaussian likelihoods
// well inside the prior box, a two-mode likelihood) and against a Simpson
// quadrature over the box for a curved one-parameter likelihood, none of which
// use the sampler's code. The header's convention: with a uniform prior on a box
// of volume V, log Z(T) = log( (1/V) integral exp(-chi2(x) / 2T) dx ).
#include "femup/solvers/sampled_evidence.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <vector>

#include "femup/core/errors.h"
#include "femup/solvers/model_evidence.h"

namespace femup {
namespace {

const double kPi = std::acos(-1.0);

// chi2 = (x - a)' A (x - a): log Z = d/2 log(2 pi T) - 1/2 log det A - log V
// when the box holds the likelihood's mass.
struct Gaussian {
  Eigen::VectorXd a;
  Eigen::MatrixXd precision;
  double Chi2(const Eigen::VectorXd& x) const { return (x - a).dot(precision * (x - a)); }
  double LogEvidence(double volume, double t) const {
    const double d = static_cast<double>(a.size());
    return 0.5 * d * std::log(2 * kPi * t) - 0.5 * std::log(precision.determinant()) -
           std::log(volume);
  }
};

// The Gaussian's chi2 as a one-part misfit (g must outlive it).
MisfitFunction Misfit(const Gaussian& g) {
  return [&g](const Eigen::VectorXd& x, Eigen::VectorXd* chi2) {
    chi2->resize(1);
    (*chi2)[0] = g.Chi2(x);
    return true;
  };
}

Gaussian Correlated() {
  Gaussian g;
  g.a = Eigen::Vector2d(0.3, -1.2);
  Eigen::Matrix2d c;  // covariance with correlation 0.9
  c << 0.04, 0.9 * 0.2 * 0.05, 0.9 * 0.2 * 0.05, 0.0025;
  g.precision = c.inverse();
  return g;
}

TEST(SampledEvidence, GaussianLikelihoodMatchesTheClosedForm) {
  const Gaussian g = Correlated();
  const Eigen::Vector2d lo(-3, -4), hi(3, 2);
  const MisfitFunction misfit = Misfit(g);
  const EvidenceSamples s = SampleEvidence(
      misfit, 1, lo, hi, {{g.a, g.precision.inverse()}}, SampledEvidenceOptions{});
  const SampledLogEvidence e = LogEvidenceFromSamples(s, {true});
  const double exact = g.LogEvidence(36.0, 1.0);
  EXPECT_NEAR(e.log_evidence, exact, std::max(0.02, 4 * e.log_standard_error));
  EXPECT_LT(e.log_standard_error, 0.03);
  EXPECT_GT(e.effective_samples, 500);
  EXPECT_EQ(s.failed, 0);
  // At T = 2 the same draws give the wider likelihood's evidence.
  const SampledLogEvidence e2 = LogEvidenceFromSamples(s, {true}, 2.0);
  EXPECT_NEAR(e2.log_evidence, g.LogEvidence(36.0, 2.0),
              std::max(0.03, 4 * e2.log_standard_error));
}

TEST(SampledEvidence, TwoModesCountedWhereLaplaceSeesOne) {
  // chi2 = -2 log(exp(-(x-1)^2/(2 s^2)) + exp(-(x+1)^2/(2 s^2))), s = 0.1:
  // Z = 2 sqrt(2 pi) s / V, V = 6.
  const double s = 0.1;
  const MisfitFunction misfit = [&](const Eigen::VectorXd& x, Eigen::VectorXd* chi2) {
    const double l = std::exp(-0.5 * std::pow((x[0] - 1) / s, 2)) +
                     std::exp(-0.5 * std::pow((x[0] + 1) / s, 2));
    chi2->resize(1);
    (*chi2)[0] = -2 * std::log(l);
    return true;
  };
  const Eigen::VectorXd lo = Eigen::VectorXd::Constant(1, -3),
                        hi = Eigen::VectorXd::Constant(1, 3);
  const double exact = std::log(2 * std::sqrt(2 * kPi) * s / 6.0);
  const Eigen::MatrixXd var = Eigen::MatrixXd::Constant(1, 1, s * s);
  const std::vector<EvidenceComponent> both{{Eigen::VectorXd::Constant(1, 1.0), var},
                                            {Eigen::VectorXd::Constant(1, -1.0), var}};
  const SampledLogEvidence e =
      LogEvidenceFromSamples(SampleEvidence(misfit, 1, lo, hi, both, {}), {true});
  EXPECT_NEAR(e.log_evidence, exact, std::max(0.02, 4 * e.log_standard_error));
  // Laplace at one mode misses the other: log 2 short.
  const ModelEvidence laplace = LaplaceEvidence(
      -2 * std::log(1 + std::exp(-200.0)), Eigen::MatrixXd::Constant(1, 1, 1 / s),
      Eigen::VectorXd::Constant(1, 1.0), lo, hi);
  EXPECT_NEAR(exact - laplace.log_evidence, std::log(2.0), 2e-3);
  // With the component at one mode only, the prior's share of the draws still
  // finds the other: the estimate stays right, with a larger error.
  SampledEvidenceOptions more;
  more.samples = 20000;
  const SampledLogEvidence one =
      LogEvidenceFromSamples(SampleEvidence(misfit, 1, lo, hi, {both[0]}, more), {true});
  EXPECT_NEAR(one.log_evidence, exact, std::max(0.05, 4 * one.log_standard_error));
}

TEST(SampledEvidence, CurvedLikelihoodMatchesQuadrature) {
  // A nonlinear one-parameter model: residual (exp(x) - 2) / 0.05 on [-1, 2].
  auto chi2_of = [](double x) { return std::pow((std::exp(x) - 2) / 0.05, 2); };
  const MisfitFunction misfit = [&](const Eigen::VectorXd& x, Eigen::VectorXd* chi2) {
    chi2->resize(1);
    (*chi2)[0] = chi2_of(x[0]);
    return true;
  };
  const int intervals = 20000;  // Simpson's rule over the box
  const double a = -1, b = 2, h = (b - a) / intervals;
  double sum = 0;
  for (int i = 0; i <= intervals; ++i) {
    const double w = (i == 0 || i == intervals) ? 1 : (i % 2 ? 4 : 2);
    sum += w * std::exp(-0.5 * chi2_of(a + i * h));
  }
  const double exact = std::log(sum * h / 3 / (b - a));
  // The component from a Laplace fit at the optimum x = ln 2 (J = 2 / 0.05).
  const EvidenceComponent c{Eigen::VectorXd::Constant(1, std::log(2.0)),
                            Eigen::MatrixXd::Constant(1, 1, std::pow(0.05 / 2, 2))};
  const SampledLogEvidence e =
      LogEvidenceFromSamples(SampleEvidence(misfit, 1, Eigen::VectorXd::Constant(1, a),
                                            Eigen::VectorXd::Constant(1, b), {c}, {}),
                             {true});
  EXPECT_NEAR(e.log_evidence, exact, std::max(0.02, 4 * e.log_standard_error));
}

TEST(SampledEvidence, PartsGiveThePredictiveDensityOfHeldOutData) {
  // Two Gaussian parts in one parameter: x ~ data 1 (mean 0.2, sd 0.1) and
  // data 2 (mean 0.35, sd 0.2). Predictive density of part 2 given part 1:
  // N(0.35; 0.2, 0.1^2 + 0.2^2) without the 1/sqrt(2 pi 0.2^2) the header
  // leaves out: log p = -1/2 d^2/(s1^2+s2^2) - 1/2 log((s1^2+s2^2)/s2^2).
  const double m1 = 0.2, s1 = 0.1, m2 = 0.35, s2 = 0.2;
  const MisfitFunction misfit = [&](const Eigen::VectorXd& x, Eigen::VectorXd* chi2) {
    chi2->resize(2);
    (*chi2)[0] = std::pow((x[0] - m1) / s1, 2);
    (*chi2)[1] = std::pow((x[0] - m2) / s2, 2);
    return true;
  };
  const EvidenceSamples s = SampleEvidence(
      misfit, 2, Eigen::VectorXd::Constant(1, -3), Eigen::VectorXd::Constant(1, 3),
      {{Eigen::VectorXd::Constant(1, m1), Eigen::MatrixXd::Constant(1, 1, s1 * s1)}}, {});
  const SampledLogEvidence fitted = LogEvidenceFromSamples(s, {true, false});
  const SampledLogEvidence all = LogEvidenceFromSamples(s, {true, true});
  const double v = s1 * s1 + s2 * s2;
  const double exact = -0.5 * (m2 - m1) * (m2 - m1) / v - 0.5 * std::log(v / (s2 * s2));
  EXPECT_NEAR(all.log_evidence - fitted.log_evidence, exact, 0.02);
  // The same as the linearised formula of model_evidence.h, exact here.
  EXPECT_NEAR(exact,
              LogPredictiveDensity(Eigen::VectorXd::Constant(1, (m1 - m2) / s2),
                                   Eigen::MatrixXd::Constant(1, 1, 1 / s2),
                                   Eigen::MatrixXd::Constant(1, 1, s1 * s1)),
              1e-12);
}

TEST(SampledEvidence, AdaptiveStagesRecoverFromAPoorStart) {
  // The component is off by 5 standard deviations of a narrow likelihood and
  // too wide: with one stage most draws are wasted; with three, the later
  // stages draw from the posterior's moments and the estimate tightens.
  const Gaussian g = Correlated();
  const MisfitFunction misfit = Misfit(g);
  const Eigen::Vector2d lo(-3, -4), hi(3, 2);
  const EvidenceComponent off{g.a + Eigen::Vector2d(1.0, 0.0),
                              Eigen::Matrix2d::Identity() * 0.25};
  SampledEvidenceOptions one;
  one.stages = 1;
  SampledEvidenceOptions three;
  three.stages = 3;
  const SampledLogEvidence e1 =
      LogEvidenceFromSamples(SampleEvidence(misfit, 1, lo, hi, {off}, one), {true});
  const SampledLogEvidence e3 =
      LogEvidenceFromSamples(SampleEvidence(misfit, 1, lo, hi, {off}, three), {true});
  const double exact = g.LogEvidence(36.0, 1.0);
  EXPECT_GT(e3.effective_samples, 3 * e1.effective_samples) << e1.effective_samples;
  // Measured: 10 effective draws of 2000 with one stage, 156 with three.
  EXPECT_LT(e3.log_standard_error, 0.1);
  EXPECT_NEAR(e3.log_evidence, exact, std::max(0.02, 4 * e3.log_standard_error));
}

TEST(SampledEvidence, SameDrawsForTheSameSeedAndStream) {
  const Gaussian g = Correlated();
  const MisfitFunction misfit = Misfit(g);
  const Eigen::Vector2d lo(-3, -4), hi(3, 2);
  SampledEvidenceOptions o;
  o.samples = 300;
  const std::vector<EvidenceComponent> c{{g.a, g.precision.inverse()}};
  const EvidenceSamples a = SampleEvidence(misfit, 1, lo, hi, c, o);
  const EvidenceSamples b = SampleEvidence(misfit, 1, lo, hi, c, o);
  EXPECT_EQ(a.chi2, b.chi2);
  o.stream = 7;
  const EvidenceSamples other = SampleEvidence(misfit, 1, lo, hi, c, o);
  EXPECT_NE(a.chi2, other.chi2);
}

TEST(SampledEvidence, FailuresAndDrawsOutsideTheBoxCountAsZeroLikelihood) {
  // The misfit fails on x < 0: the evidence is that of the half box.
  const MisfitFunction misfit = [](const Eigen::VectorXd& x, Eigen::VectorXd* chi2) {
    chi2->resize(1);
    (*chi2)[0] = 0;
    return x[0] >= 0;
  };
  SampledEvidenceOptions o;
  o.samples = 4000;
  const EvidenceSamples s = SampleEvidence(
      misfit, 1, Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1),
      {{Eigen::VectorXd::Constant(1, 0.9), Eigen::MatrixXd::Constant(1, 1, 0.25)}}, o);
  EXPECT_GT(s.failed, 0);
  EXPECT_GT(s.outside, 0);  // the component's tail reaches past x = 1
  const SampledLogEvidence e = LogEvidenceFromSamples(s, {true});
  EXPECT_NEAR(e.log_evidence, std::log(0.5), std::max(0.03, 4 * e.log_standard_error));
  // Nothing evaluable: -inf, not NaN.
  const MisfitFunction never = [](const Eigen::VectorXd&, Eigen::VectorXd*) {
    return false;
  };
  const SampledLogEvidence none =
      LogEvidenceFromSamples(SampleEvidence(never, 1, Eigen::VectorXd::Constant(1, -1),
                                            Eigen::VectorXd::Constant(1, 1), {}, o),
                             {true});
  EXPECT_EQ(none.log_evidence, -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isinf(none.log_standard_error));
}

TEST(SampledEvidence, BadInputNamed) {
  const MisfitFunction misfit = [](const Eigen::VectorXd&, Eigen::VectorXd* chi2) {
    chi2->setZero(1);
    return true;
  };
  const Eigen::VectorXd lo = Eigen::VectorXd::Zero(1), hi = Eigen::VectorXd::Ones(1);
  auto message = [&](SampledEvidenceOptions o, Eigen::VectorXd l, Eigen::VectorXd u,
                     std::vector<EvidenceComponent> c) {
    try {
      SampleEvidence(misfit, 1, l, u, c, o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SampledEvidenceOptions few;
  few.samples = 5;
  EXPECT_NE(message(few, lo, hi, {}).find("samples"), std::string::npos);
  SampledEvidenceOptions share;
  share.prior_share = 0;
  EXPECT_NE(message(share, lo, hi, {}).find("prior_share"), std::string::npos);
  SampledEvidenceOptions stages;
  stages.stages = 0;
  EXPECT_NE(message(stages, lo, hi, {}).find("stages"), std::string::npos);
  SampledEvidenceOptions cold;
  cold.temperature = 0.5;
  EXPECT_NE(message(cold, lo, hi, {}).find("temperature"), std::string::npos);
  EXPECT_NE(message({}, hi, lo, {}).find("range[1]"), std::string::npos);
  EXPECT_NE(
      message({}, lo, hi, {{Eigen::VectorXd::Zero(2), Eigen::MatrixXd::Identity(2, 2)}})
          .find("component[1]"),
      std::string::npos);
  EXPECT_NE(message({}, lo, hi, {{lo, -Eigen::MatrixXd::Identity(1, 1)}})
                .find("positive definite"),
            std::string::npos);
  const EvidenceSamples s = SampleEvidence(misfit, 1, lo, hi, {}, {});
  EXPECT_THROW(LogEvidenceFromSamples(s, {true, true}), InputError);
  EXPECT_THROW(LogEvidenceFromSamples(s, {true}, 0.5), InputError);
}

}  // namespace
}  // namespace femup
