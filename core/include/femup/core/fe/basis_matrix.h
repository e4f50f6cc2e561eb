// BasisMatrix: a correction factor's basis matrix (an element or substructure
// matrix placed in the model's n x n), held on the DOFs it touches.
//
// A model of n DOFs with p factors would hold p sparse n x n matrices, each with
// n + 1 column pointers however few entries it has: n p integers, quadratic in
// the model's size when the factors follow the elements (411 MB of pointers
// against 51 MB of entries for 1,000 factors at 10^5 DOF). Here a basis is the
// sorted list of the DOFs it touches, `dofs`, and a sparse local matrix on them,
// `local` (dofs.size() square): B(dofs[i], dofs[j]) = local(i, j), zero
// elsewhere. Memory and work grow with its entries, not with n.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace femup {

class BasisMatrix {
 public:
  using Sparse = Eigen::SparseMatrix<double>;

  BasisMatrix() = default;
  // From a square sparse matrix: keeps the rows and columns that have a stored
  // entry (its pattern's DOFs), so a symmetric matrix loses nothing. Implicit,
  // so that a builder's assembled n x n matrix can be assigned directly.
  BasisMatrix(const Sparse& full);  // NOLINT(google-explicit-constructor)
  // From a local matrix on `dofs` (distinct, each in [0, n), any order) in a
  // model of n DOFs; the DOFs are sorted and `local` permuted to match.
  // Throws InputError when local is not dofs.size() square or a DOF is out of
  // range or repeated.
  BasisMatrix(int n, std::vector<int> dofs, const Sparse& local);

  // From entries (row, col, value) of an n x n matrix, duplicates summed, in
  // O(t log t) for t entries (no O(n) work: a builder can make thousands of
  // bases of a large model). The entries must make a symmetric matrix for a
  // model's basis (ParametrisedModel::AddParameter checks). Throws InputError
  // when an index is outside [0, n).
  static BasisMatrix FromTriplets(
      int n, std::vector<Eigen::Triplet<double>>::const_iterator first,
      std::vector<Eigen::Triplet<double>>::const_iterator last);

  // Eigen 3.4's SparseMatrix copies when moved; these swap.
  BasisMatrix(BasisMatrix&& other) noexcept;
  BasisMatrix& operator=(BasisMatrix&& other) noexcept;
  BasisMatrix(const BasisMatrix&) = default;
  BasisMatrix& operator=(const BasisMatrix&) = default;

  int rows() const { return n_; }
  int cols() const { return n_; }
  // Stored entries (of `local`).
  Eigen::Index nonZeros() const { return local_.nonZeros(); }
  // The DOFs touched, ascending.
  const std::vector<int>& dofs() const { return dofs_; }
  // The matrix on those DOFs: local()(i, j) = B(dofs()[i], dofs()[j]); compressed.
  const Sparse& local() const { return local_; }
  // B as an n x n sparse matrix (O(n + entries): for small models and tests).
  Sparse ToSparse() const;
  // Rows dofs() of B X, for X with n rows: local() X(dofs(), :), so that the
  // product costs the basis's entries times X's columns.
  Eigen::MatrixXd RestrictedProduct(const Eigen::Ref<const Eigen::MatrixXd>& x) const;
  // x' B y for x and y with n entries, in O(entries).
  double Form(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const;
  // y += scale B x for x and y with n entries; touches y at dofs() only.
  void AddProductTo(double scale, const Eigen::VectorXd& x, Eigen::VectorXd* y) const;
  // Appends (dofs[i], dofs[j], scale local(i, j)) for every stored entry.
  void AppendTriplets(double scale, std::vector<Eigen::Triplet<double>>* out) const;

  void swap(BasisMatrix& other) noexcept;

 private:
  int n_ = 0;
  std::vector<int> dofs_;
  Sparse local_;
};

}  // namespace femup
