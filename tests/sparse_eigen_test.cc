#include "linalg/sparse_eigen.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "concurrent_runs.h"
#include "expect_error.h"
#include "femup/core/errors.h"

namespace femup {
namespace internal {
namespace {

const double kPi = std::acos(-1.0);

SparseMatrix FromTriplets(int n, const std::vector<Eigen::Triplet<double>>& triplets) {
  SparseMatrix a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

SparseMatrix Identity(int n) {
  SparseMatrix a(n, n);
  a.setIdentity();
  return a;
}

// Chain of n unit springs between n unit masses; `grounded` adds a spring from
// the first mass to the ground (fixed-free), otherwise the chain is free-free.
SparseMatrix ChainStiffness(int n, bool grounded) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i + 1 < n; ++i) {  // spring between masses i and i + 1
    t.emplace_back(i, i, 1.0);
    t.emplace_back(i + 1, i + 1, 1.0);
    t.emplace_back(i, i + 1, -1.0);
    t.emplace_back(i + 1, i, -1.0);
  }
  if (grounded) t.emplace_back(0, 0, 1.0);
  return FromTriplets(n, t);
}

// Random SPD pencil: K is a grid Laplacian with random edge stiffnesses plus
// small random ground springs; M is diagonal plus a diagonally dominated
// tridiagonal coupling.
void RandomPencil(int nx, int ny, unsigned seed, SparseMatrix* K, SparseMatrix* M) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> edge(0.5, 2.0);
  std::uniform_real_distribution<double> ground(0.01, 0.1);
  std::uniform_real_distribution<double> mass(1.0, 2.0);
  std::uniform_real_distribution<double> coupling(-0.2, 0.2);
  const int n = nx * ny;
  auto id = [nx](int x, int y) { return y * nx + x; };
  std::vector<Eigen::Triplet<double>> k;
  auto spring = [&k](int a, int b, double s) {
    k.emplace_back(a, a, s);
    k.emplace_back(b, b, s);
    k.emplace_back(a, b, -s);
    k.emplace_back(b, a, -s);
  };
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      if (x + 1 < nx) spring(id(x, y), id(x + 1, y), edge(rng));
      if (y + 1 < ny) spring(id(x, y), id(x, y + 1), edge(rng));
      k.emplace_back(id(x, y), id(x, y), ground(rng));
    }
  }
  std::vector<Eigen::Triplet<double>> m;
  for (int i = 0; i < n; ++i) m.emplace_back(i, i, mass(rng));
  for (int i = 0; i + 1 < n; ++i) {
    const double c = coupling(rng);
    m.emplace_back(i, i + 1, c);
    m.emplace_back(i + 1, i, c);
  }
  *K = FromTriplets(n, k);
  *M = FromTriplets(n, m);
}

double Mac(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double ab = a.dot(b);
  return ab * ab / (a.squaredNorm() * b.squaredNorm());
}

// Shared checks: ascending, M-orthonormal, small residuals, sign convention.
void ExpectValidModes(const SparseMatrix& K, const SparseMatrix& M, const Modes& modes,
                      int k) {
  ASSERT_EQ(modes.size(), k);
  ASSERT_EQ(modes.shapes.rows(), K.rows());
  ASSERT_EQ(modes.shapes.cols(), k);
  for (int j = 0; j + 1 < k; ++j) {
    EXPECT_LE(modes.eigenvalues[j], modes.eigenvalues[j + 1]) << "mode " << j;
  }
  const Eigen::MatrixXd gram = modes.shapes.transpose() * (M * modes.shapes);
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff(), 1e-9);
  for (int j = 0; j < k; ++j) {
    const Eigen::VectorXd phi = modes.shapes.col(j);
    const Eigen::VectorXd k_phi = K * phi;
    const Eigen::VectorXd residual = k_phi - modes.eigenvalues[j] * (M * phi);
    if (k_phi.norm() > 1e-8) {
      EXPECT_LT(residual.norm() / k_phi.norm(), 1e-8) << "mode " << j;
    } else {  // rigid-body mode
      EXPECT_LT(residual.norm(), 1e-10) << "mode " << j;
    }
    Eigen::Index largest = 0;
    phi.cwiseAbs().maxCoeff(&largest);
    EXPECT_GT(phi[largest], 0.0) << "mode " << j;
  }
}

