// Private: CHOLMOD's LL' factorisation as the sparse eigensolver uses it
// (sparse_eigen.cc): quiet on failure, with the DOF where it broke down, its
// pivots, triangular solves on kept work space, and a symbolic analysis that
// another factorisation can take over.
#pragma once

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cstddef>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/fe/model.h"
#include "linalg/group_ordering.h"

namespace femup {
namespace internal {

// CHOLMOD LL' that stays quiet on failure (the caller reports), says where the
// factorisation broke down and exposes its pivots. Simplicial or supernodal is
// CHOLMOD's choice from the analysed fill (its supernodal_switch).
class CholmodLlt : public Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> {
 public:
  explicit CholmodLlt(double supernodal_switch) {
    setMode(Eigen::CholmodSimplicialLLt);  // LL' (a non-positive pivot fails), not LDL'
    cholmod().supernodal = CHOLMOD_AUTO;
    cholmod().supernodal_switch = supernodal_switch;
    cholmod().print = 0;
  }

  CholmodLlt(const CholmodLlt&) = delete;
  CholmodLlt& operator=(const CholmodLlt&) = delete;
  ~CholmodLlt() {
    cholmod_free_dense(&x_, &cholmod());
    cholmod_free_dense(&y_, &cholmod());
    cholmod_free_dense(&e_, &cholmod());
  }

  // y = L^{-1} x (sys = CHOLMOD_L) or L^{-T} x (CHOLMOD_Lt), in the permuted
  // numbering; x and y hold n entries and may not overlap. The result and
  // CHOLMOD's work space are kept between calls (cholmod_solve2), so the
  // Lanczos steps allocate nothing. After a successful LL' factorize().
  void SolveTriangular(int sys, const double* x, double* y) {
    const cholmod_factor* factor = m_cholmodFactor;
    cholmod_dense b{};
    b.nrow = factor->n;
    b.ncol = 1;
    b.nzmax = factor->n;
    b.d = factor->n;
    b.x = const_cast<double*>(x);  // read only: B is an input of cholmod_solve2
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(sys, m_cholmodFactor, &b, nullptr, &x_, nullptr, &y_, &e_,
                        &cholmod())) {
      throw NumericalError("modal analysis",
                           "CHOLMOD's triangular solve failed (status " +
                               std::to_string(cholmod().status) + ")");
    }
    std::copy_n(static_cast<const double*>(x_->x), factor->n, y);
  }

  // The symbolic analysis of `a` (its lower triangle) on a fill-reducing
  // permutation from the graph of `groups` (group_ordering.h: METIS on the
  // nodes rather than the DOFs); CHOLMOD's own ordering when `groups` is empty
  // or METIS fails. Eigen's analyzePattern() with cholmod_analyze_p.
  void AnalyzePatternByGroups(const SparseMatrix& a, const std::vector<int>& groups) {
    const std::vector<int> perm =
        groups.empty() ? std::vector<int>{} : GroupOrdering(a, groups, &cholmod());
    if (perm.empty()) {
      AnalyzePatternLocked(a);
      return;
    }
    if (m_cholmodFactor != nullptr) cholmod_free_factor(&m_cholmodFactor, &cholmod());
    cholmod_sparse view = Eigen::viewAsCholmod(a.selfadjointView<Eigen::Lower>());
    const int nmethods = cholmod().nmethods;
    const int ordering = cholmod().method[0].ordering;
    cholmod().nmethods = 1;
    cholmod().method[0].ordering = CHOLMOD_GIVEN;
    m_cholmodFactor =
        cholmod_analyze_p(&view, const_cast<int*>(perm.data()), nullptr, 0, &cholmod());
    cholmod().nmethods = nmethods;
    cholmod().method[0].ordering = ordering;
    if (m_cholmodFactor == nullptr) {
      AnalyzePatternLocked(a);
      return;
    }
    m_isInitialized = true;
    m_info = Eigen::Success;
    m_analysisIsOk = true;
    m_factorizationIsOk = false;
  }

  // Eigen's analyzePattern(): CHOLMOD's own ordering, which may be METIS
  // (internal::MetisMutex).
  void AnalyzePatternLocked(const SparseMatrix& a) {
    const std::lock_guard<std::mutex> lock(MetisMutex());
    analyzePattern(a);
  }

  // Takes `other`'s symbolic analysis (ordering and pattern of L) as its own,
  // so that another matrix of the analysed pattern factorises without
  // analysing again, on this object's own CHOLMOD work space (another thread).
  void CopyAnalysis(const CholmodLlt& other) {
    if (m_cholmodFactor != nullptr) cholmod_free_factor(&m_cholmodFactor, &cholmod());
    m_cholmodFactor = cholmod_copy_factor(other.m_cholmodFactor, &cholmod());
    if (m_cholmodFactor == nullptr) {
      throw std::bad_alloc();
    }
    m_isInitialized = true;
    m_analysisIsOk = true;
    m_factorizationIsOk = false;
  }

  // The fill-reducing permutation P of P A P' = L L': (P x)[k] = x[perm[k]].
  // Null for the identity.
  const int* Permutation() const {
    return static_cast<const int*>(m_cholmodFactor->Perm);
  }

  // DOF (original numbering) at which the factorisation broke down, or -1.
  Eigen::Index FailedDof() const {
    const cholmod_factor* factor = m_cholmodFactor;
    if (factor == nullptr || factor->minor >= factor->n) return -1;
    return OriginalDof(factor->minor);
  }

  // Pivots L_jj^2 (D_jj for an LDL' factor) by DOF in the original numbering.
  // Only after a successful factorisation.
  Eigen::VectorXd Pivots() const {
    const cholmod_factor* factor = m_cholmodFactor;
    const Eigen::Index n = static_cast<Eigen::Index>(factor->n);
    const double* x = static_cast<const double*>(factor->x);
    Eigen::VectorXd pivots(n);
    if (factor->is_super) {
      const int* super = static_cast<const int*>(factor->super);
      const int* pi = static_cast<const int*>(factor->pi);
      const int* px = static_cast<const int*>(factor->px);
      for (std::size_t s = 0; s < factor->nsuper; ++s) {
        const int num_cols = super[s + 1] - super[s];
        const int num_rows = pi[s + 1] - pi[s];
        const double* block = x + px[s];  // num_rows x num_cols, column-major
        for (int c = 0; c < num_cols; ++c) {
          const double l = block[c * num_rows + c];
          pivots[OriginalDof(super[s] + c)] = l * l;
        }
      }
    } else {
      const int* p = static_cast<const int*>(factor->p);
      for (Eigen::Index j = 0; j < n; ++j) {
        const double d = x[p[j]];
        pivots[OriginalDof(j)] = factor->is_ll ? d * d : d;
      }
    }
    return pivots;
  }

 private:
  Eigen::Index OriginalDof(std::size_t pivot) const {
    const int* perm = static_cast<const int*>(m_cholmodFactor->Perm);
    return perm != nullptr ? perm[pivot] : static_cast<Eigen::Index>(pivot);
  }

  cholmod_dense* x_ = nullptr;  // cholmod_solve2's result and work space
  cholmod_dense* y_ = nullptr;
  cholmod_dense* e_ = nullptr;
};

}  // namespace internal
}  // namespace femup
