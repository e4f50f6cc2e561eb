// BasisMatrix: a basis held on its DOFs equals the n x n matrix it came from,
// whichever way it is built, and its products and triplets act on those DOFs.
#include "femup/core/fe/basis_matrix.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;

// A symmetric n x n matrix with entries on `dofs` only (random, fixed seed).
Eigen::MatrixXd RandomOn(int n, const std::vector<int>& dofs, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i : dofs) {
    for (int j : dofs) {
      if (i <= j) a(i, j) = a(j, i) = u(rng);
    }
  }
  return a;
}

TEST(BasisMatrix, FromAFullMatrixKeepsItsDofsAndEntries) {
  const int n = 9;
  const std::vector<int> dofs = {1, 4, 5, 8};
  const Eigen::MatrixXd a = RandomOn(n, dofs, 7);
  const BasisMatrix b(Sparse(a.sparseView()));
  EXPECT_EQ(b.rows(), n);
  EXPECT_EQ(b.cols(), n);
  EXPECT_EQ(b.dofs(), dofs);
  EXPECT_EQ(b.local().rows(), 4);
  EXPECT_EQ(b.nonZeros(), 16);
  EXPECT_EQ(Eigen::MatrixXd(b.ToSparse()), a);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_EQ(b.local().coeff(i, j), a(dofs[i], dofs[j]));
  }
}

TEST(BasisMatrix, FromALocalMatrixSortsItsDofs) {
  // Local matrix on DOFs listed 6, 2, 3: entry (i, j) belongs at (dofs[i], dofs[j]).
  Eigen::MatrixXd local(3, 3);
  local << 1, 2, 3, 2, 4, 5, 3, 5, 6;
  const BasisMatrix b(8, {6, 2, 3}, Sparse(local.sparseView()));
  EXPECT_EQ(b.dofs(), (std::vector<int>{2, 3, 6}));
  const Eigen::MatrixXd full(b.ToSparse());
  EXPECT_EQ(full(6, 6), 1);
  EXPECT_EQ(full(6, 2), 2);
  EXPECT_EQ(full(2, 6), 2);
  EXPECT_EQ(full(3, 6), 3);
  EXPECT_EQ(full(2, 2), 4);
  EXPECT_EQ(full(2, 3), 5);
  EXPECT_EQ(full(3, 3), 6);
  EXPECT_EQ(full.cwiseAbs().sum(), 1 + 2 * 2 + 2 * 3 + 4 + 2 * 5 + 6);
}

TEST(BasisMatrix, FromTripletsSumsDuplicatesLikeEigen) {
  const int n = 12;
  std::vector<Triplet> t = {{3, 3, 1.0}, {3, 7, -2.0},  {7, 3, -2.0}, {7, 7, 4.0},
                            {3, 3, 0.5}, {10, 10, 2.0}, {7, 10, 1.5}, {10, 7, 1.5}};
  const BasisMatrix b = BasisMatrix::FromTriplets(n, t.cbegin(), t.cend());
  Sparse expected(n, n);
  expected.setFromTriplets(t.begin(), t.end());
  EXPECT_EQ(b.dofs(), (std::vector<int>{3, 7, 10}));
  EXPECT_EQ(Eigen::MatrixXd(b.ToSparse()), Eigen::MatrixXd(expected));
  // Only a segment of the list.
  const BasisMatrix first = BasisMatrix::FromTriplets(n, t.cbegin(), t.cbegin() + 4);
  EXPECT_EQ(first.dofs(), (std::vector<int>{3, 7}));
  EXPECT_EQ(first.nonZeros(), 4);
}

TEST(BasisMatrix, RestrictedProductIsTheFullProductOnItsDofs) {
  const int n = 20;
  const std::vector<int> dofs = {0, 3, 11, 19};
  const Eigen::MatrixXd a = RandomOn(n, dofs, 11);
  const BasisMatrix b(Sparse(a.sparseView()));
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  Eigen::MatrixXd x(n, 3);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = g(rng);
  const Eigen::MatrixXd full = a * x;
  // A block of a larger matrix is taken without a copy (Eigen::Ref).
  Eigen::MatrixXd wide(n, 5);
  wide.leftCols(3) = x;
  const Eigen::MatrixXd got = b.RestrictedProduct(wide.leftCols(3));
  ASSERT_EQ(got.rows(), 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_LE((got.row(i) - full.row(dofs[i])).cwiseAbs().maxCoeff(), 1e-14);
  }
  // Rows off the basis's DOFs of the full product are zero.
  EXPECT_EQ(full.row(5).cwiseAbs().sum(), 0.0);
}