using testing::InputErrorMessage;

TEST(SparseEigenTest, FixedFreeChainMatchesAnalyticEigenvalues) {
  const int n = 200;
  const int k = 10;
  const SparseMatrix K = ChainStiffness(n, /*grounded=*/true);
  const SparseMatrix M = Identity(n);
  EigenOptions options;
  options.num_modes = k;
  const Modes modes = SolveModesSparse(K, M, options);
  ExpectValidModes(K, M, modes, k);
  for (int j = 1; j <= k; ++j) {
    const double s = std::sin((2 * j - 1) * kPi / (2.0 * (2 * n + 1)));
    const double expected = 4.0 * s * s;
    EXPECT_NEAR(modes.eigenvalues[j - 1], expected, 1e-10 * expected) << "j = " << j;
  }
}

void ExpectMatchesDense(const SparseMatrix& K, const SparseMatrix& M, const Modes& modes,
                        int first, int k) {
  const Eigen::MatrixXd kd(K);
  const Eigen::MatrixXd md(M);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(kd, md);
  ASSERT_EQ(dense.info(), Eigen::Success);
  ExpectValidModes(K, M, modes, k);
  for (int j = 0; j < k; ++j) {
    const double expected = dense.eigenvalues()[first + j];
    EXPECT_NEAR(modes.eigenvalues[j], expected, 1e-9 * std::abs(expected)) << "j = " << j;
    EXPECT_GT(Mac(modes.shapes.col(j), dense.eigenvectors().col(first + j)), 1.0 - 1e-9)
        << "j = " << j;
  }
}

TEST(SparseEigenTest, RandomPencilMatchesDenseSolver) {
  SparseMatrix K, M;
  RandomPencil(20, 25, 20240611u, &K, &M);
  ASSERT_EQ(K.rows(), 500);
  EigenOptions options;
  options.num_modes = 12;
  const Modes modes = SolveModesSparse(K, M, options);
  ExpectMatchesDense(K, M, modes, 0, 12);
}

// The ordering on a graph of DOF groups (EigenOptions::dof_groups, as a model's
// nodes): the dense solver's modes on a grid pencil with its DOFs in groups of
// 5 consecutive ones (and a last group of another size); groups of the wrong
// size or a negative group are refused by name before any work.
TEST(SparseEigenTest, NodeGraphOrderingMatchesDenseSolver) {
  SparseMatrix K, M;
  RandomPencil(20, 25, 20261128u, &K, &M);
  EigenOptions options;
  options.num_modes = 10;
  for (Eigen::Index i = 0; i < K.rows(); ++i)
    options.dof_groups.push_back(static_cast<int>(std::min<Eigen::Index>(i / 5, 97)));
  const Modes modes = SolveModesSparse(K, M, options);
  ExpectMatchesDense(K, M, modes, 0, 10);
  options.dof_groups.pop_back();
  EXPECT_THROW(SolveModesSparse(K, M, options), InputError);
  options.dof_groups.push_back(-1);
  femup::testing::ExpectError([&] { SolveModesSparse(K, M, options); }, {"dof_groups"});
}

// Solves on several threads at once give the bits of a solve alone. METIS
// (the node-graph ordering) keeps its random number generator in global
// variables; without a lock, two orderings at once took each other's draws,
// and a diagnosis's fits changed with the number of threads.
TEST(SparseEigenTest, SolvesOnSeveralThreadsAtOnceGiveTheBitsOfOneAlone) {
  SparseMatrix K, M;
  RandomPencil(20, 25, 20261129u, &K, &M);
  EigenOptions options;
  options.num_modes = 6;
  for (Eigen::Index i = 0; i < K.rows(); ++i)
    options.dof_groups.push_back(static_cast<int>(i / 3));
  const Modes alone = SolveModesSparse(K, M, options);
  femup::testing::ExpectSameBitsOnThreads(4, 25, [&] {
    const Modes modes = SolveModesSparse(K, M, options);
    return modes.eigenvalues == alone.eigenvalues && modes.shapes == alone.shapes;
  });
}

