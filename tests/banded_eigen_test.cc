// The banded eigensolver (core/include/femup/core/linalg/banded_eigen.h), checked against
// the analytic spectrum of a clamped Euler-Bernoulli beam, the analytic
// spectrum of a fixed-free spring chain, and the dense generalised solver on a
// random banded pencil.
#include "femup/core/linalg/banded_eigen.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <string>

namespace femup {
namespace {

const double kPi = std::acos(-1.0);

// A clamped Hermite beam of `ne` elements (EI = 1, m = 1 per length, length
// 1): bending DOFs (w, theta) of nodes 1..ne, bandwidth 3.
void ClampedBeam(int ne, Eigen::MatrixXd* k, Eigen::MatrixXd* m) {
  const double l = 1.0 / ne;
  Eigen::Matrix4d ke, me;
  ke << 12, 6 * l, -12, 6 * l, 6 * l, 4 * l * l, -6 * l, 2 * l * l, -12, -6 * l, 12,
      -6 * l, 6 * l, 2 * l * l, -6 * l, 4 * l * l;
  ke /= l * l * l;
  me << 156, 22 * l, 54, -13 * l, 22 * l, 4 * l * l, 13 * l, -3 * l * l, 54, 13 * l, 156,
      -22 * l, -13 * l, -3 * l * l, -22 * l, 4 * l * l;
  me *= l / 420;
  const int n = 2 * (ne + 1);
  Eigen::MatrixXd kf = Eigen::MatrixXd::Zero(n, n), mf = kf;
  for (int e = 0; e < ne; ++e) {
    kf.block<4, 4>(2 * e, 2 * e) += ke;
    mf.block<4, 4>(2 * e, 2 * e) += me;
  }
  *k = kf.bottomRightCorner(n - 2, n - 2);
  *m = mf.bottomRightCorner(n - 2, n - 2);
}

TEST(BandedEigen, ClampedBeamMatchesTheAnalyticSpectrum) {
  Eigen::MatrixXd k, m;
  ClampedBeam(40, &k, &m);
  EXPECT_EQ(Bandwidth(k), 3);
  BandedEigenpairs out;
  std::string why;
  ASSERT_TRUE(LowestBandedEigenpairs(k, m, 4, true, &out, &why)) << why;
  // beta_k L of a cantilever (the 40-element mesh is within 1e-5 of them) (roots of cos x
  // cosh x = -1).
  const double beta[] = {1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349};
  for (int p = 0; p < 4; ++p) {
    const double exact = std::pow(beta[p], 4);  // omega^2 with EI = m = L = 1
    EXPECT_NEAR(out.eigenvalues[p] / exact, 1.0, 2e-5) << "mode " << p + 1;
  }
  // Eigenvectors: residual, M-orthonormality, sign.
  for (int p = 0; p < 4; ++p) {
    const Eigen::VectorXd x = out.vectors.col(p);
    const Eigen::VectorXd r = k * x - out.eigenvalues[p] * (m * x);
    EXPECT_LT(r.norm(), 1e-12 * k.norm() * x.norm()) << "mode " << p + 1;
    Eigen::Index largest = 0;
    x.cwiseAbs().maxCoeff(&largest);
    EXPECT_GT(x[largest], 0);
    for (int q = 0; q < 4; ++q)
      EXPECT_NEAR(x.dot(m * out.vectors.col(q)), p == q ? 1.0 : 0.0, 1e-9);
  }
}

TEST(BandedEigen, FixedFreeChainMatchesTheAnalyticSpectrum) {
  // Unit masses and springs, spring 1 to the ground: lambda_k =
  // 4 sin^2((2k - 1) pi / (2 (2n + 1))).
  const int n = 30;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    k(i, i) = i + 1 < n ? 2 : 1;
    if (i + 1 < n) k(i, i + 1) = k(i + 1, i) = -1;
  }
  const Eigen::MatrixXd m = Eigen::MatrixXd::Identity(n, n);
  BandedEigenpairs out;
  std::string why;
  ASSERT_TRUE(LowestBandedEigenpairs(k, m, 5, false, &out, &why)) << why;
  EXPECT_EQ(out.vectors.size(), 0);
  for (int p = 1; p <= 5; ++p) {
    const double s = std::sin((2 * p - 1) * kPi / (2 * (2 * n + 1)));
    EXPECT_NEAR(out.eigenvalues[p - 1], 4 * s * s, 1e-13);
  }
}

TEST(BandedEigen, RandomBandedPencilMatchesTheDenseSolver) {
  std::mt19937 rng(20261125);
  std::normal_distribution<double> g(0, 1);
  const int n = 50, b = 4;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n), c = a;
  for (int i = 0; i < n; ++i)
    for (int j = i; j <= std::min(n - 1, i + b); ++j) {
      a(i, j) = a(j, i) = g(rng);
      c(i, j) = c(j, i) = 0.1 * g(rng);
    }
  const Eigen::MatrixXd k = a * 0.5 + a.transpose() * 0.5;
  // M diagonally dominant: positive definite.
  Eigen::MatrixXd m = c;
  for (int i = 0; i < n; ++i) m(i, i) = 2 + std::abs(g(rng));
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(k, m);
  BandedEigenpairs out;
  std::string why;
  ASSERT_TRUE(LowestBandedEigenpairs(k, m, 6, true, &out, &why)) << why;
  for (int p = 0; p < 6; ++p) {
    EXPECT_NEAR(out.eigenvalues[p], dense.eigenvalues()[p], 1e-11);
    const Eigen::VectorXd v = dense.eigenvectors().col(p);
    EXPECT_NEAR(std::abs(out.vectors.col(p).dot(m * v)), 1.0, 1e-8) << "mode " << p + 1;
  }
}

TEST(BandedEigen, RejectsBadInput) {
  Eigen::MatrixXd k, m;
  ClampedBeam(5, &k, &m);
  BandedEigenpairs out;
  std::string why;
  EXPECT_FALSE(LowestBandedEigenpairs(k, m.topLeftCorner(4, 4), 2, false, &out, &why));
  EXPECT_NE(why.find("same size"), std::string::npos) << why;
  EXPECT_FALSE(LowestBandedEigenpairs(k, m, 0, false, &out, &why));
  EXPECT_NE(why.find("between 1"), std::string::npos) << why;
  EXPECT_FALSE(LowestBandedEigenpairs(k, m, 11, false, &out, &why));
  Eigen::MatrixXd bad = m;
  bad(3, 3) = -1;
  EXPECT_FALSE(LowestBandedEigenpairs(k, bad, 2, false, &out, &why));
  EXPECT_NE(why.find("positive definite"), std::string::npos) << why;
}

}  // namespace
}  // namespace femup
