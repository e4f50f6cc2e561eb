// SparseCholesky (sparse_cholesky.h) against Eigen's dense LLT on small
// matrices: solves, half solves with dense and sparse right-hand sides, the
// weighted inner products they give, for every ordering; and its errors.
#include "femup/core/linalg/sparse_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "concurrent_runs.h"
#include "femup/core/errors.h"

namespace femup {
namespace {

// A 2D grid Laplacian (nx x ny, 5-point) plus `shift` on the diagonal: SPD for
// shift > 0, with a fill pattern that depends on the ordering.
SparseMatrix Grid(int nx, int ny, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  const auto id = [nx](int i, int j) { return j * nx + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i + 1 < nx) {
        t.emplace_back(id(i, j), id(i + 1, j), -1.0);
        t.emplace_back(id(i + 1, j), id(i, j), -1.0);
      }
      if (j + 1 < ny) {
        t.emplace_back(id(i, j), id(i, j + 1), -1.0);
        t.emplace_back(id(i, j + 1), id(i, j), -1.0);
      }
    }
  }
  SparseMatrix a(nx * ny, nx * ny);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

// Columns with a few random entries each, in a few random rows.
SparseMatrix SparseColumns(int n, int cols, int per_column, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> row(0, n - 1);
  std::normal_distribution<double> value(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < cols; ++c) {
    for (int k = 0; k < per_column; ++k) t.emplace_back(row(rng), c, value(rng));
  }
  SparseMatrix b(n, cols);
  b.setFromTriplets(t.begin(), t.end());
  return b;
}

using Ordering = SparseCholeskyOptions::Ordering;

class SparseCholeskyOrdering : public ::testing::TestWithParam<Ordering> {};

TEST_P(SparseCholeskyOrdering, SolvesAsTheDenseFactor) {
  const SparseMatrix a = Grid(13, 11, 0.05);
  const Eigen::MatrixXd dense = a;
  SparseCholeskyOptions options;
  options.ordering = GetParam();
  const SparseCholesky chol(a, options);
  EXPECT_EQ(chol.size(), a.rows());
  EXPECT_GE(chol.info().nnz_l, (a.nonZeros() + a.rows()) / 2);

  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd b(a.rows(), 3);
  for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = normal(rng);
  const Eigen::MatrixXd x = chol.Solve(b);
  const Eigen::MatrixXd reference = dense.llt().solve(b);
  EXPECT_LT((x - reference).cwiseAbs().maxCoeff(),
            1e-10 * reference.cwiseAbs().maxCoeff());
  EXPECT_LT((dense * x - b).norm(), 1e-11 * b.norm() * dense.norm());

  // b' A^-1 b = y' y for y = L^-1 P b.
  const Eigen::MatrixXd y = chol.HalfSolve(b);
  const Eigen::MatrixXd weighted = b.transpose() * reference;
  EXPECT_LT((y.transpose() * y - weighted).cwiseAbs().maxCoeff(),
            1e-10 * weighted.cwiseAbs().maxCoeff());
}

TEST_P(SparseCholeskyOrdering, SparseHalfSolveEqualsTheDenseOne) {
  const SparseMatrix a = Grid(17, 9, 0.01);
  SparseCholeskyOptions options;
  options.ordering = GetParam();
  const SparseCholesky chol(a, options);
  const SparseMatrix b = SparseColumns(static_cast<int>(a.rows()), 25, 3, 5);
  const SparseMatrix w = chol.HalfSolve(b);
  ASSERT_EQ(w.rows(), a.rows());
  ASSERT_EQ(w.cols(), b.cols());
  const Eigen::MatrixXd dense_w = chol.HalfSolve(Eigen::MatrixXd(b));
  EXPECT_LT((Eigen::MatrixXd(w) - dense_w).cwiseAbs().maxCoeff(),
            1e-13 * dense_w.cwiseAbs().maxCoeff());
  // Every entry the dense solve makes nonzero is in the sparse pattern.
  const Eigen::MatrixXd pattern = Eigen::MatrixXd(w).cwiseAbs();
  for (Eigen::Index c = 0; c < w.cols(); ++c) {
    for (Eigen::Index r = 0; r < w.rows(); ++r) {
      if (dense_w(r, c) != 0.0) {
        EXPECT_NE(pattern(r, c), 0.0) << r << ", " << c;
      }
    }
  }
  // And the pattern is sparse: a column holds the elimination-tree ancestors
  // of its entries only, not all n rows.
  EXPECT_LT(w.nonZeros(), b.cols() * a.rows() / 2);
  // W' W = B' A^-1 B.
  const Eigen::MatrixXd reference =
      Eigen::MatrixXd(b).transpose() * Eigen::MatrixXd(a).llt().solve(Eigen::MatrixXd(b));
  const Eigen::MatrixXd gram = Eigen::MatrixXd(SparseMatrix(w.transpose()) * w);
  EXPECT_LT((gram - reference).cwiseAbs().maxCoeff(),
            1e-10 * reference.cwiseAbs().maxCoeff());
}

TEST_P(SparseCholeskyOrdering, SharedPatternHalfSolveEqualsTheDenseOne) {
  const SparseMatrix a = Grid(15, 10, 0.02);
  SparseCholeskyOptions options;
  options.ordering = GetParam();
  const SparseCholesky chol(a, options);
  const SparseMatrix pattern = SparseColumns(static_cast<int>(a.rows()), 20, 4, 13);
  std::vector<SparseMatrix> b(3, pattern);
  std::mt19937_64 rng(21);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (SparseMatrix& bj : b) {
    for (Eigen::Index k = 0; k < bj.nonZeros(); ++k) bj.valuePtr()[k] = normal(rng);
  }
  b[1].valuePtr()[0] = 0.0;  // an explicit zero keeps its place in the pattern
  const std::vector<SparseMatrix> w = chol.HalfSolve(b);
  ASSERT_EQ(w.size(), b.size());
  for (std::size_t j = 0; j < b.size(); ++j) {
    const Eigen::MatrixXd one = chol.HalfSolve(Eigen::MatrixXd(b[j]));
    EXPECT_LT((Eigen::MatrixXd(w[j]) - one).cwiseAbs().maxCoeff(),
              1e-13 * one.cwiseAbs().maxCoeff())
        << j;
    EXPECT_EQ(w[j].nonZeros(), w[0].nonZeros());
  }
  EXPECT_TRUE(chol.HalfSolve(std::vector<SparseMatrix>{}).empty());
  std::vector<SparseMatrix> mixed = {
      pattern, SparseColumns(static_cast<int>(a.rows()), 20, 4, 14)};
  EXPECT_THROW(chol.HalfSolve(mixed), InputError);
}

INSTANTIATE_TEST_SUITE_P(All, SparseCholeskyOrdering,
                         ::testing::Values(Ordering::kAuto, Ordering::kAmd,
                                           Ordering::kNestedDissection));

TEST(SparseCholesky, NestedDissectionKeepsHalfSolvesShorterOnALongStrip) {
  // A long strip (3 x 400): minimum degree eliminates it end to end, so a
  // column near one end reaches most of the strip; nested dissection cuts it
  // in halves, quarters, ..., so the reach is a few separators.
  const SparseMatrix a = Grid(3, 400, 0.01);
  const SparseMatrix b = SparseColumns(static_cast<int>(a.rows()), 40, 2, 9);
  SparseCholeskyOptions nd;
  nd.ordering = Ordering::kNestedDissection;
  const SparseMatrix w = SparseCholesky(a, nd).HalfSolve(b);
  EXPECT_LT(w.nonZeros(), b.cols() * a.rows() / 10);
}

TEST(SparseCholesky, CountsTheFactorisationsFlopsFromTheColumnCounts) {
  // A path (tridiagonal, n = 50) has no fill under minimum degree, which
  // eliminates it from the ends: every column of L holds its diagonal and one
  // entry below but the last, so nnz(L) = 2n - 1 and the LL' flop count
  // sum_j c_j^2 is 4 (n - 1) + 1. Nested dissection's separators make some
  // fill on it, hence more flops: never fewer than without fill.
  SparseCholeskyOptions amd;
  amd.ordering = Ordering::kAmd;
  const SparseCholesky path(Grid(50, 1, 0.5), amd);
  EXPECT_EQ(path.info().nnz_l, 99);
  EXPECT_EQ(path.info().flops, 197.0);
  SparseCholeskyOptions nd;
  nd.ordering = Ordering::kNestedDissection;
  EXPECT_GE(SparseCholesky(Grid(50, 1, 0.5), nd).info().flops, 197.0);
  // A diagonal matrix: one entry per column, n flops.
  SparseMatrix diagonal(7, 7);
  diagonal.setIdentity();
  EXPECT_EQ(SparseCholesky(diagonal).info().flops, 7.0);
}

// The half solve's operation count from its result's pattern: on a diagonal
// matrix one division per entry and right-hand side; on a path under minimum
// degree (L bidiagonal, the last column alone) three more per entry outside
// the last row.
TEST(SparseCholesky, CountsTheHalfSolvesFlopsFromThePattern) {
  SparseMatrix diagonal(7, 7);
  diagonal.setIdentity();
  const SparseCholesky d(diagonal);
  const SparseMatrix b = SparseColumns(7, 3, 2, 5);
  const SparseMatrix w = d.HalfSolve(b);
  EXPECT_EQ(d.HalfSolveFlops(w, 4), 4.0 * static_cast<double>(w.nonZeros()));
  SparseCholeskyOptions amd;
  amd.ordering = Ordering::kAmd;
  const SparseCholesky path(Grid(50, 1, 0.5), amd);
  SparseMatrix one(50, 1);
  one.insert(0, 0) = 1.0;
  const SparseMatrix reach = path.HalfSolve(one);
  double expected = 0;
  for (SparseMatrix::InnerIterator it(reach, 0); it; ++it)
    expected += it.row() == 49 ? 1.0 : 3.0;
  EXPECT_EQ(path.HalfSolveFlops(reach, 1), expected);
  EXPECT_THROW(path.HalfSolveFlops(reach, 0), InputError);
  EXPECT_THROW(path.HalfSolveFlops(w, 1), InputError);
}

// The shared-pattern half solve runs blocks of columns on threads: the same
// bits for 1, 2 and 3 threads (each column's arithmetic is its own), and the
// same pattern; a negative count is refused by name.
TEST(SparseCholesky, HalfSolveThreadsGiveTheSameBits) {
  const SparseMatrix a = Grid(30, 20, 0.02);
  const SparseMatrix pattern = SparseColumns(static_cast<int>(a.rows()), 100, 5, 31);
  std::vector<SparseMatrix> b(4, pattern);
  std::mt19937_64 rng(33);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (SparseMatrix& bj : b) {
    for (Eigen::Index k = 0; k < bj.nonZeros(); ++k) bj.valuePtr()[k] = normal(rng);
  }
  std::vector<std::vector<SparseMatrix>> runs;
  for (const int threads : {1, 2, 3}) {
    SparseCholeskyOptions options;
    options.threads = threads;
    runs.push_back(SparseCholesky(a, options).HalfSolve(b));
  }
  for (std::size_t r = 1; r < runs.size(); ++r) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      const SparseMatrix& one = runs[0][j];
      const SparseMatrix& other = runs[r][j];
      ASSERT_EQ(other.nonZeros(), one.nonZeros());
      EXPECT_TRUE(std::equal(one.outerIndexPtr(), one.outerIndexPtr() + one.cols() + 1,
                             other.outerIndexPtr()));
      EXPECT_TRUE(std::equal(one.innerIndexPtr(), one.innerIndexPtr() + one.nonZeros(),
                             other.innerIndexPtr()));
      EXPECT_TRUE(
          std::equal(one.valuePtr(), one.valuePtr() + one.nonZeros(), other.valuePtr()));
    }
  }
  // And the values are L^-1 P B: W' W = B' A^-1 B against a dense solve.
  const Eigen::MatrixXd dense_b(b[2]);
  const Eigen::MatrixXd reference =
      dense_b.transpose() * Eigen::MatrixXd(a).llt().solve(dense_b);
  const Eigen::MatrixXd w(runs[1][2]);
  EXPECT_LT((w.transpose() * w - reference).cwiseAbs().maxCoeff(),
            1e-12 * reference.cwiseAbs().maxCoeff());
  SparseCholeskyOptions negative;
  negative.name = "model.mass";
  negative.threads = -1;
  try {
    SparseCholesky chol(a, negative);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "model.mass");
    EXPECT_NE(std::string(e.what()).find("threads"), std::string::npos) << e.what();
  }
}

