#include "linalg/sparse_eigen.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace internal {

// Flops per entry of L from which CHOLMOD factorises supernodally (its own
// default is 40). On the space frames of docs/benchmarks.md, 10^5 DOF (193
// flops per entry with AMD) factorise about as fast simplicially and solve
// 1.5-4.4x faster (2.9-8.9 ms against 9.4-15.7 ms, ATLAS or OpenBLAS); 10^6 DOF
// (1,093 with METIS) stay supernodal, where the dense kernels pay.
const double kSupernodalSwitch = 500;

namespace {

constexpr char kWhere[] = "modal analysis";

// Largest backward error ||A y - b|| / (||A|| ||y|| + ||b||) accepted from the
// LDLT factorisation (which does not pivot, so it can be unstable when K - shift*M
// is indefinite).
constexpr double kMaxLdltBackwardError = 1e-10;

// A pivot smaller than this times the absolute row sum of its row marks
// K - shift*M as singular to working precision: the shift is an eigenvalue (to
// rounding), and the Lanczos process would meet 1 / (lambda - shift) ~ 1e16.
constexpr double kSingularPivotRatio = 1e-14;

std::string Format(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

// "(k = 6, n = 200, shift = 0)": the context every error message carries.
std::string Context(int k, Eigen::Index n, double shift) {
  std::ostringstream out;
  out << "(k = " << k << ", n = " << n << ", shift = " << Format(shift) << ")";
  return out.str();
}

// Row sums of |A| for the symmetric A whose lower triangle is `lower`.
Eigen::VectorXd AbsRowSums(const SparseMatrix& lower) {
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(lower.rows());
  for (Eigen::Index j = 0; j < lower.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(lower, j); it; ++it) {
      sums[it.row()] += std::abs(it.value());
      if (it.row() != j) sums[j] += std::abs(it.value());
    }
  }
  return sums;
}

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
};

// Spectra operation y = (K - sigma M)^{-1} x for GEigsMode::ShiftInvert.
// K and M hold lower triangles. Factorises with CHOLMOD (LL') and falls back to
// SimplicialLDLT when K - sigma M is not positive definite. One symbolic
// analysis (ordering and fill) serves every shift and the check of M: K - sigma
// M has the pattern of K + M whatever sigma. set_shift() does not throw: it
// records what went wrong in failure().
class CholmodShiftInvertOp {
 public:
  using Scalar = double;
  using Ldlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>;