// CHOLMOD's simplicial and supernodal LL' (a switch of 0 flops per entry of L
// makes every factorisation supernodal, a huge one simplicial) give the dense
// solver's modes, here with an M whose pattern is not inside K's (the grid's
// row ends are coupled in M only): both are factorised on one analysis of K + M.
TEST(SparseEigenTest, SimplicialAndSupernodalFactorisationsMatchDenseSolver) {
  SparseMatrix K, M;
  RandomPencil(20, 25, 20261127u, &K, &M);
  EigenOptions options;
  options.num_modes = 8;
  for (double supernodal_switch : {0.0, 1e300}) {
    SCOPED_TRACE(supernodal_switch);
    const Modes modes = SolveModesSparse(K, M, options, supernodal_switch);
    ExpectMatchesDense(K, M, modes, 0, 8);
  }
}

// The supernodal factorisation (CHOLMOD's dense kernels: the BLAS's dgemm,
// dsyrk, dtrsm and LAPACK's dpotrf) on several threads at once gives the bits
// of one alone: the BLAS is safe to call from femup's threads (OpenBLAS's
// pthread flavour locks its buffers; the serial flavour does not).
TEST(SparseEigenTest, SupernodalSolvesOnSeveralThreadsAtOnceGiveTheBitsOfOneAlone) {
  SparseMatrix K, M;
  RandomPencil(30, 30, 20261130u, &K, &M);
  EigenOptions options;
  options.num_modes = 6;
  const Modes alone = SolveModesSparse(K, M, options, 0.0);
  femup::testing::ExpectSameBitsOnThreads(4, 10, [&] {
    const Modes modes = SolveModesSparse(K, M, options, 0.0);
    return modes.eigenvalues == alone.eigenvalues && modes.shapes == alone.shapes;
  });
}

// The two Lanczos processes on one pencil: below the spectrum the standard form
// L^{-1} P M P' L^{-T} on K - shift*M's LL' factor; a shift inside the
// spectrum (here between modes 2 and 3 of the pencil) takes the LDL' factor
// and the M-inner product. Both give the dense solver's modes above the shift,
// and the modes they share agree to the dense solver's accuracy.
TEST(SparseEigenTest, StandardAndGeneralisedLanczosAgreeOnOnePencil) {
  SparseMatrix K, M;
  RandomPencil(20, 25, 20261128u, &K, &M);
  EigenOptions options;
  options.num_modes = 10;
  const Modes below = SolveModesSparse(K, M, options);  // LL': the standard form
  ExpectMatchesDense(K, M, below, 0, 10);
  options.shift = 0.5 * (below.eigenvalues[1] + below.eigenvalues[2]);
  options.num_modes = 6;
  const Modes inside = SolveModesSparse(K, M, options);  // LDL': the M-inner product
  ExpectMatchesDense(K, M, inside, 2, 6);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(inside.eigenvalues[j], below.eigenvalues[j + 2],
                1e-9 * below.eigenvalues[j + 2]);
    EXPECT_GT(Mac(inside.shapes.col(j), below.shapes.col(j + 2)), 1.0 - 1e-9) << j;
  }
}

