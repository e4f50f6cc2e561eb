// Private to femup_core: assembling element matrices into global sparse ones.
#pragma once

#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <vector>

#include "femup/core/fe/fe.h"
#include "femup/core/fe/frame3d.h"
#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"

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

// Adds an element's matrices (ke, me, N x N) to a rigid support where the
// element meets it: `dof[i]` is a model DOF (>= 0) or -1, and `restrained[i]`
// the index into support->directions of a restrained DOF (-1 otherwise).
template <int N>
void AddToRigidSupport(const Eigen::Matrix<double, N, N>& ke,
                       const Eigen::Matrix<double, N, N>& me,
                       const std::array<int, N>& dof,
                       const std::array<int, N>& restrained, RigidSupport* support) {
  const int r = static_cast<int>(support->directions.size());
  if (support->k_bb.rows() != r) {
    support->k_bb = Eigen::MatrixXd::Zero(r, r);
    support->m_bb = Eigen::MatrixXd::Zero(r, r);
    support->k_fb.resize(0, r);
    support->m_fb.resize(0, r);
  }
  for (int j = 0; j < N; ++j) {
    if (restrained[j] < 0) continue;
    const int b = restrained[j];
    for (int i = 0; i < N; ++i) {
      if (restrained[i] >= 0) {
        support->k_bb(restrained[i], b) += ke(i, j);
        support->m_bb(restrained[i], b) += me(i, j);
      } else if (dof[i] >= 0) {
        auto at = std::find(support->rows.begin(), support->rows.end(), dof[i]);
        const int row = static_cast<int>(at - support->rows.begin());
        if (at == support->rows.end()) {
          support->rows.push_back(dof[i]);
          support->k_fb.conservativeResize(row + 1, r);
          support->m_fb.conservativeResize(row + 1, r);
          support->k_fb.row(row).setZero();
          support->m_fb.row(row).setZero();
        }
        support->k_fb(row, b) += ke(i, j);
        support->m_fb(row, b) += me(i, j);
      }
    }
  }
}

}  // namespace femup::internal
