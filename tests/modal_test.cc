// Modal analysis (core/include/femup/core/linalg/modal.h), checked against eigen
// residuals, the analytic spectrum of a fixed-free chain and hand-built MAC examples.
#include "femup/core/linalg/modal.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "paper_beam.h"
#include "solver_problems.h"

namespace femup {
namespace {

const double kPi = std::acos(-1.0);

SparseMatrix Sparse(const Eigen::MatrixXd& a) { return a.sparseView(); }

// n unit masses joined by unit springs, spring 1 to the ground.
void UnitChain(int n, SparseMatrix* k, SparseMatrix* m) {
  Eigen::MatrixXd kd = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    kd(i, i) += 1;  // spring i+1 below mass i+1
    if (i > 0) {
      kd(i - 1, i - 1) += 1;
      kd(i - 1, i) -= 1;
      kd(i, i - 1) -= 1;
    }
  }
  *k = Sparse(kd);
  *m = Sparse(Eigen::MatrixXd::Identity(n, n));
}

// A random SPD pencil with a non-diagonal mass (fixed seed).
void RandomPencil(int n, unsigned seed, SparseMatrix* k, SparseMatrix* m) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd a(n, n), b(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      a(i, j) = g(rng);
      b(i, j) = g(rng);
    }
  }
  *k = Sparse(a * a.transpose() + n * Eigen::MatrixXd::Identity(n, n));
  *m = Sparse(0.1 * b * b.transpose() + Eigen::MatrixXd::Identity(n, n));
}

