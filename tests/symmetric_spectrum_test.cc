// Dense symmetric spectra and pencils by LAPACK
// (core/include/femup/core/linalg/symmetric_spectrum.h), checked against
// closed forms: the second-difference matrix's eigenvalues
// 2 - 2 cos(j pi / (n + 1)) and sine vectors, and a pencil with a diagonal
// mass (a chain of unequal masses seen through M^(-1/2)).
#include "femup/core/linalg/symmetric_spectrum.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

namespace femup {
namespace {

const double kPi = std::acos(-1.0);

// tridiag(-1, 2, -1), n x n.
Eigen::MatrixXd SecondDifference(int n) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 2;
    if (i + 1 < n) a(i + 1, i) = a(i, i + 1) = -1;
  }
  return a;
}

double SecondDifferenceValue(int n, int j) {  // j = 1..n
  return 2 - 2 * std::cos(j * kPi / (n + 1));
}

TEST(SymmetricSpectrum, SecondDifferenceEigenvaluesAndVectors) {
  const int n = 40;
  Eigen::VectorXd all;
  ASSERT_TRUE(SymmetricEigenvalues(SecondDifference(n), &all));
  ASSERT_EQ(all.size(), n);
  for (int j = 1; j <= n; ++j)
    EXPECT_NEAR(all[j - 1], SecondDifferenceValue(n, j), 1e-13);

  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  ASSERT_TRUE(SmallestEigenpairs(SecondDifference(n), 3, &values, &vectors));
  ASSERT_EQ(vectors.rows(), n);
  ASSERT_EQ(vectors.cols(), 3);
  for (int j = 1; j <= 3; ++j) {
    EXPECT_NEAR(values[j - 1], SecondDifferenceValue(n, j), 1e-13);
    Eigen::VectorXd sine(n);
    for (int i = 0; i < n; ++i) sine[i] = std::sin((i + 1) * j * kPi / (n + 1));
    sine.normalize();
    EXPECT_NEAR(std::abs(sine.dot(vectors.col(j - 1))), 1.0, 1e-12) << "mode " << j;
  }
}

TEST(SymmetricSpectrum, OnlyTheLowerTriangleIsRead) {
  Eigen::MatrixXd a = SecondDifference(6);
  a.triangularView<Eigen::StrictlyUpper>().setConstant(99.0);
  Eigen::VectorXd values;
  ASSERT_TRUE(SymmetricEigenvalues(a, &values));
  for (int j = 1; j <= 6; ++j)
    EXPECT_NEAR(values[j - 1], SecondDifferenceValue(6, j), 1e-13);
}

// K x = lambda M x with M = D^2 diagonal: y = D x solves D^-1 K D^-1 y =
// lambda y. With K = D T D (T the second-difference matrix) the eigenvalues
// are T's and x = D^-1 (T's vector), M-orthonormal.
TEST(SymmetricSpectrum, PencilWithADiagonalMassHasTheClosedForm) {
  const int n = 30;
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> scale(0.5, 3.0);
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d[i] = scale(rng);
  const Eigen::MatrixXd t = SecondDifference(n);
  const Eigen::MatrixXd k = d.asDiagonal() * t * d.asDiagonal();
  const Eigen::MatrixXd m = d.cwiseAbs2().asDiagonal();
  for (int count : {1, 4, n}) {
    Eigen::VectorXd values;
    Eigen::MatrixXd vectors;
    ASSERT_EQ(SmallestPencilEigenpairs(k, m, count, &values, &vectors),
              PencilStatus::kOk);
    ASSERT_EQ(values.size(), count);
    ASSERT_EQ(vectors.rows(), n);
    ASSERT_EQ(vectors.cols(), count);
    for (int j = 1; j <= count; ++j) {
      EXPECT_NEAR(values[j - 1], SecondDifferenceValue(n, j), 1e-12);
      Eigen::VectorXd x(n);
      for (int i = 0; i < n; ++i) x[i] = std::sin((i + 1) * j * kPi / (n + 1)) / d[i];
      x /= std::sqrt(x.dot(m * x));
      EXPECT_NEAR(std::abs(x.dot(m * vectors.col(j - 1))), 1.0, 1e-11) << "mode " << j;
    }
    const Eigen::MatrixXd gram = vectors.transpose() * m * vectors;
    EXPECT_LT((gram - Eigen::MatrixXd::Identity(count, count)).cwiseAbs().maxCoeff(),
              1e-12);
  }
}

TEST(SymmetricSpectrum, PencilRefusesAMassThatIsNotPositiveDefinite) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Identity(4, 4);
  m(2, 2) = -1;
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  EXPECT_EQ(SmallestPencilEigenpairs(SecondDifference(4), m, 2, &values, &vectors),
            PencilStatus::kMassNotPositiveDefinite);
  EXPECT_EQ(SmallestPencilEigenpairs(SecondDifference(4), Eigen::MatrixXd::Identity(4, 4),
                                     5, &values, &vectors),
            PencilStatus::kFailed);
  EXPECT_EQ(SmallestPencilEigenpairs(SecondDifference(4), Eigen::MatrixXd::Identity(3, 3),
                                     2, &values, &vectors),
            PencilStatus::kFailed);
  ASSERT_EQ(SmallestPencilEigenpairs(SecondDifference(4), Eigen::MatrixXd::Identity(4, 4),
                                     0, &values, &vectors),
            PencilStatus::kOk);
  EXPECT_EQ(values.size(), 0);
  EXPECT_EQ(vectors.rows(), 4);
}

}  // namespace
}  // namespace femup