// From 10^4 DOFs M's factorisation (its check) runs beside K - shift*M's when
// threads allow: the same bits whatever the thread count, and the same input
// error when M is not positive definite.
TEST(SparseEigenTest, ThreadCountDoesNotChangeTheModesOrTheErrors) {
  const int n = 12000;
  const SparseMatrix K = ChainStiffness(n, /*grounded=*/true);
  std::vector<Eigen::Triplet<double>> m;  // a consistent (tridiagonal) mass
  for (int i = 0; i < n; ++i) m.emplace_back(i, i, i + 1 < n ? 2.0 / 3.0 : 1.0 / 3.0);
  for (int i = 0; i + 1 < n; ++i) {
    m.emplace_back(i, i + 1, 1.0 / 6.0);
    m.emplace_back(i + 1, i, 1.0 / 6.0);
  }
  SparseMatrix M = FromTriplets(n, m);
  EigenOptions options;
  options.num_modes = 5;
  options.threads = 1;
  const Modes one = SolveModesSparse(K, M, options);
  options.threads = 2;
  const Modes two = SolveModesSparse(K, M, options);
  options.threads = 0;
  const Modes all = SolveModesSparse(K, M, options);
  EXPECT_EQ(one.eigenvalues, two.eigenvalues);
  EXPECT_EQ(one.shapes, two.shapes);
  EXPECT_EQ(one.eigenvalues, all.eigenvalues);
  EXPECT_EQ(one.shapes, all.shapes);
  // A fixed-free rod of n two-node elements (unit stiffness, consistent mass):
  // u_i = sin(i t) with t = (2j - 1) pi / (2n) satisfies the free end, and the
  // interior rows give lambda_j = 6 (1 - cos t) / (2 + cos t).
  for (int j = 0; j < 5; ++j) {
    const double t = (2.0 * (j + 1) - 1.0) * kPi / (2.0 * n);
    const double exact = 6.0 * (1.0 - std::cos(t)) / (2.0 + std::cos(t));
    EXPECT_NEAR(one.eigenvalues[j], exact, 1e-6 * exact) << j;
  }

  M.coeffRef(7000, 7001) = 1.0;  // |c| > 2/3: M indefinite
  M.coeffRef(7001, 7000) = 1.0;
  for (int threads : {1, 2}) {
    options.threads = threads;
    const std::string message =
        InputErrorMessage([&] { SolveModesSparse(K, M, options); });
    EXPECT_NE(message.find("mass matrix is not positive definite (its Cholesky "
                           "factorisation breaks down at DOF "),
              std::string::npos)
        << message;
  }
}

// Only the lower triangles are read: entries above the diagonal that disagree
// with them (here scaled by 3) change nothing, on either Lanczos process.
TEST(SparseEigenTest, OnlyTheLowerTrianglesAreRead) {
  SparseMatrix K, M;
  RandomPencil(20, 25, 20261129u, &K, &M);
  SparseMatrix k_skewed = K;
  SparseMatrix m_skewed = M;
  for (SparseMatrix* a : {&k_skewed, &m_skewed}) {
    for (Eigen::Index j = 0; j < a->outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(*a, j); it; ++it) {
        if (it.row() < j) it.valueRef() *= 3.0;
      }
    }
  }
  for (const bool inside : {false, true}) {
    EigenOptions options;
    options.num_modes = 6;
    if (inside)
      options.shift = 0.5 * (SolveModesSparse(K, M, options).eigenvalues[0] +
                             SolveModesSparse(K, M, options).eigenvalues[1]);
    const Modes expected = SolveModesSparse(K, M, options);
    const Modes skewed = SolveModesSparse(k_skewed, m_skewed, options);
    EXPECT_EQ(expected.eigenvalues, skewed.eigenvalues) << inside;
    EXPECT_EQ(expected.shapes, skewed.shapes) << inside;
  }
}

TEST(SparseEigenTest, ShiftInsideSpectrumUsesLdltAndReturnsModesAboveShift) {
  SparseMatrix K, M;
  RandomPencil(20, 25, 20240611u, &K, &M);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(
      (Eigen::MatrixXd(K)), (Eigen::MatrixXd(M)), Eigen::EigenvaluesOnly);
  EigenOptions options;
  options.num_modes = 6;
  // K - shift*M is indefinite: the Cholesky fails and LDLT takes over.
  options.shift = 0.5 * (dense.eigenvalues()[19] + dense.eigenvalues()[20]);
  const Modes modes = SolveModesSparse(K, M, options);
  ExpectMatchesDense(K, M, modes, 20, 6);
}

TEST(SparseEigenTest, FreeFreeChainWithNegativeShiftFindsRigidBodyMode) {
  const int n = 60;
  const int k = 5;
  const SparseMatrix K = ChainStiffness(n, /*grounded=*/false);
  const SparseMatrix M = Identity(n);
  EigenOptions options;
  options.num_modes = k;
  options.shift = -0.1;
  const Modes modes = SolveModesSparse(K, M, options);
  ExpectValidModes(K, M, modes, k);
  EXPECT_NEAR(modes.eigenvalues[0], 0.0, 1e-10);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(modes.shapes(i, 0), 1.0 / std::sqrt(n), 1e-10) << "i = " << i;
  }
  for (int j = 1; j < k; ++j) {
    const double s = std::sin(j * kPi / (2.0 * n));
    const double expected = 4.0 * s * s;
    EXPECT_NEAR(modes.eigenvalues[j], expected, 1e-10 * expected) << "j = " << j;
  }
}

