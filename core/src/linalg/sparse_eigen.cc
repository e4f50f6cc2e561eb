#include "linalg/sparse_eigen.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <memory>
#include <new>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/parallel.h"
#include "linalg/cholmod_llt.h"

namespace femup {
namespace internal {

// Flops per entry of L from which CHOLMOD factorises supernodally (its own
// default is 40). On the space frames of docs/benchmarks.md, 10^5 DOF (193
// flops per entry with AMD) factorise about as fast simplicially and solve
// 1.5-4.4x faster (2.9-8.9 ms against 9.4-15.7 ms, ATLAS or OpenBLAS); 10^6 DOF
// (1,093 with METIS) stay supernodal, where the dense kernels pay.
const double kSupernodalSwitch = 500;

// From this many DOFs, M's factorisation (the check that it is positive
// definite) runs beside K - shift*M's when EigenOptions::threads allows. On the
// 10^5-DOF frame each takes 0.12-0.16 s; below 10^4 DOFs they take
// milliseconds, less than starting a thread saves.
const Eigen::Index kParallelFactorisationDofs = 10000;

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

// The lower triangle of alpha A + beta B (entries of A and B above the
// diagonal are not read) on the union of their patterns, explicit zeros kept, so
// that every combination of the same A and B has the same pattern (CHOLMOD
// factorises on an analysis only matrices of the analysed pattern). One merge
// per column: Eigen's sparse sum takes five times as long on the 10^5-DOF frame.
// The inner indices of each column of A and B must be ascending (as Eigen's
// compressed matrices have them).
SparseMatrix Combine(double alpha, const SparseMatrix& a, double beta,
                     const SparseMatrix& b) {
  const Eigen::Index n = a.cols();
  SparseMatrix sum(a.rows(), n);
  sum.resizeNonZeros(a.nonZeros() + b.nonZeros());  // an upper bound; trimmed below
  int* outer = sum.outerIndexPtr();
  int* inner = sum.innerIndexPtr();
  double* values = sum.valuePtr();
  Eigen::Index next = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    outer[j] = static_cast<int>(next);
    SparseMatrix::InnerIterator ia(a, j);
    SparseMatrix::InnerIterator ib(b, j);
    while (ia && ia.row() < j) ++ia;  // the lower triangles only
    while (ib && ib.row() < j) ++ib;
    while (ia || ib) {
      if (ib && (!ia || ib.row() < ia.row())) {
        inner[next] = static_cast<int>(ib.row());
        values[next] = beta * ib.value();
        ++ib;
      } else if (ia && (!ib || ia.row() < ib.row())) {
        inner[next] = static_cast<int>(ia.row());
        values[next] = alpha * ia.value();
        ++ia;
      } else {
        inner[next] = static_cast<int>(ia.row());
        values[next] = alpha * ia.value() + beta * ib.value();
        ++ia;
        ++ib;
      }
      ++next;
    }
  }
  outer[n] = static_cast<int>(next);
  sum.data().resize(next);
  return sum;
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

// True when no entry off the diagonal is non-zero.
bool IsDiagonal(const SparseMatrix& lower) {
  for (Eigen::Index j = 0; j < lower.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(lower, j); it; ++it) {
      if (it.row() != j && it.value() != 0.0) return false;
    }
  }
  return true;
}

// -1 when the symmetric M whose lower triangle is `m_lower` is positive
// definite; otherwise the DOF at which its Cholesky factorisation breaks down
// (n when CHOLMOD does not say). A diagonal M is read directly; any other is
// factorised (LL') on a copy of `analysed`'s analysis of the pattern of K + M,
// with its own work space, so that this can run beside K - shift*M's.
Eigen::Index MassBreakdown(const SparseMatrix& k_lower, const SparseMatrix& m_lower,
                           const CholmodLlt& analysed, double supernodal_switch) {
  const Eigen::Index n = m_lower.rows();
  if (IsDiagonal(m_lower)) {
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!(m_lower.coeff(j, j) > 0.0)) return j;
    }
    return -1;
  }
  const SparseMatrix m_on_pattern =
      Combine(0.0, k_lower, 1.0, m_lower);  // analysed pattern
  CholmodLlt llt(supernodal_switch);
  llt.CopyAnalysis(analysed);
  llt.factorize(m_on_pattern);
  if (llt.info() == Eigen::Success) return -1;
  const Eigen::Index dof = llt.FailedDof();
  return dof >= 0 ? dof : n;
}

// The shift-inverted pencil as a standard symmetric operator, for a
// positive definite K - sigma M = P' L L' P: C = L^{-1} P M P' L^{-T}. Its
// eigenvalues are those of (K - sigma M)^{-1} M, nu = 1 / (lambda - sigma), and
// its eigenvectors psi = L' P phi. A Lanczos step then costs one product with M
// and the two triangular solves, and its orthogonalisation is Euclidean: the
// generalised (M-inner product) Lanczos multiplies by M three times a step.
class StandardShiftInvertOp {
 public:
  using Scalar = double;