void ExpectValidModes(const SparseMatrix& k, const SparseMatrix& m, const Modes& modes,
                      double residual_tol) {
  const Eigen::MatrixXd kd(k), md(m);
  for (int j = 0; j < modes.size(); ++j) {
    const Eigen::VectorXd phi = modes.shapes.col(j);
    const double lambda = modes.eigenvalues[j];
    const Eigen::VectorXd r = kd * phi - lambda * (md * phi);
    EXPECT_LE(r.norm(),
              residual_tol * (kd.norm() + std::abs(lambda) * md.norm()) * phi.norm())
        << "mode " << j + 1;
    if (j > 0) {
      EXPECT_GE(lambda, modes.eigenvalues[j - 1]) << "ascending";
    }
    Eigen::Index imax = 0;
    phi.cwiseAbs().maxCoeff(&imax);
    EXPECT_GT(phi[imax], 0.0) << "largest entry positive, mode " << j + 1;
  }
  const Eigen::MatrixXd gram = modes.shapes.transpose() * md * modes.shapes;
  EXPECT_LE((gram - Eigen::MatrixXd::Identity(modes.size(), modes.size()))
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
}

TEST(SolveModes, DenseRandomPencilResidualOrthonormalitySign) {
  SparseMatrix k, m;
  RandomPencil(12, 7, &k, &m);
  const Modes modes = SolveModes(k, m);
  ASSERT_EQ(modes.size(), 12);
  ASSERT_EQ(modes.shapes.rows(), 12);
  ExpectValidModes(k, m, modes, 1e-13);
  // The eigenvalues are those of M^-1/2 K M^-1/2, computed independently.
  const Eigen::MatrixXd kd(k), md(m);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> msqrt(md);
  const Eigen::MatrixXd w = msqrt.operatorInverseSqrt();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(w * kd * w);
  EXPECT_LE((modes.eigenvalues - es.eigenvalues()).cwiseAbs().maxCoeff(),
            1e-12 * es.eigenvalues().maxCoeff());
}

TEST(SolveModes, FixedFreeChainAnalyticSpectrum) {
  const int n = 10;
  SparseMatrix k, m;
  UnitChain(n, &k, &m);
  const Modes modes = SolveModes(k, m);
  ExpectValidModes(k, m, modes, 1e-14);
  for (int j = 1; j <= n; ++j) {
    const double theta = (2 * j - 1) * kPi / (2 * n + 1);
    const double lambda = 4 * std::pow(std::sin(theta / 2), 2);
    EXPECT_NEAR(modes.eigenvalues[j - 1], lambda, 1e-13) << "mode " << j;
    // Shape x_k = sin(k theta), k = 1..n.
    Eigen::VectorXd shape(n);
    for (int i = 0; i < n; ++i) shape[i] = std::sin((i + 1) * theta);
    EXPECT_NEAR(Mac(modes.shapes.col(j - 1), shape), 1.0, 1e-12) << "mode " << j;
  }
  // FrequenciesHz = sqrt(lambda) / 2 pi.
  const Eigen::VectorXd f = modes.FrequenciesHz();
  for (int j = 0; j < n; ++j) {
    EXPECT_NEAR(f[j], std::sqrt(modes.eigenvalues[j]) / (2 * kPi), 1e-15);
  }
}

TEST(SolveModes, SubsetAndShift) {
  const int n = 10;
  SparseMatrix k, m;
  UnitChain(n, &k, &m);
  EigenOptions options;
  options.num_modes = 3;
  const Modes first = SolveModes(k, m, options);
  ASSERT_EQ(first.size(), 3);
  ASSERT_EQ(first.shapes.cols(), 3);
  auto lambda = [n](int j) {
    return 4 * std::pow(std::sin((2 * j - 1) * kPi / (2 * (2 * n + 1))), 2);
  };
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(first.eigenvalues[j], lambda(j + 1), 1e-13);
  // Dense with a shift between lambda_3 and lambda_4: modes 4, 5, ...
  options.method = EigenOptions::Method::kDense;
  options.shift = 0.5 * (lambda(3) + lambda(4));
  const Modes shifted = SolveModes(k, m, options);
  ASSERT_EQ(shifted.size(), 3);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(shifted.eigenvalues[j], lambda(j + 4), 1e-13);
  ExpectValidModes(k, m, shifted, 1e-14);
}

std::string WhatOfSolve(const SparseMatrix& k, const SparseMatrix& m,
                        const EigenOptions& options = {}) {
  try {
    SolveModes(k, m, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(SolveModes, BadInputThrows) {
  SparseMatrix k, m;
  UnitChain(4, &k, &m);
  const SparseMatrix indefinite =
      Sparse(Eigen::Vector4d(1, -1, 1, 1).asDiagonal().toDenseMatrix());
  const SparseMatrix singular =
      Sparse(Eigen::Vector4d(1, 0, 1, 1).asDiagonal().toDenseMatrix());
  EXPECT_NE(WhatOfSolve(k, indefinite).find("not positive definite"), std::string::npos)
      << WhatOfSolve(k, indefinite);
  EXPECT_NE(WhatOfSolve(k, singular).find("not positive definite"), std::string::npos)
      << WhatOfSolve(k, singular);

  EigenOptions options;
  options.num_modes = 5;
  EXPECT_NE(WhatOfSolve(k, m, options).find("5 modes"), std::string::npos)
      << WhatOfSolve(k, m, options);
  options.num_modes = 0;
  EXPECT_THROW(SolveModes(k, m, options), InputError);
  options.num_modes = -2;
  EXPECT_THROW(SolveModes(k, m, options), InputError);

  SparseMatrix m3 = Sparse(Eigen::MatrixXd::Identity(3, 3));
  EXPECT_THROW(SolveModes(k, m3), InputError);
  EXPECT_THROW(SolveModes(SparseMatrix(0, 0), SparseMatrix(0, 0)), InputError);

  options = EigenOptions();
  options.method = EigenOptions::Method::kSparseShiftInvert;  // needs num_modes
  EXPECT_THROW(SolveModes(k, m, options), InputError);
}

TEST(EigenOptions, Validate) {
  EXPECT_EQ(EigenOptions().Validate().ToString(), "");
  EigenOptions o;
  o.num_modes = 0;
  EXPECT_NE(o.Validate().ToString(), "");
  o = EigenOptions();
  o.dense_limit = 0;
  EXPECT_NE(o.Validate().ToString(), "");
  o = EigenOptions();
  o.shift = std::nan("");
  EXPECT_NE(o.Validate().ToString(), "");
  o = EigenOptions();
  o.tolerance = 0;
  EXPECT_NE(o.Validate().ToString(), "");
  o = EigenOptions();
  o.max_iterations = 0;
  EXPECT_NE(o.Validate().ToString(), "");
  o = EigenOptions();
  o.threads = -1;
  EXPECT_NE(o.Validate().ToString().find("threads must be >= 0"), std::string::npos);
  o.threads = 3;
  EXPECT_EQ(o.Validate().ToString(), "");
}

TEST(Modes, FrequenciesHzOfHandValues) {
  Modes modes;
  modes.eigenvalues.resize(3);
  modes.eigenvalues << std::pow(2 * kPi * 3.0, 2), 0.0, -5.0;
  const Eigen::VectorXd f = modes.FrequenciesHz();
  EXPECT_NEAR(f[0], 3.0, 1e-14);
  EXPECT_EQ(f[1], 0.0);
  EXPECT_EQ(f[2], 0.0);
}

TEST(MassNormalise, ScalesToUnitModalMass) {
  SparseMatrix k, m;
  RandomPencil(6, 11, &k, &m);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd shapes(6, 3);
  for (int i = 0; i < shapes.size(); ++i) shapes.data()[i] = g(rng);
  const Eigen::MatrixXd original = shapes;
  MassNormalise(m, &shapes);
  const Eigen::MatrixXd md(m);
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(shapes.col(j).dot(md * shapes.col(j)), 1.0, 1e-14);
    // Same direction, positive factor.
    const double c = shapes.col(j).dot(original.col(j)) / original.col(j).squaredNorm();
    EXPECT_GT(c, 0.0);
    EXPECT_LE((shapes.col(j) - c * original.col(j)).norm(), 1e-14 * shapes.col(j).norm());
  }
  shapes.col(1).setZero();
  EXPECT_THROW(MassNormalise(m, &shapes), InputError);
}

// ---------------------------------------------------------------------------
// MAC and pairing.

TEST(Mac, Properties) {
  const Eigen::Vector4d a(1, -2, 0.5, 3);
  EXPECT_NEAR(Mac(a, a), 1.0, 1e-15);
  EXPECT_NEAR(Mac(a, -7.5 * a), 1.0, 1e-15);
  EXPECT_NEAR(Mac(a, 1e-9 * a), 1.0, 1e-15);
  const Eigen::Vector4d orthogonal(2, 1, 0, 0);  // a . o = 0
  EXPECT_EQ(Mac(a, orthogonal), 0.0);
  EXPECT_EQ(Mac(a, Eigen::Vector4d::Zero()), 0.0);
  EXPECT_EQ(Mac(Eigen::Vector4d::Zero(), Eigen::Vector4d::Zero()), 0.0);
  // Hand value: (a.b)^2 / (|a|^2 |b|^2) for b = (1, 1, 1, 1): 2.5^2 / (14.25 * 4).
  EXPECT_NEAR(Mac(a, Eigen::Vector4d::Ones()), 6.25 / 57.0, 1e-15);
  EXPECT_NEAR(Mac(Eigen::Vector4d::Ones(), a), 6.25 / 57.0, 1e-15);
  EXPECT_THROW(Mac(a, Eigen::Vector3d(1, 2, 3)), InputError);
}

Eigen::MatrixXd RandomOrthonormal(int rows, int cols, unsigned seed) {
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(fixtures::RandomGaussian(rows, cols, seed));
  return qr.householderQ() * Eigen::MatrixXd::Identity(rows, cols);
}

TEST(Mac, MatrixOfOrthonormalSetsIsIdentityAndMatchesPairwise) {
  const Eigen::MatrixXd q = RandomOrthonormal(8, 5, 5);
  const Eigen::MatrixXd mac = MacMatrix(q, q);
  EXPECT_LE((mac - Eigen::MatrixXd::Identity(5, 5)).cwiseAbs().maxCoeff(), 1e-14);
  const Eigen::MatrixXd other = RandomOrthonormal(8, 3, 6);
  const Eigen::MatrixXd cross = MacMatrix(q, other);
  ASSERT_EQ(cross.rows(), 5);
  ASSERT_EQ(cross.cols(), 3);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double ab = q.col(i).dot(other.col(j));
      EXPECT_NEAR(cross(i, j), ab * ab, 1e-14);  // unit columns
    }
  }
}

TEST(PairModesByMac, RecoversPermutationWithNoise) {
  const int n = 12, m = 6;
  const Eigen::MatrixXd reference = RandomOrthonormal(n, m, 21);
  const std::vector<int> perm = {3, 0, 5, 1, 4, 2};  // candidate k = reference perm[k]
  std::mt19937_64 rng(99);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd candidate(n, m);
  for (int k = 0; k < m; ++k) {
    Eigen::VectorXd noise(n);
    for (int i = 0; i < n; ++i) noise[i] = 0.05 * g(rng);
    const double scale = (k % 2 ? -1.0 : 1.0) * (1.0 + k);
    candidate.col(k) = scale * (reference.col(perm[k]) + noise);
  }
  const std::vector<ModePair> pairs = PairModesByMac(reference, candidate);
  ASSERT_EQ(pairs.size(), static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    const ModePair& p = pairs[perm[k]];
    EXPECT_EQ(p.reference, perm[k]);
    EXPECT_EQ(p.candidate, k);
    EXPECT_NEAR(p.mac, Mac(reference.col(perm[k]), candidate.col(k)), 1e-15);
    EXPECT_GT(p.mac, 0.9);
  }
}

TEST(PairModesByMac, WeakPairsLeftUnpaired) {
  const Eigen::MatrixXd q = RandomOrthonormal(8, 4, 31);
  const Eigen::MatrixXd reference = q.leftCols(3);
  Eigen::MatrixXd candidate(8, 3);
  candidate.col(0) = q.col(1);
  candidate.col(1) = q.col(0) + 0.01 * q.col(2);
  candidate.col(2) = q.col(3);  // orthogonal to every reference mode
  const std::vector<ModePair> strict = PairModesByMac(reference, candidate, 0.9);
  ASSERT_EQ(strict.size(), 3u);
  EXPECT_EQ(strict[0].candidate, 1);
  EXPECT_EQ(strict[1].candidate, 0);
  EXPECT_EQ(strict[2].reference, 2);
  EXPECT_EQ(strict[2].candidate, -1);

  // More reference modes than candidates: the extra one is unpaired.
  const std::vector<ModePair> fewer = PairModesByMac(q, candidate.leftCols(2), 0.5);
  ASSERT_EQ(fewer.size(), 4u);
  EXPECT_EQ(fewer[0].candidate, 1);
  EXPECT_EQ(fewer[1].candidate, 0);
  EXPECT_EQ(fewer[2].candidate, -1);
  EXPECT_EQ(fewer[3].candidate, -1);
}

// A portal frame's two vertical beam modes read by one vertical sensor (and
// three horizontal ones where they move little): both MACs are 0.998 against
// the measured vertical mode, the higher one's by the noise. Their shape
// misfits are within the tie, and the frequency pairs it with the mode 1.6 %
// away, not the one 13 % away; PairModesByMac takes the noise's pick.
TEST(PairModesByMacAndMisfit, TheFrequencyPairsModesTheSensorsSeeAlike) {
  Eigen::MatrixXd reference(4, 2), candidate(4, 3);
  reference.col(0) << 0.60, 0.63, 1.03, -0.01;  // a sway mode
  reference.col(1) << 0.025, 0.031, 0.010, -0.998;
  candidate.col(0) << 0.58, 0.58, 1.0, 0.0;
  candidate.col(1) << 0.0022, -0.0022, -0.0013, -1.0;  // 5.01 Hz
  candidate.col(2) << 0.0002, -0.0002, -0.0008, 1.0;   // 5.58 Hz
  const Eigen::MatrixXd mac = MacMatrix(reference, candidate);
  ASSERT_GT(mac(1, 2), mac(1, 1));  // the noise prefers the wrong one
  ASSERT_EQ(PairModesByMac(reference, candidate)[1].candidate, 2);
  // Misfits in noise units squared: shapes at 2 % of the peak, frequencies
  // (eigenvalues) at 0.4 %; the measured vertical mode at 4.93 Hz.
  Eigen::MatrixXd shape(2, 3), frequency(2, 3);
  for (int j = 0; j < 2; ++j) {
    for (int k = 0; k < 3; ++k) shape(j, k) = (1 - mac(j, k)) * 2500.0;
  }
  const double hz[] = {0.765, 5.006, 5.581}, measured[] = {0.759, 4.926};
  for (int j = 0; j < 2; ++j) {
    for (int k = 0; k < 3; ++k) {
      const double r = (hz[k] * hz[k] / (measured[j] * measured[j]) - 1) / 0.004;
      frequency(j, k) = r * r;
    }
  }
  const std::vector<ModePair> pairs =
      PairModesByMacAndMisfit(mac, shape, frequency, 0.0, 9.0);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].candidate, 0);
  EXPECT_EQ(pairs[1].candidate, 1);
  EXPECT_DOUBLE_EQ(pairs[1].mac, mac(1, 1));
  // No tie: the MAC decides alone, as PairModesByMac.
  const std::vector<ModePair> by_mac =
      PairModesByMacAndMisfit(mac, shape, frequency, 0.0, 0.0);
  EXPECT_EQ(by_mac[1].candidate, 2);
  // Shapes the sensors tell apart are not overruled by the frequency: a
  // candidate whose misfit is beyond the tie is never taken.
  Eigen::MatrixXd far = shape;
  far(1, 1) = shape(1, 2) + 10.0;
  EXPECT_EQ(PairModesByMacAndMisfit(mac, far, frequency, 0.0, 9.0)[1].candidate, 2);
  // Below min_mac: unpaired, whatever the misfits.
  EXPECT_EQ(PairModesByMacAndMisfit(mac, shape, frequency, 0.999, 9.0)[1].candidate, -1);
  EXPECT_THROW(PairModesByMacAndMisfit(mac, shape.leftCols(2), frequency, 0.0, 9.0),
               InputError);
  EXPECT_THROW(PairModesByMacAndMisfit(mac, shape, frequency, 0.0, -1.0), InputError);
}