TEST(SparseEigenTest, FreeFreeChainAtZeroShiftIsReportedAsSingular) {
  const int n = 60;
  EigenOptions options;
  options.num_modes = 3;
  const std::string message = InputErrorMessage([&] {
    SolveModesSparse(ChainStiffness(n, /*grounded=*/false), Identity(n), options);
  });
  EXPECT_NE(message.find("modal analysis: "), std::string::npos) << message;
  EXPECT_NE(message.find("singular"), std::string::npos) << message;
  EXPECT_NE(message.find("negative shift"), std::string::npos) << message;
}

TEST(SparseEigenTest, ShiftAtRoundedZeroEigenvalueIsReportedAsSingular) {
  // Free-free chains with inexact spring constants: K has a pivot of the order of
  // 1e-16, negative for the first (the Cholesky fails and LDLT takes over) and
  // positive for the second (the Cholesky succeeds).
  const int n = 60;
  for (int period : {7, 11}) {
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i + 1 < n; ++i) {
      const double s = 1.0 / (3 + i % period);
      t.emplace_back(i, i, s);
      t.emplace_back(i + 1, i + 1, s);
      t.emplace_back(i, i + 1, -s);
      t.emplace_back(i + 1, i, -s);
    }
    const SparseMatrix K = FromTriplets(n, t);
    EigenOptions options;
    options.num_modes = 3;
    const std::string message =
        InputErrorMessage([&] { SolveModesSparse(K, Identity(n), options); });
    EXPECT_NE(message.find("singular to working precision"), std::string::npos)
        << message;
    EXPECT_NE(message.find("negative shift"), std::string::npos) << message;
    // With a negative shift the same model solves, rigid-body mode first.
    options.shift = -0.01;
    const Modes modes = SolveModesSparse(K, Identity(n), options);
    ExpectValidModes(K, Identity(n), modes, 3);
    EXPECT_NEAR(modes.eigenvalues[0], 0.0, 1e-12);
  }
}

TEST(SparseEigenTest, TooFewEigenvaluesAboveShiftThrows) {
  const int n = 40;
  EigenOptions options;
  options.num_modes = 3;
  options.shift = 10.0;  // above the whole spectrum (< 4)
  const std::string message = InputErrorMessage([&] {
    SolveModesSparse(ChainStiffness(n, /*grounded=*/true), Identity(n), options);
  });
  EXPECT_NE(message.find("only 0 eigenvalues lie above the shift"), std::string::npos)
      << message;
}