  // `m_lower`: M, of which only the lower triangle is read, in place (on a copy
  // of the lower triangle of the 10^5-DOF frame's M, the symmetric product took
  // 0.44 ms, as long as a full row-major copy's, at half the memory).
  StandardShiftInvertOp(CholmodLlt* llt, const SparseMatrix& m_lower)
      : llt_(llt),
        m_(m_lower),
        perm_(llt->Permutation()),
        a_(m_lower.rows()),
        b_(m_lower.rows()) {}

  Eigen::Index rows() const { return m_.rows(); }
  Eigen::Index cols() const { return m_.rows(); }

  void perform_op(const double* x_in, double* y_out) const {
    llt_->SolveTriangular(CHOLMOD_Lt, x_in, a_.data());      // a = L^{-T} x
    Unpermute(a_, &b_);                                      // b = P' a
    a_.noalias() = m_.selfadjointView<Eigen::Lower>() * b_;  // a = M b
    Permute(a_, &b_);                                        // b = P a
    llt_->SolveTriangular(CHOLMOD_L, b_.data(), y_out);      // y = L^{-1} b
  }

  // phi = P' L^{-T} psi: the pencil's eigenvector of C's eigenvector psi.
  Eigen::VectorXd ModeShape(const Eigen::VectorXd& psi) const {
    llt_->SolveTriangular(CHOLMOD_Lt, psi.data(), a_.data());
    Eigen::VectorXd phi(m_.rows());
    Unpermute(a_, &phi);
    return phi;
  }

 private:
  void Permute(const Eigen::VectorXd& x, Eigen::VectorXd* y) const {
    if (perm_ == nullptr) {
      *y = x;
      return;
    }
    for (Eigen::Index k = 0; k < x.size(); ++k) (*y)[k] = x[perm_[k]];
  }
  void Unpermute(const Eigen::VectorXd& x, Eigen::VectorXd* y) const {
    if (perm_ == nullptr) {
      *y = x;
      return;
    }
    for (Eigen::Index k = 0; k < x.size(); ++k) (*y)[perm_[k]] = x[k];
  }

  CholmodLlt* llt_;
  const SparseMatrix& m_;
  const int* perm_;
  mutable Eigen::VectorXd a_, b_;
};

// The factorisation of K - sigma M, and the Spectra operation y = (K - sigma
// M)^{-1} x for GEigsMode::ShiftInvert (only K's and M's lower triangles are read).
// Factorises with CHOLMOD (LL') and falls back to SimplicialLDLT when K - sigma
// M is not positive definite. One symbolic analysis (ordering and fill) serves
// every shift: K - sigma M has the pattern of K + M whatever sigma. set_shift()
// does not throw: it records what went wrong in failure().
class CholmodShiftInvertOp {
 public:
  using Scalar = double;
  using Ldlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>;