  CholmodShiftInvertOp(const SparseMatrix& k_lower, const SparseMatrix& m_lower,
                       double supernodal_switch)
      : k_(k_lower), m_(m_lower), n_(k_lower.rows()), llt_(supernodal_switch) {}

  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }

  // -1 when M is positive definite; otherwise the DOF at which its Cholesky
  // factorisation breaks down (n when CHOLMOD does not say). A diagonal M is
  // read directly; any other is factorised on the analysis of K + M.
  Eigen::Index MassBreakdown() {
    if (IsDiagonal(m_)) {
      for (Eigen::Index j = 0; j < n_; ++j) {
        if (!(m_.coeff(j, j) > 0.0)) return j;
      }
      return -1;
    }
    const SparseMatrix m_on_pattern = 0.0 * k_ + m_;  // M on the pattern of K + M
    Analyse(m_on_pattern);
    llt_.factorize(m_on_pattern);
    if (llt_.info() == Eigen::Success) return -1;
    const Eigen::Index dof = llt_.FailedDof();
    return dof >= 0 ? dof : n_;
  }

  void set_shift(double sigma) {
    if (factorised_ && sigma == sigma_) return;  // already factorised at sigma
    Factorise(sigma);
  }

  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, n_);
    Eigen::Map<Eigen::VectorXd> y(y_out, n_);
    if (ldlt_ != nullptr) {
      y = ldlt_->solve(x);
    } else {
      y = llt_.solve(x);
    }
  }

  // Empty when the last set_shift() factorised; otherwise what went wrong.
  const std::string& failure() const { return failure_; }
  bool uses_ldlt() const { return ldlt_ != nullptr; }
  // Number of eigenvalues of the pencil below the shift (Sylvester's law of
  // inertia: the negative pivots of K - shift*M, M being positive definite).
  Eigen::Index num_below_shift() const { return num_below_shift_; }

 private:
  static bool IsDiagonal(const SparseMatrix& lower) {
    for (Eigen::Index j = 0; j < lower.outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(lower, j); it; ++it) {
        if (it.row() != j && it.value() != 0.0) return false;
      }
    }
    return true;
  }

  // The symbolic analysis, once, on the pattern of K + M (`a` holds exactly
  // that pattern: Eigen's sparse sums keep the union of their operands').
  void Analyse(const SparseMatrix& a) {
    if (analysed_) return;
    llt_.analyzePattern(a);
    analysed_ = true;
  }

  void Factorise(double sigma) {
    sigma_ = sigma;
    factorised_ = false;
    failure_.clear();
    num_below_shift_ = 0;
    ldlt_.reset();
    const SparseMatrix a = k_ - sigma * m_;  // lower triangle of K - sigma M
    const Eigen::VectorXd row_sums = AbsRowSums(a);

    Analyse(a);
    llt_.factorize(a);
    if (llt_.info() == Eigen::Success) {
      factorised_ = CheckPivots(llt_.Pivots(), row_sums);
      return;
    }

    // Not positive definite: the shift lies inside the spectrum (or above it).
    ldlt_ = std::make_unique<Ldlt>();
    ldlt_->compute(a);
    if (ldlt_->info() != Eigen::Success) {
      ldlt_.reset();
      failure_ =
          "K - shift*M is singular or needs pivoting (its LDLT meets a zero pivot): "
          "the shift is, or is too close to, an eigenvalue; move the shift (for a "
          "model with rigid-body modes, lambda = 0, use a negative shift)";
      return;
    }
    const Eigen::VectorXd& d = ldlt_->vectorD();  // in the permuted numbering
    const auto& to_permuted = ldlt_->permutationP().indices();
    Eigen::VectorXd pivots(n_);
    for (Eigen::Index j = 0; j < n_; ++j) pivots[j] = d[to_permuted[j]];
    if (!CheckPivots(pivots, row_sums)) {
      ldlt_.reset();
      return;
    }
    const double error = LdltBackwardError(a, row_sums);
    if (!(error <= kMaxLdltBackwardError)) {
      ldlt_.reset();
      failure_ =
          "K - shift*M is indefinite and its LDLT factorisation (no pivoting) is "
          "unstable at this shift (backward error " +
          Format(error) + "); move the shift";
      return;
    }
    num_below_shift_ = (d.array() < 0.0).count();
    factorised_ = true;
  }

  // False, with failure_ set, when a pivot is negligible against its row.
  bool CheckPivots(const Eigen::VectorXd& pivots, const Eigen::VectorXd& row_sums) {
    for (Eigen::Index j = 0; j < n_; ++j) {
      if (!(std::abs(pivots[j]) > kSingularPivotRatio * row_sums[j])) {
        std::ostringstream out;
        out << "K - shift*M is singular to working precision (pivot " << Format(pivots[j])
            << " at DOF " << j << " against a row of size " << Format(row_sums[j])
            << "): the shift is an eigenvalue; move the shift (for a model with "
               "rigid-body modes, lambda = 0, use a negative shift)";
        failure_ = out.str();
        return false;
      }
    }
    return true;
  }

  // ||A y - b||_inf / (||A||_inf ||y||_inf + ||b||_inf) for one solve, where A
  // is the symmetric matrix whose lower triangle is `a`.
  double LdltBackwardError(const SparseMatrix& a, const Eigen::VectorXd& row_sums) const {
    Eigen::VectorXd b(n_);
    for (Eigen::Index i = 0; i < n_; ++i) b[i] = 1.0 + 0.5 * std::sin(1.7 * i);
    const Eigen::VectorXd y = ldlt_->solve(b);
    const Eigen::VectorXd r = a.selfadjointView<Eigen::Lower>() * y - b;
    const double scale =
        row_sums.maxCoeff() * y.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>();
    return r.lpNorm<Eigen::Infinity>() / scale;  // NaN when y is not finite
  }

  const SparseMatrix& k_;
  const SparseMatrix& m_;
  const Eigen::Index n_;
  double sigma_ = 0.0;
  bool analysed_ = false;
  bool factorised_ = false;
  std::string failure_;
  Eigen::Index num_below_shift_ = 0;
  CholmodLlt llt_;
  std::unique_ptr<Ldlt> ldlt_;
};

bool AllFinite(const SparseMatrix& a) {
  for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
      if (!std::isfinite(it.value())) return false;
    }
  }
  return true;
}

}  // namespace