TEST(SparseEigenTest, MassNotPositiveDefiniteThrows) {
  const int n = 50;
  const SparseMatrix K = ChainStiffness(n, /*grounded=*/true);
  EigenOptions options;
  options.num_modes = 4;
  for (double bad : {0.0, -1.0}) {
    SparseMatrix M = Identity(n);
    M.coeffRef(17, 17) = bad;
    const std::string message =
        InputErrorMessage([&] { SolveModesSparse(K, M, options); });
    EXPECT_NE(message.find("modal analysis: mass matrix is not positive definite"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("DOF 17"), std::string::npos) << message;
    EXPECT_NE(message.find("n = 50"), std::string::npos) << message;
  }
}

// A consistent (non-diagonal) M that is not positive definite: found by its
// factorisation on the analysis of K + M, with the DOF where it breaks down.
TEST(SparseEigenTest, NonDiagonalMassNotPositiveDefiniteThrows) {
  const int n = 50;
  const SparseMatrix K = ChainStiffness(n, /*grounded=*/true);
  std::vector<Eigen::Triplet<double>> m;
  for (int i = 0; i < n; ++i) m.emplace_back(i, i, 2.0 / 3.0);
  for (int i = 0; i + 1 < n; ++i) {
    const double c = i == 20 ? 1.0 : 1.0 / 6.0;  // |c| > 2/3: M[20:22, 20:22] indefinite
    m.emplace_back(i, i + 1, c);
    m.emplace_back(i + 1, i, c);
  }
  const SparseMatrix M = FromTriplets(n, m);
  EigenOptions options;
  options.num_modes = 4;
  for (double supernodal_switch : {0.0, 1e300}) {
    const std::string message =
        InputErrorMessage([&] { SolveModesSparse(K, M, options, supernodal_switch); });
    EXPECT_NE(message.find("modal analysis: mass matrix is not positive definite "
                           "(its Cholesky factorisation breaks down at DOF "),
              std::string::npos)
        << message;
  }
}

TEST(SparseEigenTest, NumModesOutOfRangeThrows) {
  const int n = 30;
  const SparseMatrix K = ChainStiffness(n, /*grounded=*/true);
  const SparseMatrix M = Identity(n);
  for (int k : {-1, 0, n, n + 5}) {
    EigenOptions options;
    options.num_modes = k;
    const std::string message =
        InputErrorMessage([&] { SolveModesSparse(K, M, options); });
    EXPECT_NE(message.find("num_modes = " + std::to_string(k) + " is out of range"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("n - 1 = 29"), std::string::npos) << message;
  }
  // k = n - 1 is the largest accepted.
  EigenOptions options;
  options.num_modes = n - 1;
  ExpectValidModes(K, M, SolveModesSparse(K, M, options), n - 1);
}

TEST(SparseEigenTest, SizeMismatchThrows) {
  EigenOptions options;
  options.num_modes = 2;
  const std::string message = InputErrorMessage(
      [&] { SolveModesSparse(ChainStiffness(10, true), Identity(9), options); });
  EXPECT_NE(message.find("stiffness is 10x10 and mass is 9x9"), std::string::npos)
      << message;
}

// Non-convergence is a numerical failure on valid input, not an input error:
// SolveModesSparse (and SolveModes) throw NumericalError, TrySolveModes returns
// it as the solution's status with the same message.
TEST(SparseEigenTest, NonConvergenceIsANumericalFailureWithIterationCount) {
  SparseMatrix K, M;
  RandomPencil(20, 25, 7u, &K, &M);
  EigenOptions options;
  options.num_modes = 12;
  options.max_iterations = 1;
  options.tolerance = 1e-15;
  options.method = EigenOptions::Method::kSparseShiftInvert;
  std::string message;
  try {
    SolveModesSparse(K, M, options);
  } catch (const NumericalError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("did not converge"), std::string::npos) << message;
  EXPECT_NE(message.find("restarts"), std::string::npos) << message;
  EXPECT_NE(message.find("k = 12, n = 500, shift = 0"), std::string::npos) << message;

  EXPECT_THROW(SolveModes(K, M, options), NumericalError);
  EigenSolution solution;
  EXPECT_NO_THROW(solution = TrySolveModes(K, M, options));
  EXPECT_FALSE(solution.ok());
  EXPECT_EQ(solution.failure, message);
  EXPECT_EQ(solution.modes.size(), 0);

  // The same pencil with the default iterations converges: a status of ok.
  options.max_iterations = EigenOptions().max_iterations;
  options.tolerance = EigenOptions().tolerance;
  solution = TrySolveModes(K, M, options);
  ASSERT_TRUE(solution.ok()) << solution.failure;
  ExpectValidModes(K, M, solution.modes, 12);
}

// Input errors stay input errors through TrySolveModes: it throws them.
TEST(SparseEigenTest, TrySolveModesThrowsInputErrors) {
  EigenOptions options;
  options.num_modes = 2;
  options.method = EigenOptions::Method::kSparseShiftInvert;
  EXPECT_THROW(TrySolveModes(ChainStiffness(10, true), Identity(9), options), InputError);
  SparseMatrix M = Identity(10);
  M.coeffRef(3, 3) = -1;
  EXPECT_THROW(TrySolveModes(ChainStiffness(10, true), M, options), InputError);
}

}  // namespace
}  // namespace internal
}  // namespace femup