  CholmodShiftInvertOp(const SparseMatrix& k_lower, const SparseMatrix& m_lower,
                       double supernodal_switch, const std::vector<int>& groups)
      : k_(k_lower),
        m_(m_lower),
        n_(k_lower.rows()),
        llt_(supernodal_switch),
        groups_(groups) {}

  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }

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
  // The LL' factor of K - sigma M after a set_shift() that factorised without
  // falling back to LDL'.
  CholmodLlt* llt() { return &llt_; }

  // The symbolic analysis of the pattern of K + M (done once; set_shift()
  // reuses it), to factorise M on. Analysed on K - sigma M, which set_shift(sigma)
  // then factorises without forming it again.
  const CholmodLlt& Analysed(double sigma) {
    Shifted(sigma);
    Analyse(shifted_);
    return llt_;
  }
  // Number of eigenvalues of the pencil below the shift (Sylvester's law of
  // inertia: the negative pivots of K - shift*M, M being positive definite).
  Eigen::Index num_below_shift() const { return num_below_shift_; }

 private:
  // The lower triangle of K - sigma M on the pattern of K + M, formed once per sigma.
  const SparseMatrix& Shifted(double sigma) {
    if (!has_shifted_ || sigma != shifted_sigma_) {
      shifted_ = Combine(1.0, k_, -sigma, m_);
      shifted_sigma_ = sigma;
      has_shifted_ = true;
    }
    return shifted_;
  }

  // The symbolic analysis, once, on the pattern of K + M (`a` holds exactly
  // that pattern: Combine keeps the union of its operands').
  void Analyse(const SparseMatrix& a) {
    if (analysed_) return;
    llt_.AnalyzePatternByGroups(a, groups_);
    analysed_ = true;
  }

  void Factorise(double sigma) {
    sigma_ = sigma;
    factorised_ = false;
    failure_.clear();
    num_below_shift_ = 0;
    ldlt_.reset();
    const SparseMatrix& a = Shifted(sigma);  // lower triangle of K - sigma M
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
  SparseMatrix shifted_;
  double shifted_sigma_ = 0.0;
  bool has_shifted_ = false;
  bool factorised_ = false;
  std::string failure_;
  Eigen::Index num_below_shift_ = 0;
  CholmodLlt llt_;
  const std::vector<int>& groups_;  // DOF groups for the ordering (may be empty)
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

  // Only the lower triangles of K and M are read, by every factorisation and
  // product (no copies of them are made).

  // The B-inner product of the Lanczos process needs M positive definite; that
  // check (a factorisation of M) and K - shift*M's are independent, and run
  // side by side on large models when options.threads allows. The check's
  // InputError, the lower index, is the one rethrown when both fail.
  if (!options.dof_groups.empty() &&
      (options.dof_groups.size() != static_cast<std::size_t>(n) ||
       *std::min_element(options.dof_groups.begin(), options.dof_groups.end()) < 0)) {
    throw InputError(kWhere, "dof_groups must be empty or one index >= 0 per DOF (" +
                                 std::to_string(n) + "), got " +
                                 std::to_string(options.dof_groups.size()) + " entries " +
                                 Context(k, n, shift));
  }
  CholmodShiftInvertOp op(K, M, supernodal_switch, options.dof_groups);
  const auto check_mass = [&](const CholmodLlt& analysed) {
    if (const Eigen::Index dof = MassBreakdown(K, M, analysed, supernodal_switch);
        dof >= 0) {
      std::ostringstream out;
      out << "mass matrix is not positive definite (its Cholesky factorisation breaks "
             "down";
      if (dof < n) out << " at DOF " << dof;
      out << ") " << Context(k, n, shift);
      throw InputError(kWhere, out.str());
    }
  };
  const CholmodLlt& analysed = op.Analysed(shift);
  ParallelFor(2, n >= kParallelFactorisationDofs ? options.threads : 1, [&](int task) {
    if (task == 0) {
      check_mass(analysed);
    } else {
      op.set_shift(shift);  // the solver's own set_shift(shift) then reuses this
    }
  });
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

  const Eigen::Index ncv = std::min<Eigen::Index>(n, std::max(2 * k + 1, 20));
  Eigen::VectorXd eigenvalues;
  Eigen::MatrixXd shapes;
  // "did not converge" with what to change, for either Lanczos process.
  const auto not_converged = [&](Eigen::Index converged, Eigen::Index restarts,
                                 Eigen::Index solves) {
    std::ostringstream out;
    out << "shift-invert Lanczos did not converge: " << converged << " of " << k
        << " modes converged after " << restarts << " restarts (" << solves
        << " solves; max_iterations = " << options.max_iterations
        << ", tolerance = " << Format(options.tolerance) << ", ncv = " << ncv << ") "
        << Context(k, n, shift)
        << "; raise max_iterations or tolerance, or move the shift";
    return NumericalError(kWhere, out.str());
  };
  try {
    if (!op.uses_ldlt()) {
      // K - shift*M positive definite (the shift below the spectrum): the
      // standard form C = L^{-1} P M P' L^{-T}, whose largest eigenvalues nu =
      // 1 / (lambda - shift) are the lambdas nearest above the shift.
      StandardShiftInvertOp standard(op.llt(), M);
      Spectra::SymEigsSolver<StandardShiftInvertOp> solver(standard, k, ncv);
      solver.init();
      const Eigen::Index converged =
          solver.compute(Spectra::SortRule::LargestAlge, options.max_iterations,
                         options.tolerance, Spectra::SortRule::LargestAlge);
      if (solver.info() != Spectra::CompInfo::Successful || converged < k) {
        throw not_converged(converged, solver.num_iterations(), solver.num_operations());
      }
      const Eigen::VectorXd nu = solver.eigenvalues();
      const Eigen::MatrixXd psi = solver.eigenvectors();
      eigenvalues.resize(k);
      shapes.resize(n, k);
      for (int j = 0; j < k; ++j) {
        eigenvalues[j] = shift + 1.0 / nu[j];
        shapes.col(j) = standard.ModeShape(psi.col(j));
      }
    } else {
      // The shift inside the spectrum (LDL'): the generalised process on the
      // M-inner product.
      using BOp = Spectra::SparseSymMatProd<double>;
      using Solver = Spectra::SymGEigsShiftSolver<CholmodShiftInvertOp, BOp,
                                                  Spectra::GEigsMode::ShiftInvert>;
      BOp mass_op(M);
      Solver solver(op, mass_op, k, ncv, shift);
      solver.init();
      // nu = 1 / (lambda - shift): the largest nu are the eigenvalues nearest
      // above the shift. Sorting SmallestAlge orders the lambdas ascending.
      const Eigen::Index converged =
          solver.compute(Spectra::SortRule::LargestAlge, options.max_iterations,
                         options.tolerance, Spectra::SortRule::SmallestAlge);
      if (solver.info() != Spectra::CompInfo::Successful || converged < k) {
        throw not_converged(converged, solver.num_iterations(), solver.num_operations());
      }
      eigenvalues = solver.eigenvalues();
      shapes = solver.eigenvectors();
    }
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
    const double modal_mass = phi.dot(M.selfadjointView<Eigen::Lower>() * phi);
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
