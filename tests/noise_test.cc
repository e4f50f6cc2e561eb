// Measurement noise (problems/include/femup/problems/noise.h): exactness at
// level 0, reproducibility by seed, and the statistics of the relative errors
// over many draws (fixed seeds).
#include "femup/problems/noise.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "enum_names.h"
#include "femup/core/errors.h"

namespace femup {
namespace {

// A state with `modes` frequencies and `rows` x `modes` shapes, all nonzero.
ModalData Synthetic(int modes, int rows) {
  ModalData d;
  d.state = "air";
  d.frequencies_hz.resize(modes);
  d.shapes.resize(rows, modes);
  for (int j = 0; j < modes; ++j) {
    d.frequencies_hz[j] = 1.0 + 0.37 * j;
    for (int i = 0; i < rows; ++i) d.shapes(i, j) = std::sin(1.0 + i + 0.5 * j) + 2.0;
  }
  return d;
}

// Relative changes r = (x' / x - 1) / level of the eigenvalues and shape
// entries.
std::vector<double> EigenvalueDraws(const ModalData& clean, const ModalData& noisy,
                                    double level) {
  std::vector<double> r;
  const Eigen::VectorXd l0 = clean.Eigenvalues(), l1 = noisy.Eigenvalues();
  for (int j = 0; j < l0.size(); ++j) r.push_back((l1[j] / l0[j] - 1.0) / level);
  return r;
}
std::vector<double> ShapeDraws(const ModalData& clean, const ModalData& noisy,
                               double level) {
  std::vector<double> r;
  for (Eigen::Index i = 0; i < clean.shapes.size(); ++i) {
    r.push_back((noisy.shapes.data()[i] / clean.shapes.data()[i] - 1.0) / level);
  }
  return r;
}

void MeanAndStd(const std::vector<double>& x, double* mean, double* std_dev) {
  double s = 0, ss = 0;
  for (double v : x) s += v;
  *mean = s / x.size();
  for (double v : x) ss += (v - *mean) * (v - *mean);
  *std_dev = std::sqrt(ss / (x.size() - 1));
}

// `clean` corrupted by noise of `level` drawn from `distribution`, the draws
// from a std::mt19937_64 seeded with `seed`.
ModalData Corrupted(const ModalData& clean, double level, NoiseDistribution distribution,
                    std::uint64_t seed) {
  NoiseModel noise;
  noise.level = level;
  noise.distribution = distribution;
  std::mt19937_64 rng(seed);
  return Corrupt(clean, noise, &rng);
}

TEST(Corrupt, LevelZeroLeavesDataUnchanged) {
  const ModalData clean = Synthetic(4, 6);
  for (NoiseDistribution dist :
       {NoiseDistribution::kGaussian, NoiseDistribution::kUniform}) {
    const ModalData out = Corrupted(clean, 0, dist, 1);
    EXPECT_EQ(out.frequencies_hz, clean.frequencies_hz);
    EXPECT_EQ(out.shapes, clean.shapes);
    EXPECT_EQ(out.state, clean.state);
  }
}

TEST(Corrupt, SameSeedSameResultDifferentSeedDifferent) {
  const ModalData clean = Synthetic(3, 5);
  NoiseModel noise;
  noise.level = 0.05;
  std::mt19937_64 a(42), b(42), c(43);
  const ModalData ra = Corrupt(clean, noise, &a);
  const ModalData rb = Corrupt(clean, noise, &b);
  const ModalData rc = Corrupt(clean, noise, &c);
  EXPECT_EQ(ra.frequencies_hz, rb.frequencies_hz);
  EXPECT_EQ(ra.shapes, rb.shapes);
  EXPECT_NE(ra.frequencies_hz, rc.frequencies_hz);
  EXPECT_NE(ra.shapes, rc.shapes);
  EXPECT_NE(ra.frequencies_hz, clean.frequencies_hz);
  // The generator advances: a second draw from the same generator differs.
  const ModalData again = Corrupt(clean, noise, &a);
  EXPECT_NE(again.shapes, ra.shapes);
}

TEST(Corrupt, DrawOrderIsEigenvaluesThenShapesColumnMajor) {
  const ModalData clean = Synthetic(3, 4);
  NoiseModel noise;
  noise.level = 0.02;
  noise.distribution = NoiseDistribution::kUniform;
  std::mt19937_64 rng(7), reference(7);
  const ModalData out = Corrupt(clean, noise, &rng);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::VectorXd l0 = clean.Eigenvalues(), l1 = out.Eigenvalues();
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(l1[j], l0[j] * (1 + noise.level * u(reference)), 1e-12 * l0[j]);
  }
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(out.shapes(i, j), clean.shapes(i, j) * (1 + noise.level * u(reference)),
                  1e-15 * std::abs(clean.shapes(i, j)));
    }
  }
}