// Factorisations on several threads at once give the bits of one alone, with
// METIS's nested dissection, whose random generator is a global of METIS's
// (internal::MetisMutex): without the lock, the Ritz bases of a diagnosis's
// fits (ritz_basis.cc) changed with the threads' timing.
TEST(SparseCholesky, FactorisationsOnSeveralThreadsAtOnceGiveTheBitsOfOneAlone) {
  const SparseMatrix a = Grid(30, 40, 0.1);
  const Eigen::MatrixXd b =
      Eigen::MatrixXd(SparseColumns(static_cast<int>(a.rows()), 3, 5, 11));
  SparseCholeskyOptions nd;
  nd.ordering = Ordering::kNestedDissection;
  const Eigen::MatrixXd alone = SparseCholesky(a, nd).Solve(b);
  femup::testing::ExpectSameBitsOnThreads(
      4, 25, [&] { return SparseCholesky(a, nd).Solve(b) == alone; });
}

// Three unknowns per node of a grid (a node's block couples them): the factor
// ordered on the node graph solves as the dense factor and fills about as
// little as the one ordered on the unknowns themselves.
TEST(SparseCholesky, NodeGroupOrderingSolvesAndFillsAsTheUnknownOrdering) {
  const SparseMatrix grid = Grid(24, 18, 0.05);
  const int nodes = static_cast<int>(grid.rows());
  Eigen::Matrix3d block;
  block << 2.0, 0.3, 0.1, 0.3, 1.5, 0.2, 0.1, 0.2, 1.0;  // SPD
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < grid.outerSize(); ++c) {
    for (SparseMatrix::InnerIterator it(grid, c); it; ++it) {
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          t.emplace_back(3 * static_cast<int>(it.row()) + a, 3 * c + b,
                         it.value() * block(a, b));
    }
  }
  SparseMatrix a(3 * nodes, 3 * nodes);
  a.setFromTriplets(t.begin(), t.end());
  SparseCholeskyOptions by_unknown;
  SparseCholeskyOptions by_node;
  for (int i = 0; i < 3 * nodes; ++i) by_node.groups.push_back(i / 3);
  const SparseCholesky plain(a, by_unknown), grouped(a, by_node);
  EXPECT_LT(grouped.info().nnz_l, 1.25 * static_cast<double>(plain.info().nnz_l));
  std::mt19937_64 rng(41);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd b(a.rows(), 2);
  for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = normal(rng);
  const Eigen::MatrixXd x = Eigen::MatrixXd(a).llt().solve(b);
  EXPECT_LT((grouped.Solve(b) - x).cwiseAbs().maxCoeff(),
            1e-12 * x.cwiseAbs().maxCoeff());
  // A group list of the wrong size, or a negative group, is refused by name.
  SparseCholeskyOptions bad;
  bad.name = "model.mass";
  bad.groups = {0, 1};
  EXPECT_THROW(SparseCholesky(a, bad), InputError);
  bad.groups.assign(static_cast<std::size_t>(a.rows()), 0);
  bad.groups[3] = -1;
  try {
    SparseCholesky chol(a, bad);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "model.mass");
    EXPECT_NE(std::string(e.what()).find("groups"), std::string::npos) << e.what();
  }
}

TEST(SparseCholesky, RejectsWhatItCannotFactorise) {
  SparseCholeskyOptions options;
  options.name = "model.mass";
  const SparseMatrix rectangular(4, 3);
  try {
    SparseCholesky chol(rectangular, options);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "model.mass");
    EXPECT_NE(std::string(e.what()).find("square"), std::string::npos) << e.what();
  }
  SparseMatrix indefinite = Grid(4, 4, 0.1);
  indefinite.coeffRef(5, 5) = -1.0;
  try {
    SparseCholesky chol(indefinite, options);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("DOF index"), std::string::npos) << e.what();
  }
  SparseMatrix nan = Grid(4, 4, 0.1);
  nan.coeffRef(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SparseCholesky(nan, options), InputError);
  const SparseCholesky chol(Grid(4, 4, 0.1), options);
  EXPECT_THROW(chol.HalfSolve(Eigen::MatrixXd::Ones(3, 1)), InputError);
  EXPECT_THROW(chol.HalfSolve(SparseMatrix(3, 1)), InputError);
}

}  // namespace
}  // namespace femup