// Every strictly increasing choice of m candidates out of c, by recursion.
void IncreasingChoices(int m, int c, int from, std::vector<int>* chosen,
                       const std::function<void(const std::vector<int>&)>& visit) {
  if (static_cast<int>(chosen->size()) == m) {
    visit(*chosen);
    return;
  }
  for (int j = from; j < c; ++j) {
    chosen->push_back(j);
    IncreasingChoices(m, c, j + 1, chosen, visit);
    chosen->pop_back();
  }
}

TEST(LastOfRepeated, GroupsEigenvaluesWithinTheTolerance) {
  Modes m;
  m.eigenvalues =
      (Eigen::VectorXd(6) << 1, 2, 2 * (1 + 1e-9), 2 * (1 + 2e-9), 3, 3).finished();
  EXPECT_EQ(LastOfRepeated(m, 0), 0);
  EXPECT_EQ(LastOfRepeated(m, 1), 3);
  EXPECT_EQ(LastOfRepeated(m, 4), 5);
  EXPECT_EQ(LastOfRepeated(m, 1, 1e-10), 1);
}

// Five orthonormal modes (M = I) with eigenvalues 1, 2, 2, 3, 5, 5: the pair
// at 2 is turned to a reference holding it in another rotation, exactly; the
// others stay as they are, the pair at 5 too (it holds the last mode and may
// extend beyond it). The shapes stay orthonormal.
TEST(AlignRepeatedModes, TurnsEachPairToTheReferenceItReproduces) {
  std::mt19937 rng(20261201);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd random(8, 6);
  for (Eigen::Index i = 0; i < random.size(); ++i) random(i) = normal(rng);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(random).householderQ() *
                            Eigen::MatrixXd::Identity(8, 6);
  Modes modes;
  modes.eigenvalues = (Eigen::VectorXd(6) << 1, 2, 2, 3, 5, 5).finished();
  modes.shapes = q;
  const double angle = 0.7;
  Eigen::MatrixXd reference(8, 3);  // mode 1, the pair turned, mode 4
  reference.col(0) = q.col(0);
  reference.col(1) = -std::sin(angle) * q.col(1) + std::cos(angle) * q.col(2);
  reference.col(2) = q.col(3);
  // Before: the pair's MACs with the turned reference are cos^2 and sin^2.
  EXPECT_NEAR(Mac(reference.col(1), q.col(1)), std::pow(std::sin(angle), 2), 1e-12);
  Modes aligned = modes;
  AlignRepeatedModes(reference, aligned.shapes, &aligned);
  EXPECT_NEAR(Mac(reference.col(1), aligned.shapes.col(1)), 1.0, 1e-12);
  EXPECT_NEAR(aligned.shapes.col(1).dot(reference.col(1)), 1.0, 1e-12);
  for (int k : {0, 3, 4, 5}) EXPECT_EQ(aligned.shapes.col(k), q.col(k)) << k;
  EXPECT_LT(
      (aligned.shapes.transpose() * aligned.shapes - Eigen::MatrixXd::Identity(6, 6))
          .cwiseAbs()
          .maxCoeff(),
      1e-12);
  // The pair's span is kept.
  const Eigen::MatrixXd pair = q.middleCols(1, 2);
  const Eigen::MatrixXd turned = aligned.shapes.middleCols(1, 2);
  EXPECT_LT((pair * (pair.transpose() * turned) - turned).cwiseAbs().maxCoeff(), 1e-12);

  // Seen at 5 of the 8 rows, with both of the pair in the reference, in
  // another rotation with a reflection: each is matched exactly.
  const std::vector<int> rows = {0, 2, 3, 5, 7};
  Eigen::MatrixXd both(8, 2);
  both.col(0) = std::cos(2.0) * q.col(1) + std::sin(2.0) * q.col(2);
  both.col(1) = std::sin(2.0) * q.col(1) - std::cos(2.0) * q.col(2);
  aligned = modes;
  AlignRepeatedModes(both(rows, Eigen::all), modes.shapes(rows, Eigen::all), &aligned);
  // (in either order: both are reproduced alike)
  for (int r = 0; r < 2; ++r) {
    EXPECT_NEAR(std::max(Mac(both.col(r), aligned.shapes.col(1)),
                         Mac(both.col(r), aligned.shapes.col(2))),
                1.0, 1e-12)
        << r;
  }

  // A reference another mode reproduces better is not taken by the pair.
  aligned = modes;
  AlignRepeatedModes(q.col(3) + 0.1 * q.col(1), modes.shapes, &aligned);
  EXPECT_EQ(aligned.shapes, modes.shapes);

  testing::ExpectInputError(
      [&] { AlignRepeatedModes(reference, modes.shapes.topRows(5), &aligned); },
      {"seen", "8 x 6"});
}