// Additive shape noise, one size per shape: psi_i + level * max |psi| * r.
TEST(Corrupt, PeakScaledShapeNoiseIsAdditive) {
  const ModalData clean = Synthetic(3, 4);
  NoiseModel noise;
  noise.level = 0.02;
  noise.shape_level = 0.1;
  noise.eigenvalues = false;
  noise.distribution = NoiseDistribution::kUniform;
  noise.shape_scale = NoiseModel::ShapeScale::kPeak;
  std::mt19937_64 rng(11), reference(11);
  const ModalData out = Corrupt(clean, noise, &rng);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  EXPECT_EQ(out.frequencies_hz, clean.frequencies_hz);
  for (int j = 0; j < 3; ++j) {
    const double peak = clean.shapes.col(j).cwiseAbs().maxCoeff();
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(out.shapes(i, j), clean.shapes(i, j) + 0.1 * peak * u(reference),
                  1e-15 * peak);
    }
  }
}

TEST(Corrupt, GaussianStatistics) {
  const double level = 0.05;
  const ModalData clean = Synthetic(20000, 2);
  const ModalData out = Corrupted(clean, level, NoiseDistribution::kGaussian, 2014);
  double mean = 0, std_dev = 0;
  // Eigenvalues: r ~ N(0, 1). With 20000 draws the standard error of the mean
  // is 0.007 and of the standard deviation 0.005.
  MeanAndStd(EigenvalueDraws(clean, out, level), &mean, &std_dev);
  EXPECT_NEAR(mean, 0.0, 0.05);
  EXPECT_NEAR(std_dev, 1.0, 0.05);
  // Shapes (40000 entries).
  MeanAndStd(ShapeDraws(clean, out, level), &mean, &std_dev);
  EXPECT_NEAR(mean, 0.0, 0.05);
  EXPECT_NEAR(std_dev, 1.0, 0.05);
}

TEST(Corrupt, UniformStatisticsAndBound) {
  const double level = 0.08;
  const ModalData clean = Synthetic(20000, 2);
  const ModalData out = Corrupted(clean, level, NoiseDistribution::kUniform, 5);
  for (const auto& draws :
       {EigenvalueDraws(clean, out, level), ShapeDraws(clean, out, level)}) {
    double worst = 0;
    for (double r : draws) worst = std::max(worst, std::abs(r));
    EXPECT_LE(worst, 1.0 + 1e-9);
    EXPECT_GT(worst, 0.99);  // the range is used
    double mean = 0, std_dev = 0;
    MeanAndStd(draws, &mean, &std_dev);
    EXPECT_NEAR(mean, 0.0, 0.05 / std::sqrt(3.0));
    EXPECT_NEAR(std_dev, 1.0 / std::sqrt(3.0), 0.05 / std::sqrt(3.0));
  }
}

TEST(Corrupt, EigenvaluesOrShapesOnly) {
  const ModalData clean = Synthetic(3, 4);
  NoiseModel noise;
  noise.level = 0.1;
  noise.shapes = false;
  std::mt19937_64 rng(9);
  ModalData out = Corrupt(clean, noise, &rng);
  EXPECT_EQ(out.shapes, clean.shapes);
  EXPECT_NE(out.frequencies_hz, clean.frequencies_hz);
  noise.shapes = true;
  noise.eigenvalues = false;
  out = Corrupt(clean, noise, &rng);
  EXPECT_EQ(out.frequencies_hz, clean.frequencies_hz);
  EXPECT_NE(out.shapes, clean.shapes);
}

