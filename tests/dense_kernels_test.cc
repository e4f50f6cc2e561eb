// The BLAS-backed dense kernels (femup/core/linalg/dense_kernels.h) against
// Eigen's own products.
#include "femup/core/linalg/dense_kernels.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstdlib>
#include <limits>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace {

TEST(RankUpdateLower, LowerTriangleOfBetaCPlusAlphaATransposeA) {
  std::srand(11);  // Eigen's Random draws from rand()
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(7, 5);
  const Eigen::MatrixXd c0 = Eigen::MatrixXd::Random(5, 5);
  Eigen::MatrixXd c = c0;
  RankUpdateLower(a, 2.0, 0.5, c);
  const Eigen::MatrixXd expected = 0.5 * c0 + 2.0 * a.transpose() * a;
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 5; ++i) {
      if (i >= j) {
        EXPECT_NEAR(c(i, j), expected(i, j), 1e-14) << i << "," << j;
      } else {
        EXPECT_EQ(c(i, j), c0(i, j)) << "upper triangle touched at " << i << "," << j;
      }
    }
  }
}

TEST(RankUpdateLower, WorksOnBlocksOfLargerMatrices) {
  std::srand(12);
  const Eigen::MatrixXd big_a = Eigen::MatrixXd::Random(9, 8);
  Eigen::MatrixXd big_c = Eigen::MatrixXd::Zero(6, 6);
  // a: rows 1-4, columns 2-4 (a stride of 9); c: the 3 x 3 block at (2, 1).
  RankUpdateLower(big_a.block(1, 2, 4, 3), 1.0, 0.0, big_c.block(2, 1, 3, 3));
  const Eigen::MatrixXd expected =
      big_a.block(1, 2, 4, 3).transpose() * big_a.block(1, 2, 4, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = j; i < 3; ++i) EXPECT_NEAR(big_c(2 + i, 1 + j), expected(i, j), 1e-14);
  }
  // Nothing outside the block's lower triangle was written.
  EXPECT_EQ(big_c.topRows(2).cwiseAbs().sum(), 0.0);
  EXPECT_EQ(big_c.col(0).cwiseAbs().sum(), 0.0);
  EXPECT_EQ(big_c(2, 2), 0.0);
}

TEST(RankUpdateLower, NoRowsScalesAndWrongSizeIsNamed) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Ones(3, 3);
  RankUpdateLower(Eigen::MatrixXd(0, 3), 1.0, 3.0, c);
  EXPECT_EQ(c(2, 0), 3.0);
  EXPECT_EQ(c(0, 2), 1.0);
  // beta = 0: c's lower triangle is not read (a NaN there becomes 0).
  c(2, 0) = std::numeric_limits<double>::quiet_NaN();
  RankUpdateLower(Eigen::MatrixXd(0, 3), 1.0, 0.0, c);
  EXPECT_EQ(c(2, 0), 0.0);
  try {
    RankUpdateLower(Eigen::MatrixXd::Ones(2, 4), 1.0, 0.0, c);
    FAIL() << "a 3 x 3 c accepted for 4 columns";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "c");
  }
}

