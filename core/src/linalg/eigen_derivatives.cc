#include "femup/core/linalg/eigen_derivatives.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace {

// Largest normwise backward error of the L D L' factor's solution for a known
// right-hand side (K - lambda M times ones) that is accepted; a larger one (a small pivot
// met without pivoting) means LU. Both factors reach about 1e-15 where they work.
constexpr double kLdltTolerance = 1e-10;

void CheckSquare(const SparseMatrix& a, Eigen::Index n, const char* what,
                 bool allow_empty) {
  if (allow_empty && a.rows() == 0 && a.cols() == 0) return;
  if (a.rows() != n || a.cols() != n) {
    std::ostringstream msg;
    msg << what << " is " << a.rows() << " x " << a.cols() << "; expected " << n << " x "
        << n << (allow_empty ? " (or empty for zero)" : "");
    throw InputError("eigen derivatives", msg.str());
  }
}

// a' B b, with an empty B read as zero.
double Form(const Eigen::VectorXd& a, const SparseMatrix& b, const Eigen::VectorXd& c) {
  return b.size() == 0 ? 0.0 : a.dot(b * c);
}

}  // namespace

double EigenvalueDerivative(const Eigen::VectorXd& phi, double lambda,
                            const SparseMatrix& dK, const SparseMatrix& dM) {
  CheckSquare(dK, phi.size(), "dK", true);
  CheckSquare(dM, phi.size(), "dM", true);
  return Form(phi, dK, phi) - lambda * Form(phi, dM, phi);
}

double EigenvalueDerivative(const Eigen::VectorXd& phi, double lambda,
                            const BasisMatrix* dK, const BasisMatrix* dM) {
  return (dK != nullptr ? dK->Form(phi, phi) : 0.0) -
         lambda * (dM != nullptr ? dM->Form(phi, phi) : 0.0);
}

NelsonSolver::NelsonSolver(const SparseMatrix& K, const SparseMatrix& M, double lambda,
                           const Eigen::VectorXd& phi)
    : NelsonSolver(K, M, lambda, phi, Eigen::MatrixXd(phi)) {}

NelsonSolver::NelsonSolver(const SparseMatrix& K, const SparseMatrix& M, double lambda,
                           const Eigen::VectorXd& phi, const Eigen::MatrixXd& cluster)
    : lambda_(lambda), phi_(phi), cluster_(cluster) {
  const Eigen::Index n = phi.size();
  if (n == 0) throw InputError("eigen derivatives", "the eigenvector is empty");
  CheckSquare(K, n, "K", false);
  CheckSquare(M, n, "M", false);
  if (!phi.allFinite() || !std::isfinite(lambda)) {
    throw InputError("eigen derivatives", "the eigenpair has a NaN or infinite entry");
  }
  mass_phi_ = M * phi;
  const double norm = phi.dot(mass_phi_);
  if (!(std::abs(norm - 1.0) <= 1e-6)) {
    std::ostringstream msg;
    msg << "phi' M phi = " << norm << "; the eigenvector must be mass-normalised";
    throw InputError("eigen derivatives", msg.str());
  }
  const Eigen::Index c = cluster.cols();
  if (cluster.rows() != n || c < 1 || c > n || !cluster.allFinite()) {
    std::ostringstream msg;
    msg << "the eigenspace is " << cluster.rows() << " x " << c << "; expected " << n
        << " rows, 1 to " << n << " finite columns";
    throw InputError("eigen derivatives", msg.str());
  }
  mass_cluster_ = M * cluster;
  const double orthonormality =
      (cluster.transpose() * mass_cluster_ - Eigen::MatrixXd::Identity(c, c))
          .lpNorm<Eigen::Infinity>();
  const double outside = (phi - cluster * (mass_cluster_.transpose() * phi)).norm();
  if (!(orthonormality <= 1e-6) || !(outside <= 1e-6 * phi.norm())) {
    throw InputError("eigen derivatives",
                     "the eigenspace must be M-orthonormal and hold phi");
  }
  // The c entries held at zero: Gaussian elimination with complete pivoting on
  // the cluster's rows (for c = 1, phi's largest entry), so that the cluster
  // restricted to them is as well conditioned as it can be.
  {
    Eigen::MatrixXd b = cluster;
    for (Eigen::Index t = 0; t < c; ++t) {
      Eigen::Index row = 0, col = 0;
      b.cwiseAbs().maxCoeff(&row, &col);
      pivots_.push_back(static_cast<int>(row));
      const Eigen::VectorXd pivot_column = b.col(col) / b(row, col);
      const Eigen::RowVectorXd pivot_row = b.row(row);
      b -= pivot_column * pivot_row;  // zeroes row `row` and column `col`
    }
    std::sort(pivots_.begin(), pivots_.end());
  }
  reduced_.assign(static_cast<std::size_t>(n), -1);
  for (Eigen::Index i = 0, next = 0, p = 0; i < n; ++i) {
    if (p < c && pivots_[static_cast<std::size_t>(p)] == i) {
      ++p;
      continue;
    }
    reduced_[static_cast<std::size_t>(i)] = static_cast<int>(next++);
  }
  const Eigen::Index nr = n - c;
  if (nr == 0) return;  // v is empty: the derivative is the normalisation term alone

  // K - lambda M without the pivots' rows and columns.
  const SparseMatrix a = K - lambda * M;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(a.nonZeros()));
  for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
    const int rc = reduced_[static_cast<std::size_t>(col)];
    if (rc < 0) continue;
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
      const int rr = reduced_[static_cast<std::size_t>(it.row())];
      if (rr >= 0) entries.emplace_back(rr, rc, it.value());
    }
  }
  SparseMatrix reduced(nr, nr);
  reduced.setFromTriplets(entries.begin(), entries.end());
  ldlt_.compute(reduced);
  if (ldlt_.info() == Eigen::Success) {
    // L D L' does not pivot: check it on a known solution (ones) before use.
    // The backward error (the residual relative to the right-hand side) is the
    // test: the forward error is large for LU too where two eigenvalues are
    // close (a jacket's two sway modes) and the reduced matrix nearly singular.
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(nr);
    const Eigen::VectorXd b = reduced * ones;
    const Eigen::VectorXd x = ldlt_.solve(b);
    // Normwise backward error: ||A x - b|| / (||A|| ||x|| + ||b||), inf-norms.
    const double norm_a = (reduced.cwiseAbs() * ones).maxCoeff();
    const double scale =
        norm_a * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>();
    if (x.allFinite() && scale > 0 &&
        (reduced * x - b).lpNorm<Eigen::Infinity>() <= kLdltTolerance * scale) {
      return;
    }
  }
  lu_ = std::make_unique<Eigen::SparseLU<SparseMatrix>>();
  lu_->analyzePattern(reduced);
  lu_->factorize(reduced);
  if (lu_->info() != Eigen::Success) {
    message_ = "K - lambda M with row/column " + std::to_string(pivots_[0] + 1) +
               (c > 1 ? " and " + std::to_string(c - 1) + " more" : std::string()) +
               " removed is singular (repeated eigenvalue, or lambda is not an "
               "eigenvalue): " +
               lu_->lastErrorMessage();
  }
}

