// Least squares in long double (solvers/include/femup/solvers/extended_precision.h),
// checked against problems whose answer is known exactly and against a double
// solve of a well-conditioned problem.
#include "femup/solvers/extended_precision.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "femup/core/errors.h"

namespace femup {
namespace {

bool LongDoubleIsWider() {
  return std::numeric_limits<long double>::digits > std::numeric_limits<double>::digits;
}

// min |A x - b| with A = [1 0; 0 1; 1 1], b = (1, 1, 5): the normal equations
// [2 1; 1 2] x = (6, 6) give x = (2, 2) exactly, residual A x - b = (1, 1, -1).
TEST(ExtendedPrecision, ExactlyRepresentableInconsistentProblem) {
  MatrixLD a(3, 2);
  a << 1, 0, 0, 1, 1, 1;
  VectorLD b(3);
  b << 1, 1, 5;
  const ExtendedPrecisionSolution s = ExtendedPrecisionLeastSquares(a, b);
  EXPECT_EQ(s.rank, 2);
  EXPECT_FALSE(s.rank_deficient());
  const long double eps = std::numeric_limits<long double>::epsilon();
  EXPECT_LE(std::fabs(s.x[0] - 2), 16 * eps);
  EXPECT_LE(std::fabs(s.x[1] - 2), 16 * eps);
  ASSERT_EQ(s.residual.size(), 3);
  EXPECT_LE(std::fabs(s.residual[0] - 1), 64 * eps);
  EXPECT_LE(std::fabs(s.residual[1] - 1), 64 * eps);
  EXPECT_LE(std::fabs(s.residual[2] + 1), 64 * eps);
  EXPECT_NE(s.message.find("full column rank (2)"), std::string::npos) << s.message;
}

// Wampler1's construction: y = 1 + x + ... + x^5 at x = 0..20, every number an
// integer below 2^53, so A and b are exact in double and in long double, and the
// answer is all ones. The same QR in double loses about 7 digits to the
// conditioning; long double (3 more digits) must lose them from a smaller start.
TEST(ExtendedPrecision, ExactPolynomialIsRecoveredBeyondDoublePrecision) {
  MatrixLD a(21, 6);
  VectorLD b(21);
  for (int i = 0; i < 21; ++i) {
    long double power = 1;
    b[i] = 0;
    for (int j = 0; j < 6; ++j) {
      a(i, j) = power;
      b[i] += power;
      power *= i;
    }
  }
  const ExtendedPrecisionSolution s = ExtendedPrecisionLeastSquares(a, b);
  EXPECT_EQ(s.rank, 6);
  const long double error = (s.x - VectorLD::Ones(6)).cwiseAbs().maxCoeff();
  EXPECT_LE(error, 1e-11L) << static_cast<double>(error);
  // The double solve of the same scaled problem, for comparison.
  const Eigen::MatrixXd ad = a.cast<double>();
  const Eigen::VectorXd scale = ad.colwise().norm().transpose();
  const Eigen::VectorXd xd =
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(ad * scale.cwiseInverse().asDiagonal())
          .solve(b.cast<double>())
          .cwiseQuotient(scale);
  const double double_error = (xd - Eigen::VectorXd::Ones(6)).cwiseAbs().maxCoeff();
  if (LongDoubleIsWider()) {
    EXPECT_LE(static_cast<double>(error), double_error / 100)
        << static_cast<double>(error) << " vs " << double_error;
  }
  EXPECT_LE(s.residual.cwiseAbs().maxCoeff(), 1e-6L);  // |b| ~ 3e6
  EXPECT_GT(s.pivot_ratio, 1.0);
}

TEST(ExtendedPrecision, AgreesWithDoubleOnAWellConditionedProblem) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd a(30, 5);
  Eigen::VectorXd b(30);
  for (int i = 0; i < a.size(); ++i) a.data()[i] = g(rng);
  for (int i = 0; i < b.size(); ++i) b[i] = g(rng);
  a.col(3) *= 1e6;  // units differ; scaling keeps the problem well conditioned
  const Eigen::VectorXd reference = a.colPivHouseholderQr().solve(b);
  const ExtendedPrecisionSolution s =
      ExtendedPrecisionLeastSquares(a.cast<long double>(), b.cast<long double>());
  EXPECT_EQ(s.rank, 5);
  for (int j = 0; j < 5; ++j) {
    EXPECT_NEAR(static_cast<double>(s.x[j]), reference[j],
                1e-12 * std::abs(reference[j]) + 1e-18)
        << j;
  }
  const Eigen::VectorXd r = a * reference - b;
  EXPECT_LE((s.residual.cast<double>() - r).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ExtendedPrecision, RankDeficiencyIsReported) {
  // The third column is the sum of the first two. Scaling the columns rounds
  // that dependency, leaving a last pivot of a few epsilon: a threshold well
  // above rounding makes the test independent of the platform's long double.
  MatrixLD a(4, 3);
  a << 1, 0, 1, 0, 1, 1, 1, 1, 2, 2, 1, 3;
  VectorLD b(4);
  b << 1, 2, 3, 4;
  ExtendedPrecisionOptions o;
  o.relative_rank_tolerance = 1e-12;
  const ExtendedPrecisionSolution s = ExtendedPrecisionLeastSquares(a, b, o);
  EXPECT_EQ(s.rank, 2);
  EXPECT_TRUE(s.rank_deficient());
  EXPECT_NE(s.message.find("rank 2 of 3"), std::string::npos) << s.message;
  // The basic solution still fits as well as any: the normal equations hold.
  const VectorLD g = a.transpose() * s.residual;
  EXPECT_LE(g.cwiseAbs().maxCoeff(), 1e-15L);
}

TEST(ExtendedPrecision, UnscaledColumnsOfTinyNormCountAsZero) {
  // With a column of norm ~1e-25, scaling keeps it; without, the rank drops.
  MatrixLD a(3, 2);
  a << 1, 1e-25L, 0, 2e-25L, 1, 0;
  VectorLD b(3);
  b << 1, 2, 3;
  EXPECT_EQ(ExtendedPrecisionLeastSquares(a, b).rank, 2);
  ExtendedPrecisionOptions o;
  o.scale_columns = false;
  EXPECT_EQ(ExtendedPrecisionLeastSquares(a, b, o).rank, 1);
}

TEST(ExtendedPrecision, BadInputNamesWhatIsWrong) {
  const auto message = [](const MatrixLD& a, const VectorLD& b,
                          const ExtendedPrecisionOptions& o) {
    try {
      ExtendedPrecisionLeastSquares(a, b, o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const MatrixLD a = MatrixLD::Identity(3, 2);
  EXPECT_EQ(message(a, VectorLD::Ones(2), {}),
            "extended precision least squares: A is 3 x 2 but b has 2 entries");
  EXPECT_EQ(message(MatrixLD(0, 0), VectorLD(), {}),
            "extended precision least squares: A is empty");
  VectorLD nan = VectorLD::Ones(3);
  nan[1] = std::numeric_limits<long double>::quiet_NaN();
  EXPECT_NE(message(a, nan, {}).find("NaN"), std::string::npos);
  ExtendedPrecisionOptions o;
  o.relative_rank_tolerance = -1;
  EXPECT_NE(message(a, VectorLD::Ones(3), o).find("relative_rank_tolerance: must be"),
            std::string::npos)
      << message(a, VectorLD::Ones(3), o);
}

}  // namespace
}  // namespace femup