// An SPD matrix's factor against Eigen's LLT, and its inverse against a solve.
TEST(CholeskyLower, FactorOfAPositiveDefiniteMatrixAndItsInverse) {
  std::srand(13);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(9, 6);
  const Eigen::MatrixXd spd = b.transpose() * b + Eigen::MatrixXd::Identity(6, 6);
  Eigen::MatrixXd a = spd;
  a.triangularView<Eigen::StrictlyUpper>().setConstant(7.0);  // not read
  ASSERT_TRUE(CholeskyLower(a));
  const Eigen::MatrixXd expected = spd.llt().matrixL();
  const Eigen::MatrixXd l = a.triangularView<Eigen::Lower>();
  EXPECT_LT((l - expected).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_EQ(a(0, 5), 7.0);  // nor written
  ASSERT_TRUE(InvertLowerTriangular(a));
  const Eigen::MatrixXd inverse = a.triangularView<Eigen::Lower>();
  EXPECT_LT((inverse * l - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_EQ(a(0, 5), 7.0);
}

TEST(CholeskyLower, IndefiniteAndSingularAreFalseAndNonSquareIsNamed) {
  Eigen::MatrixXd indefinite(2, 2);
  indefinite << 1, 2, 2, 1;
  EXPECT_FALSE(CholeskyLower(indefinite));
  Eigen::MatrixXd singular = Eigen::MatrixXd::Identity(3, 3);
  singular(1, 1) = 0;
  EXPECT_FALSE(InvertLowerTriangular(singular));
  Eigen::MatrixXd empty(0, 0);
  EXPECT_TRUE(CholeskyLower(empty));
  EXPECT_TRUE(InvertLowerTriangular(empty));
  for (const bool factor : {true, false}) {
    try {
      Eigen::MatrixXd rectangle = Eigen::MatrixXd::Ones(2, 3);
      if (factor) {
        CholeskyLower(rectangle);
      } else {
        InvertLowerTriangular(rectangle);
      }
      FAIL() << "a 2 x 3 matrix accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "a");
    }
  }
}

TEST(SolveLowerInPlace, AgainstEigensTriangularSolveAndSizesNamed) {
  std::srand(15);
  Eigen::MatrixXd l = Eigen::MatrixXd::Random(5, 5);
  l.diagonal().array() += 4.0;
  l.triangularView<Eigen::StrictlyUpper>().setConstant(
      std::numeric_limits<double>::quiet_NaN());  // not read
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(5, 3);
  Eigen::MatrixXd x = b;
  SolveLowerInPlace(l, x);
  const Eigen::MatrixXd lower = l.triangularView<Eigen::Lower>();
  EXPECT_LT((lower * x - b).cwiseAbs().maxCoeff(), 1e-14);
  Eigen::MatrixXd none(5, 0);
  SolveLowerInPlace(l, none);
  Eigen::MatrixXd wrong(4, 2);
  try {
    SolveLowerInPlace(l, wrong);
    FAIL() << "4 rows accepted for a 5 x 5 l";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "x");
  }
  try {
    SolveLowerInPlace(Eigen::MatrixXd::Ones(5, 4), x);
    FAIL() << "a 5 x 4 l accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "l");
  }
}

// A rank-2 semidefinite 5 x 5 matrix: rank 2, and P' a P = L L' on L's first
// two columns, the pivots a permutation, the largest diagonal entry first.
TEST(PivotedCholeskyLower, RankAndFactorOfASemidefiniteMatrix) {
  std::srand(14);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(2, 5);
  const Eigen::MatrixXd a0 = b.transpose() * b;
  Eigen::MatrixXd a = a0;
  std::vector<int> pivots;
  const int rank = PivotedCholeskyLower(a, -1, &pivots);
  ASSERT_EQ(rank, 2);
  ASSERT_EQ(pivots.size(), 5u);
  std::vector<int> sorted = pivots;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<int>{0, 1, 2, 3, 4}));
  Eigen::Index largest = 0;
  a0.diagonal().maxCoeff(&largest);
  EXPECT_EQ(pivots[0], largest);
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(5, 2);
  for (int j = 0; j < 2; ++j) l.col(j).tail(5 - j) = a.col(j).tail(5 - j);
  Eigen::MatrixXd permuted(5, 5);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) permuted(i, j) = a0(pivots[i], pivots[j]);
  }
  EXPECT_LT((l * l.transpose() - permuted).cwiseAbs().maxCoeff(), 1e-13);
  // A tolerance above the second pivot stops at the first.
  Eigen::MatrixXd again = a0;
  EXPECT_EQ(PivotedCholeskyLower(again, a0.diagonal().maxCoeff() * 0.999999, &pivots), 1);
}

TEST(PivotedCholeskyLower, NotFiniteIsMinusOneAndNonSquareIsNamed) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(3, 3);
  a(2, 1) = std::numeric_limits<double>::infinity();
  std::vector<int> pivots;
  EXPECT_EQ(PivotedCholeskyLower(a, -1, &pivots), -1);
  Eigen::MatrixXd empty(0, 0);
  EXPECT_EQ(PivotedCholeskyLower(empty, -1, &pivots), 0);
  Eigen::MatrixXd rectangle = Eigen::MatrixXd::Ones(3, 2);
  try {
    PivotedCholeskyLower(rectangle, -1, &pivots);
    FAIL() << "a 3 x 2 matrix accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "a");
  }
}

}  // namespace
}  // namespace femup