TEST(PairModesInOrder, MatchesExhaustiveSearchOnRandomShapes) {
  std::mt19937_64 rng(20261125);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 10, m = 4, c = 7;
    Eigen::MatrixXd reference(n, m), candidate(n, c);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) reference(i, j) = g(rng);
      for (int j = 0; j < c; ++j) candidate(i, j) = g(rng);
    }
    double best = -1;
    std::vector<int> chosen;
    IncreasingChoices(m, c, 0, &chosen, [&](const std::vector<int>& pick) {
      double sum = 0;
      for (int i = 0; i < m; ++i) sum += Mac(reference.col(i), candidate.col(pick[i]));
      best = std::max(best, sum);
    });
    const std::vector<ModePair> pairs = PairModesInOrder(reference, candidate);
    ASSERT_EQ(pairs.size(), static_cast<std::size_t>(m));
    double sum = 0;
    for (int i = 0; i < m; ++i) {
      EXPECT_EQ(pairs[i].reference, i);
      ASSERT_GE(pairs[i].candidate, 0);
      if (i > 0) {
        EXPECT_GT(pairs[i].candidate, pairs[i - 1].candidate);
      }
      EXPECT_NEAR(pairs[i].mac, Mac(reference.col(i), candidate.col(pairs[i].candidate)),
                  1e-15);
      sum += pairs[i].mac;
    }
    EXPECT_NEAR(sum, best, 1e-12) << "trial " << trial;
  }
}

