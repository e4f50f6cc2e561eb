#include "femup/eigen_derivatives.h"

#include <cmath>
#include <sstream>
#include <vector>

#include "femup/errors.h"

namespace femup {
namespace {

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
    : lambda_(lambda), phi_(phi) {
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
  Eigen::Index k = 0;
  phi.cwiseAbs().maxCoeff(&k);
  pivot_ = static_cast<int>(k);
  if (n == 1) return;  // v is empty: the derivative is c phi alone

  // K - lambda M without row and column k, indices above k shifted down by one.
  const SparseMatrix a = K - lambda * M;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(a.nonZeros()));
  for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
    if (col == k) continue;
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
      if (it.row() == k) continue;
      entries.emplace_back(it.row() - (it.row() > k), col - (col > k), it.value());
    }
  }
  SparseMatrix reduced(n - 1, n - 1);
  reduced.setFromTriplets(entries.begin(), entries.end());
  lu_.analyzePattern(reduced);
  lu_.factorize(reduced);
  if (lu_.info() != Eigen::Success) {
    message_ = "K - lambda M with row/column " + std::to_string(k + 1) +
               " removed is singular (repeated eigenvalue, or lambda is not an "
               "eigenvalue): " +
               lu_.lastErrorMessage();
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
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  if (n > 1) {
    Eigen::VectorXd f_reduced(n - 1);
    f_reduced << f.head(pivot_), f.tail(n - 1 - pivot_);
    const Eigen::VectorXd v_reduced = lu_.solve(f_reduced);
    v.head(pivot_) = v_reduced.head(pivot_);
    v.tail(n - 1 - pivot_) = v_reduced.tail(n - 1 - pivot_);
  }
  // The multiple of phi that keeps phi' M phi = 1: d/dp (phi' M phi) =
  // 2 phi' M dphi + phi' dM phi = 0.
  const double c = -mass_phi_.dot(v) - 0.5 * phi_dm_phi;
  out.eigenvector = v + c * phi_;
  return out;
}

Eigen::VectorXd EigenvectorDerivative(const SparseMatrix& K, const SparseMatrix& M,
                                      double lambda, const Eigen::VectorXd& phi,
                                      const SparseMatrix& dK, const SparseMatrix& dM) {
  return NelsonSolver(K, M, lambda, phi).Derivative(dK, dM).eigenvector;
}

}  // namespace femup