EigenpairDerivative NelsonSolver::Derivative(const SparseMatrix& dK,
                                             const SparseMatrix& dM) const {
  if (!ok()) throw InputError("eigen derivatives", message_);
  const Eigen::Index n = phi_.size();
  CheckSquare(dK, n, "dK", true);
  CheckSquare(dM, n, "dM", true);
  const double phi_dm_phi = Form(phi_, dM, phi_);
  const double dlambda = Form(phi_, dK, phi_) - lambda_ * phi_dm_phi;
  // Right-hand side f = -(dK - dlambda M - lambda dM) phi.
  Eigen::VectorXd f = dlambda * mass_phi_;
  if (dK.size() > 0) f -= dK * phi_;
  if (dM.size() > 0) f += lambda_ * (dM * phi_);
  return Solve(dlambda, phi_dm_phi, f);
}

EigenpairDerivative NelsonSolver::Derivative(const BasisMatrix* dK,
                                             const BasisMatrix* dM) const {
  if (!ok()) throw InputError("eigen derivatives", message_);
  const double phi_dm_phi = dM != nullptr ? dM->Form(phi_, phi_) : 0.0;
  const double dlambda =
      (dK != nullptr ? dK->Form(phi_, phi_) : 0.0) - lambda_ * phi_dm_phi;
  Eigen::VectorXd f = dlambda * mass_phi_;
  if (dK != nullptr) dK->AddProductTo(-1.0, phi_, &f);
  if (dM != nullptr) dM->AddProductTo(lambda_, phi_, &f);
  return Solve(dlambda, phi_dm_phi, f);
}

EigenpairDerivative NelsonSolver::Solve(double dlambda, double phi_dm_phi,
                                        const Eigen::VectorXd& f) const {
  const Eigen::Index n = phi_.size();
  EigenpairDerivative out;
  out.eigenvalue = dlambda;
  // f off the eigenspace (a no-op for c = 1, where phi' f = 0 already): the
  // singular system is then consistent.
  const Eigen::VectorXd g = f - mass_cluster_ * (cluster_.transpose() * f);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  const Eigen::Index nr = n - static_cast<Eigen::Index>(pivots_.size());
  if (nr > 0) {
    Eigen::VectorXd g_reduced(nr);
    for (Eigen::Index i = 0; i < n; ++i) {
      const int r = reduced_[static_cast<std::size_t>(i)];
      if (r >= 0) g_reduced[r] = g[i];
    }
    const Eigen::VectorXd v_reduced =
        lu_ != nullptr ? Eigen::VectorXd(lu_->solve(g_reduced)) : ldlt_.solve(g_reduced);
    for (Eigen::Index i = 0; i < n; ++i) {
      const int r = reduced_[static_cast<std::size_t>(i)];
      if (r >= 0) v[i] = v_reduced[r];
    }
  }
  // v's component in the eigenspace removed, and the multiple of phi that keeps
  // phi' M phi = 1: d/dp (phi' M phi) = 2 phi' M dphi + phi' dM phi = 0.
  v -= cluster_ * (mass_cluster_.transpose() * v);
  out.eigenvector = v - 0.5 * phi_dm_phi * phi_;
  return out;
}

Eigen::VectorXd EigenvectorDerivative(const SparseMatrix& K, const SparseMatrix& M,
                                      double lambda, const Eigen::VectorXd& phi,
                                      const SparseMatrix& dK, const SparseMatrix& dM) {
  return NelsonSolver(K, M, lambda, phi).Derivative(dK, dM).eigenvector;
}

}  // namespace femup