TEST(PairModesInOrder, KeepsTheOrderWhereTheLargestMacFirstCrosses) {
  // Reference 1 is most like candidate 0 but a little like candidate 1;
  // reference 0 is most like candidate 1. Largest-first crosses the pairs.
  const Eigen::MatrixXd q = RandomOrthonormal(6, 3, 41);
  Eigen::MatrixXd reference(6, 2), candidate(6, 2);
  candidate = q.leftCols(2);
  reference.col(0) = 0.6 * q.col(0) + 0.8 * q.col(1);
  reference.col(1) = 0.95 * q.col(0) + 0.31 * q.col(1);
  const std::vector<ModePair> greedy = PairModesByMac(reference, candidate);
  ASSERT_EQ(greedy[1].candidate, 0);
  ASSERT_EQ(greedy[0].candidate, 1);
  const std::vector<ModePair> ordered = PairModesInOrder(reference, candidate);
  EXPECT_EQ(ordered[0].candidate, 0);
  EXPECT_EQ(ordered[1].candidate, 1);
  EXPECT_NEAR(ordered[0].mac, 0.36, 1e-12);
  EXPECT_NEAR(ordered[1].mac, Mac(reference.col(1), q.col(1)), 1e-12);
}

TEST(PairModesInOrder, PairsAsManyAsTheCandidatesAllow) {
  const Eigen::MatrixXd q = RandomOrthonormal(8, 4, 31);
  // Three references, two candidates: two pairs, the order kept.
  Eigen::MatrixXd candidate(8, 2);
  candidate.col(0) = q.col(1);
  candidate.col(1) = q.col(2);
  const std::vector<ModePair> pairs = PairModesInOrder(q.leftCols(3), candidate);
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0].candidate, -1);
  EXPECT_EQ(pairs[1].candidate, 0);
  EXPECT_EQ(pairs[2].candidate, 1);
  EXPECT_NEAR(pairs[1].mac, 1.0, 1e-12);
  // No candidates, no references.
  EXPECT_EQ(PairModesInOrder(q.leftCols(2), Eigen::MatrixXd(8, 0))[1].candidate, -1);
  EXPECT_TRUE(PairModesInOrder(Eigen::MatrixXd(8, 0), candidate).empty());
}

