// Private to femup_core: assembling element matrices into global sparse ones.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "femup/core/fe/fe.h"
#include "femup/core/fe/frame3d.h"
#include "femup/core/fe/model.h"

namespace femup::internal {

using Triplets = std::vector<Eigen::Triplet<double>>;

// n x n, duplicates summed, compressed.
inline SparseMatrix FromTriplets(int n, const Triplets& t) {
  SparseMatrix m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

// Scatters a 6x6 element matrix into global free DOFs; dof[i] < 0 is a fixed DOF.
inline void Scatter(const Matrix6& ke, const std::array<int, 6>& dof, Triplets* out) {
  for (int i = 0; i < 6; ++i) {
    if (dof[i] < 0) continue;
    for (int j = 0; j < 6; ++j) {
      if (dof[j] < 0 || ke(i, j) == 0.0) continue;
      out->emplace_back(dof[i], dof[j], ke(i, j));
    }
  }
}

// The same for a 12x12 (3D frame) element matrix.
inline void Scatter(const Matrix12& ke, const std::array<int, 12>& dof, Triplets* out) {
  for (int i = 0; i < 12; ++i) {
    if (dof[i] < 0) continue;
    for (int j = 0; j < 12; ++j) {
      if (dof[j] < 0 || ke(i, j) == 0.0) continue;
      out->emplace_back(dof[i], dof[j], ke(i, j));
    }
  }
}

}  // namespace femup::internal
