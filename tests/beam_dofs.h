// Test helpers shared by the beam tests: a DOF found by its label, the
// transverse monomial fields of a cantilever, and the bending eigenproblem on
// a chosen set of DOFs.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "femup/core/fe/structure.h"

namespace femup {
namespace fixtures {

// The index of the DOF labelled `label` in `s`, or -1.
inline int Dof(const Structure& s, const std::string& label) {
  for (std::size_t i = 0; i < s.dof_labels.size(); ++i) {
    if (s.dof_labels[i] == label) return static_cast<int>(i);
  }
  return -1;
}

// DOF vector of the transverse field ux(z) = z^k (rz = -dux/dz) on the nodes
// that have DOFs; all axial DOFs 0.
inline Eigen::VectorXd MonomialField(const Structure& s,
                                     const std::vector<double>& heights, int k) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(s.dof_labels.size());
  for (std::size_t node = 0; node < heights.size(); ++node) {
    const double z = heights[node];
    const int ux = Dof(s, "n" + std::to_string(node) + ":ux");
    const int rz = Dof(s, "n" + std::to_string(node) + ":rz");
    if (ux >= 0) u(ux) = std::pow(z, k);
    if (rz >= 0) u(rz) = k == 0 ? 0.0 : -k * std::pow(z, k - 1);
  }
  return u;
}

// Frequencies (Hz, ascending) and mode shapes (columns, over `keep`) of K and M
// restricted to the DOFs `keep`. Solved as M phi = mu K phi, mu = 1 / omega^2:
// the lowest frequencies come out as the largest mu, to full relative precision
// (K phi = lambda M phi would give them only to eps * lambda_max / lambda).
struct ReducedModes {
  Eigen::VectorXd hz;
  Eigen::MatrixXd shapes;
};

inline ReducedModes SolveReducedModes(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m,
                                      const std::vector<int>& keep) {
  const int n = static_cast<int>(keep.size());
  Eigen::MatrixXd kb(n, n), mb(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      kb(i, j) = k(keep[i], keep[j]);
      mb(i, j) = m(keep[i], keep[j]);
    }
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(mb, kb);
  EXPECT_EQ(eig.info(), Eigen::Success);
  const double pi = std::acos(-1.0);
  return {eig.eigenvalues().reverse().cwiseInverse().cwiseSqrt() / (2 * pi),
          eig.eigenvectors().rowwise().reverse()};
}

}  // namespace fixtures
}  // namespace femup