// ---------------------------------------------------------------------------
// Sparse shift-invert path against the dense solver.

TEST(SolveModes, SparseShiftAndAutoOnLongChainMatchAnalytic) {
  const int n = 200;
  SparseMatrix k, m;
  UnitChain(n, &k, &m);
  auto lambda = [n](int j) {
    return 4 * std::pow(std::sin((2 * j - 1) * kPi / (2 * (2 * n + 1))), 2);
  };
  EigenOptions options;
  options.num_modes = 4;
  options.dense_limit = 100;  // kAuto takes the sparse path for n = 200
  for (EigenOptions::Method method :
       {EigenOptions::Method::kSparseShiftInvert, EigenOptions::Method::kAuto}) {
    options.method = method;
    options.shift = 0.0;
    const Modes lowest = SolveModes(k, m, options);
    ASSERT_EQ(lowest.size(), 4);
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(lowest.eigenvalues[j], lambda(j + 1), 1e-9 * lambda(j + 1)) << j;
    }
    ExpectValidModes(k, m, lowest, 1e-12);
    // Shift between lambda_10 and lambda_11: modes 11..14.
    options.shift = 0.5 * (lambda(10) + lambda(11));
    const Modes shifted = SolveModes(k, m, options);
    ASSERT_EQ(shifted.size(), 4);
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(shifted.eigenvalues[j], lambda(j + 11), 1e-9 * lambda(j + 11)) << j;
    }
    ExpectValidModes(k, m, shifted, 1e-12);
  }
  options.method = EigenOptions::Method::kSparseShiftInvert;
  options.shift = 0.0;
  options.num_modes = n;  // the sparse solver needs k < n
  EXPECT_THROW(SolveModes(k, m, options), InputError);
}