TEST(BasisMatrix, FormAndAddedProductAreTheFullOnes) {
  const int n = 15;
  const std::vector<int> dofs = {2, 6, 7, 14};
  const Eigen::MatrixXd a = RandomOn(n, dofs, 23);
  const BasisMatrix b(Sparse(a.sparseView()));
  std::mt19937 rng(9);
  std::normal_distribution<double> g;
  Eigen::VectorXd x(n), y(n);
  for (int i = 0; i < n; ++i) {
    x[i] = g(rng);
    y[i] = g(rng);
  }
  EXPECT_NEAR(b.Form(x, y), x.dot(a * y), 1e-13);
  Eigen::VectorXd z = y;
  b.AddProductTo(-2.5, x, &z);
  EXPECT_LE((z - (y - 2.5 * a * x)).cwiseAbs().maxCoeff(), 1e-13);
  Eigen::VectorXd short_vector(n - 1);
  EXPECT_THROW(b.Form(short_vector, y), InputError);
  EXPECT_THROW(b.AddProductTo(1.0, x, &short_vector), InputError);
}

TEST(BasisMatrix, AppendTripletsScalesAndPlaces) {
  const int n = 6;
  const Eigen::MatrixXd a = RandomOn(n, {1, 2}, 5);
  const BasisMatrix b(Sparse(a.sparseView()));
  std::vector<Triplet> t;
  b.AppendTriplets(-3.0, &t);
  Sparse s(n, n);
  s.setFromTriplets(t.begin(), t.end());
  EXPECT_LE((Eigen::MatrixXd(s) + 3.0 * a).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(BasisMatrix, MovesAndSwapsWithoutLosingEntries) {
  const Eigen::MatrixXd a = RandomOn(5, {0, 4}, 2);
  BasisMatrix b(Sparse(a.sparseView()));
  BasisMatrix moved(std::move(b));
  EXPECT_EQ(Eigen::MatrixXd(moved.ToSparse()), a);
  BasisMatrix other;
  other = std::move(moved);
  EXPECT_EQ(other.rows(), 5);
  EXPECT_EQ(Eigen::MatrixXd(other.ToSparse()), a);
  BasisMatrix empty;
  empty.swap(other);
  EXPECT_EQ(empty.dofs(), (std::vector<int>{0, 4}));
  EXPECT_EQ(other.rows(), 0);
  const BasisMatrix copy = empty;
  EXPECT_EQ(Eigen::MatrixXd(copy.ToSparse()), a);
}

TEST(BasisMatrix, BadInputNamesWhatIsWrong) {
  const auto what = [](auto make) {
    try {
      make();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const Sparse two(Eigen::MatrixXd::Identity(2, 2).sparseView());
  EXPECT_NE(what([&] {
              BasisMatrix(5, {1, 2, 3}, two);
            }).find("expected 3 x 3"),
            std::string::npos);
  EXPECT_NE(what([&] {
              BasisMatrix(5, {1, 7}, two);
            }).find("DOF 7 is outside [0, 5)"),
            std::string::npos);
  EXPECT_NE(what([&] {
              BasisMatrix(5, {2, 2}, two);
            }).find("DOF 2 is listed twice"),
            std::string::npos);
  EXPECT_NE(what([&] { BasisMatrix(Sparse(2, 3)); }).find("expected a square matrix"),
            std::string::npos);
  const std::vector<Triplet> t = {{0, 9, 1.0}};
  EXPECT_NE(what([&] {
              BasisMatrix::FromTriplets(4, t.cbegin(), t.cend());
            }).find("entry (0, 9) is outside a 4 x 4 matrix"),
            std::string::npos);
  EXPECT_NE(what([&] {
              Eigen::MatrixXd x(3, 1);
              BasisMatrix(two).RestrictedProduct(x);
            }).find("3 rows, expected 2"),
            std::string::npos);
}

}  // namespace
}  // namespace femup
