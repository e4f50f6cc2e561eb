// Derivatives of one eigenpair of the symmetric pencil (K, M) with respect to a
// parameter p, given dK = dK/dp and dM = dM/dp: the eigenvalue derivative and
// the eigenvector derivative by Nelson's method (exact, no modal truncation),
// for a mass-normalised eigenvector of a distinct (non-repeated) eigenvalue.
// The eigenvector derivative keeps the mass normalisation: it is the derivative
// of phi(p) with phi' M phi = 1 for every p, and the sign of phi held fixed.
//
// An empty (0 x 0) dK or dM means zero (a parameter that does not enter K, or M).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/fe/model.h"

namespace femup {

// dlambda/dp = phi' (dK - lambda dM) phi, for phi with phi' M phi = 1.
// Throws InputError when sizes disagree.
double EigenvalueDerivative(const Eigen::VectorXd& phi, double lambda,
                            const SparseMatrix& dK, const SparseMatrix& dM);

// The same with dK and dM a correction factor's basis or nullptr (zero), in
// O(the basis's entries). Throws InputError when sizes disagree.
double EigenvalueDerivative(const Eigen::VectorXd& phi, double lambda,
                            const BasisMatrix* dK, const BasisMatrix* dM);

struct EigenpairDerivative {
  double eigenvalue = 0;        // dlambda/dp
  Eigen::VectorXd eigenvector;  // dphi/dp (num_dofs)
};

// Nelson's method for one eigenpair, factorising once for any number of
// parameters. The derivative v + c phi solves
//   (K - lambda M) v = -(dK - dlambda M - lambda dM) phi,   v_k = 0,
//   c = -phi' M v - 0.5 phi' dM phi,
// where k is the index of phi's largest-magnitude entry: K - lambda M with row
// and column k removed is non-singular (for a distinct eigenvalue) but
// indefinite. It is symmetric, so it is factorised as L D L' (Eigen's
// simplicial LDLT, AMD ordering: 5-10 times faster than LU on frames), which
// does not pivot: the factor is checked by solving for a known vector, and a
// normwise backward error above 1e-10 falls back to sparse LU with partial
// pivoting.
//
// A repeated (or numerically repeated) eigenvalue, as in a symmetric jacket's
// two sway modes, has no unique eigenvector: any M-orthonormal combination of
// its c eigenvectors is one. Given that eigenspace (`cluster`, n x c) and phi in
// it, the solver gives the derivative of phi's component outside the
// eigenspace (the multi-row extension of Nelson's method: c rows and columns
// removed where the cluster's rows are best conditioned, the right-hand side
// projected off the eigenspace) plus the normalisation term; the rotation
// within the eigenspace, which the eigenvalues alone do not fix, is left out
// (the caller chooses it, e.g. to fit measured shapes). With c = 1 this is
// Nelson's method as above.
// The solver keeps what it needs (the factor, phi, M phi); K and M may be
// destroyed after construction.
class NelsonSolver {
 public:
  // K, M: n x n symmetric, M positive definite; (lambda, phi) an eigenpair with
  // phi' M phi = 1. Throws InputError when sizes disagree, phi is not finite or
  // not mass-normalised (to 1e-6). A singular reduced matrix (a repeated
  // eigenvalue, or lambda not an eigenvalue) is not thrown: ok() is then false.
  NelsonSolver(const SparseMatrix& K, const SparseMatrix& M, double lambda,
               const Eigen::VectorXd& phi);
  // For phi in the eigenspace of lambda spanned by the columns of `cluster`
  // (n x c, M-orthonormal; c = 1 is the constructor above). Throws InputError
  // as above, and when cluster's size is wrong, it is not M-orthonormal (to
  // 1e-6), or phi is not in its span (to 1e-6).
  NelsonSolver(const SparseMatrix& K, const SparseMatrix& M, double lambda,
               const Eigen::VectorXd& phi, const Eigen::MatrixXd& cluster);

  // True when the reduced matrix was factorised; otherwise message() says why.
  bool ok() const { return message_.empty(); }
  const std::string& message() const { return message_; }
  // True when the reduced matrix is factorised by LU (L D L' was not accurate).
  bool uses_lu() const { return lu_ != nullptr; }
  int num_dofs() const { return static_cast<int>(phi_.size()); }

  // Derivatives for one parameter (dK, dM: n x n or empty). Throws InputError
  // when sizes disagree or the factorisation failed (!ok()).
  EigenpairDerivative Derivative(const SparseMatrix& dK, const SparseMatrix& dM) const;
  // The same with dK and dM a correction factor's basis or nullptr (zero): the
  // model's bases need not be expanded to n x n.
  EigenpairDerivative Derivative(const BasisMatrix* dK, const BasisMatrix* dM) const;

 private:
  // The derivative from dlambda, phi' dM phi and the right-hand side
  // f = -(dK - dlambda M - lambda dM) phi.
  EigenpairDerivative Solve(double dlambda, double phi_dm_phi,
                            const Eigen::VectorXd& f) const;

  double lambda_;
  Eigen::VectorXd phi_;
  Eigen::VectorXd mass_phi_;      // M phi
  Eigen::MatrixXd cluster_;       // the eigenspace (n x c)
  Eigen::MatrixXd mass_cluster_;  // M cluster
  std::vector<int> pivots_;       // the entries held at zero in v, ascending
  std::vector<int> reduced_;      // each DOF's index in the reduced matrix, or -1
  // The reduced matrix's factor: L D L' where it is accurate, else LU.
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  std::unique_ptr<Eigen::SparseLU<SparseMatrix>> lu_;
  std::string message_;
};

// dphi/dp for one parameter: a NelsonSolver used once. Throws InputError as the
// solver does, and also when the reduced matrix is singular (repeated eigenvalue).
Eigen::VectorXd EigenvectorDerivative(const SparseMatrix& K, const SparseMatrix& M,
                                      double lambda, const Eigen::VectorXd& phi,
                                      const SparseMatrix& dK, const SparseMatrix& dM);

}  // namespace femup