// The diagnosis's scale: a 2 m steel flat bar of 20 elements (60 DOFs; the
// bundled air-and-water example's model), lambda_max / lambda_1 ~ 8e7. The
// dense path's eigenvalues are its vectors' Rayleigh quotients (modal.cc):
// each of the 8 lowest within 2e-12 of a long-double solution of the same
// pencil (measured: 5.5e-13 on mode 1, below 1e-13 from mode 2 on, with
// OpenBLAS's SkylakeX kernels; 5.7e-12 on mode 1 with its Haswell kernels,
// which it picks on an AMD EPYC: the bound is 1e-11, against ~1e-7 of
// lambda_1 for Eigen's full decomposition before).
TEST(SolveModes, DenseEigenvaluesOfAStiffBeamAreRayleighQuotients) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(2.0, 20));
  spec.section = {210e9, 9.0e-4, 1.6875e-8, 7850};
  const Structure s = BuildCantilever(spec);
  ASSERT_EQ(s.stiffness.rows(), 60);
  EigenOptions options;
  options.method = EigenOptions::Method::kDense;
  options.num_modes = 8;
  const Modes dense = SolveModes(s.stiffness, s.mass, options);
  using MatrixLd = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  const Eigen::MatrixXd kd(s.stiffness), md(s.mass);
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixLd> reference(
      kd.cast<long double>(), md.cast<long double>(), Eigen::EigenvaluesOnly);
  const long double spread = reference.eigenvalues()[59] / reference.eigenvalues()[0];
  EXPECT_GT(spread, 1e7L);
  for (int j = 0; j < 8; ++j) {
    const double ref = static_cast<double>(reference.eigenvalues()[j]);
    EXPECT_NEAR(dense.eigenvalues[j], ref, 1e-11 * ref) << "mode " << j + 1;
  }
}

