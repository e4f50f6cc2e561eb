// The lowest eigenpairs of a small symmetric-definite pencil K x = lambda M x
// whose matrices are banded (a beam's or a chain's, DOFs numbered along the
// structure): LAPACK's dsbgvx for the eigenvalues, which works on the band
// only (O(n b^2) for the reduction instead of the dense O(n^3)), and inverse
// iteration with a banded LU (dgbtrf/dgbtrs) for the eigenvectors asked for.
// Where a study evaluates one small model thousands of times (the blind
// benchmark's Bayes oracle, benchmark_oracle.h), this is several times
// faster than the dense generalised solver.
#pragma once

#include <Eigen/Core>
#include <string>

namespace femup {

struct BandedEigenpairs {
  Eigen::VectorXd eigenvalues;  // the lowest `count`, ascending
  // n x count, M-normalised (x' M x = 1), sign fixed so that the entry of
  // largest magnitude is positive; empty unless vectors were asked for.
  Eigen::MatrixXd vectors;
};

// The bandwidth of a square matrix: the largest |i - j| with a non-zero entry.
int Bandwidth(const Eigen::MatrixXd& a);

// The lowest `count` eigenpairs of (K, M), K symmetric, M symmetric positive
// definite, both given as dense matrices (only their band is read; the band
// is the larger of their bandwidths). Returns false with *why when the sizes do
// not match, count is not in [1, n], M is not positive definite or LAPACK
// fails.
bool LowestBandedEigenpairs(const Eigen::MatrixXd& stiffness, const Eigen::MatrixXd& mass,
                            int count, bool vectors, BandedEigenpairs* out,
                            std::string* why);

}  // namespace femup