Modes SolveModesSparse(const SparseMatrix& K, const SparseMatrix& M,
                       const EigenOptions& options, double supernodal_switch) {
  const int k = options.num_modes;
  const double shift = options.shift;
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows()) {
    std::ostringstream out;
    out << "stiffness is " << K.rows() << "x" << K.cols() << " and mass is " << M.rows()
        << "x" << M.cols() << "; both must be square and of the same size";
    throw InputError(kWhere, out.str());
  }
  const Eigen::Index n = K.rows();
  if (k < 1 || k > n - 1) {
    std::ostringstream out;
    out << "num_modes = " << k << " is out of range for the sparse eigensolver: it needs "
        << "1 <= num_modes <= n - 1 = " << n - 1 << " " << Context(k, n, shift);
    throw InputError(kWhere, out.str());
  }
  if (!std::isfinite(shift)) {
    throw InputError(kWhere, "shift must be finite " + Context(k, n, shift));
  }
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    throw InputError(kWhere, "tolerance = " + Format(options.tolerance) +
                                 " must be positive and finite " + Context(k, n, shift));
  }
  if (options.max_iterations < 1) {
    throw InputError(kWhere,
                     "max_iterations = " + std::to_string(options.max_iterations) +
                         " must be at least 1 " + Context(k, n, shift));
  }
  if (!AllFinite(K)) {
    throw InputError(kWhere,
                     "stiffness matrix has a non-finite entry " + Context(k, n, shift));
  }
  if (!AllFinite(M)) {
    throw InputError(kWhere,
                     "mass matrix has a non-finite entry " + Context(k, n, shift));
  }

  // Only the lower triangles are read, by every factorisation and product.
  SparseMatrix k_lower = K.triangularView<Eigen::Lower>();
  SparseMatrix m_lower = M.triangularView<Eigen::Lower>();
  k_lower.makeCompressed();
  m_lower.makeCompressed();

  // The B-inner product of the Lanczos process needs M positive definite.
  CholmodShiftInvertOp op(k_lower, m_lower, supernodal_switch);
  if (const Eigen::Index dof = op.MassBreakdown(); dof >= 0) {
    std::ostringstream out;
    out << "mass matrix is not positive definite (its Cholesky factorisation breaks "
           "down";
    if (dof < n) out << " at DOF " << dof;
    out << ") " << Context(k, n, shift);
    throw InputError(kWhere, out.str());
  }
  op.set_shift(shift);  // the solver's own set_shift(shift) then reuses this
  // K - shift*M singular at the shift (a free-free model at shift 0): the
  // study's shift or supports are to change, so an input error that says so.
  if (!op.failure().empty()) {
    throw InputError(kWhere, "cannot factorise K - shift*M: " + op.failure() + " " +
                                 Context(k, n, shift));
  }

  if (n - op.num_below_shift() < k) {
    std::ostringstream out;
    out << "only " << n - op.num_below_shift() << " eigenvalues lie above the shift ("
        << op.num_below_shift() << " of " << n << " lie below it), fewer than the " << k
        << " requested " << Context(k, n, shift) << "; lower the shift";
    throw InputError(kWhere, out.str());
  }

  using BOp = Spectra::SparseSymMatProd<double>;
  using Solver = Spectra::SymGEigsShiftSolver<CholmodShiftInvertOp, BOp,
                                              Spectra::GEigsMode::ShiftInvert>;
  BOp mass_op(m_lower);
  const Eigen::Index ncv = std::min<Eigen::Index>(n, std::max(2 * k + 1, 20));
  Eigen::VectorXd eigenvalues;
  Eigen::MatrixXd shapes;
  try {
    Solver solver(op, mass_op, k, ncv, shift);
    solver.init();
    // nu = 1 / (lambda - shift): the largest nu are the eigenvalues nearest
    // above the shift. Sorting SmallestAlge orders the lambdas ascending.
    const Eigen::Index converged =
        solver.compute(Spectra::SortRule::LargestAlge, options.max_iterations,
                       options.tolerance, Spectra::SortRule::SmallestAlge);
    if (solver.info() != Spectra::CompInfo::Successful || converged < k) {
      std::ostringstream out;
      out << "shift-invert Lanczos did not converge: " << converged << " of " << k
          << " modes converged after " << solver.num_iterations() << " restarts ("
          << solver.num_operations()
          << " solves; max_iterations = " << options.max_iterations
          << ", tolerance = " << Format(options.tolerance) << ", ncv = " << ncv << ") "
          << Context(k, n, shift)
          << "; raise max_iterations or tolerance, or move the shift";
      throw NumericalError(kWhere, out.str());
    }
    eigenvalues = solver.eigenvalues();
    shapes = solver.eigenvectors();
  } catch (const NumericalError&) {
    throw;
  } catch (const std::exception& e) {
    throw NumericalError(kWhere,
                         std::string("shift-invert Lanczos failed (") + e.what() +
                             "); K - shift*M may be nearly singular: move the shift " +
                             Context(k, n, shift));
  }

  // Ascending eigenvalues (Spectra already sorts; keep it explicit).
  std::vector<Eigen::Index> order(eigenvalues.size());
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return eigenvalues[a] < eigenvalues[b];
  });

  Modes modes;
  modes.eigenvalues.resize(k);
  modes.shapes.resize(n, k);
  for (int j = 0; j < k; ++j) {
    modes.eigenvalues[j] = eigenvalues[order[j]];
    Eigen::VectorXd phi = shapes.col(order[j]);
    // Spectra returns M-orthonormal vectors; normalise again explicitly.
    const double modal_mass = phi.dot(m_lower.selfadjointView<Eigen::Lower>() * phi);
    if (!(modal_mass > 0.0) || !std::isfinite(modal_mass)) {
      std::ostringstream out;
      out << "mode " << j << " has modal mass " << Format(modal_mass)
          << "; expected a positive value " << Context(k, n, shift);
      throw NumericalError(kWhere, out.str());
    }
    phi /= std::sqrt(modal_mass);
    Eigen::Index largest = 0;
    phi.cwiseAbs().maxCoeff(&largest);
    if (phi[largest] < 0.0) phi = -phi;
    modes.shapes.col(j) = phi;
  }
  return modes;
}

}  // namespace internal
}  // namespace femup