TEST(SolveModes, SparseMatchesDenseOn300DofCantilever) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(1.9, 100));
  const Structure s = BuildCantilever(spec);
  ASSERT_EQ(s.stiffness.rows(), 300);
  EigenOptions dense_options;
  dense_options.method = EigenOptions::Method::kDense;
  const Modes dense = SolveModes(s.stiffness, s.mass, dense_options);
  EigenOptions sparse_options;
  sparse_options.method = EigenOptions::Method::kSparseShiftInvert;
  sparse_options.num_modes = 6;
  const Modes sparse = SolveModes(s.stiffness, s.mass, sparse_options);
  ASSERT_EQ(sparse.size(), 6);
  ASSERT_EQ(sparse.shapes.rows(), 300);

  // Reference eigenvalues in long double (64-bit mantissa). This pencil spans
  // lambda_max / lambda_1 ~ 1e8-1e9 (axial and rotational DOFs of 19 mm
  // elements), so a double-precision dense solve's eigenvalues are only
  // accurate to about eps * lambda_max / lambda_1 ~ 5e-8 on lambda_1; the
  // dense path returns its vectors' Rayleigh quotients instead (measured
  // 3.8e-10 on mode 1's frequency), checked at 1e-9, and the sparse
  // shift-invert path (which resolves the low end) at 1e-8.
  using MatrixLd = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  const Eigen::MatrixXd kd(s.stiffness), md(s.mass);
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixLd> reference(
      kd.cast<long double>(), md.cast<long double>(), Eigen::EigenvaluesOnly);
  const Eigen::VectorXd fd = dense.FrequenciesHz(), fs = sparse.FrequenciesHz();
  for (int j = 0; j < 6; ++j) {
    const double f_ref =
        static_cast<double>(std::sqrt(reference.eigenvalues()[j]) / (2 * kPi));
    EXPECT_NEAR(fs[j], f_ref, 1e-8 * f_ref) << "sparse, mode " << j + 1;
    EXPECT_NEAR(fd[j], f_ref, 1e-9 * f_ref) << "dense, mode " << j + 1;
    EXPECT_NEAR(fs[j], fd[j], 1e-8 * fd[j]) << "sparse vs dense, mode " << j + 1;
    EXPECT_GT(Mac(sparse.shapes.col(j), dense.shapes.col(j)), 1 - 1e-8)
        << "mode " << j + 1;
  }
  // M-orthonormal, sign convention, backward error of each pair.
  const Eigen::MatrixXd gram = sparse.shapes.transpose() * md * sparse.shapes;
  EXPECT_LE((gram - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(), 1e-10);
  for (int j = 0; j < 6; ++j) {
    const Eigen::VectorXd phi = sparse.shapes.col(j);
    Eigen::Index imax = 0;
    phi.cwiseAbs().maxCoeff(&imax);
    EXPECT_GT(phi[imax], 0.0);
    EXPECT_GT(phi.dot(dense.shapes.col(j)), 0.0) << "same sign as dense, mode " << j + 1;
    const Eigen::VectorXd r = kd * phi - sparse.eigenvalues[j] * (md * phi);
    EXPECT_LE(r.norm(), 1e-14 * kd.norm() * phi.norm()) << "mode " << j + 1;
  }
}

}  // namespace
}  // namespace femup