TEST(Corrupt, InvalidLevelsThrow) {
  const ModalData clean = Synthetic(2, 3);
  for (double level : {-0.01, 1.0, 2.0, std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity()}) {
    NoiseModel noise;
    noise.level = level;
    EXPECT_NE(noise.Validate().ToString(), "") << level;
    std::mt19937_64 rng(1);
    EXPECT_THROW(Corrupt(clean, noise, &rng), InputError) << level;
  }
  NoiseModel ok;
  ok.level = 0.99;
  EXPECT_EQ(ok.Validate().ToString(), "");
}

TEST(Corrupt, NonPositiveEigenvalueThrows) {
  // Gaussian at 50 %: a draw below -2 makes 1 + level r <= 0; among 2000
  // draws (fixed seed) that happens.
  const ModalData clean = Synthetic(2000, 1);
  NoiseModel noise;
  noise.level = 0.5;
  std::mt19937_64 rng(3);
  EXPECT_THROW(Corrupt(clean, noise, &rng), InputError);
}

// The counter-based generator of the noise study: the same statistics, and
// the same numbers whether corrupting into a new object, into reused storage
// or in place.
TEST(Corrupt, CounterGeneratorStatisticsAndInPlace) {
  const double level = 0.05;
  const ModalData clean = Synthetic(20000, 2);
  for (NoiseDistribution dist :
       {NoiseDistribution::kGaussian, NoiseDistribution::kUniform}) {
    NoiseModel noise;
    noise.level = level;
    noise.distribution = dist;
    CounterRng rng(2014, 1, 2);
    const ModalData out = Corrupt(clean, noise, &rng);
    const double expected_std =
        dist == NoiseDistribution::kGaussian ? 1.0 : 1.0 / std::sqrt(3.0);
    for (const auto& draws :
         {EigenvalueDraws(clean, out, level), ShapeDraws(clean, out, level)}) {
      double mean = 0, std_dev = 0;
      MeanAndStd(draws, &mean, &std_dev);
      EXPECT_NEAR(mean, 0.0, 0.05 * expected_std) << ToString(dist);
      EXPECT_NEAR(std_dev, expected_std, 0.05 * expected_std) << ToString(dist);
    }
    CounterRng again(2014, 1, 2);
    ModalData reused = Synthetic(3, 1);  // other sizes: resized
    Corrupt(clean, noise, &again, &reused);
    EXPECT_EQ(reused.frequencies_hz, out.frequencies_hz);
    EXPECT_EQ(reused.shapes, out.shapes);
    EXPECT_EQ(reused.state, out.state);
    CounterRng third(2014, 1, 2);
    ModalData in_place = clean;
    Corrupt(in_place, noise, &third, &in_place);
    EXPECT_EQ(in_place.frequencies_hz, out.frequencies_hz);
    EXPECT_EQ(in_place.shapes, out.shapes);
  }
  // Peak-scaled shape noise in place: the peak is the clean one.
  NoiseModel peak;
  peak.level = 0.02;
  peak.shape_scale = NoiseModel::ShapeScale::kPeak;
  CounterRng a(5, 0, 0), b(5, 0, 0);
  const ModalData small = Synthetic(2, 6);
  const ModalData copy = Corrupt(small, peak, &a);
  ModalData in_place = small;
  Corrupt(in_place, peak, &b, &in_place);
  EXPECT_EQ(in_place.shapes, copy.shapes);
}

TEST(NoiseDistribution, Names) {
  testing::ExpectEnumNames<NoiseDistribution>(
      {{NoiseDistribution::kGaussian, "gaussian"},
       {NoiseDistribution::kUniform, "uniform"}},
      NoiseDistributionFromString, NoiseDistribution::kGaussian,
      {{"uniform", NoiseDistribution::kUniform}}, "laplace");
}

}  // namespace
}  // namespace femup
