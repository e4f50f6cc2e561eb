#include "femup/core/fe/basis_matrix.h"

#include <algorithm>
#include <numeric>
#include <sstream>
#include <utility>

#include "femup/core/errors.h"

namespace femup {
namespace {

// The k x k compressed matrix with entry (index[i], index[j]) = a(i, j) for
// every stored entry of a (duplicates summed).
BasisMatrix::Sparse Renumbered(const BasisMatrix::Sparse& a,
                               const std::vector<int>& index, Eigen::Index k) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(a.nonZeros()));
  for (Eigen::Index c = 0; c < a.outerSize(); ++c) {
    for (BasisMatrix::Sparse::InnerIterator it(a, c); it; ++it) {
      t.emplace_back(index[static_cast<std::size_t>(it.row())],
                     index[static_cast<std::size_t>(it.col())], it.value());
    }
  }
  BasisMatrix::Sparse out(k, k);
  out.setFromTriplets(t.begin(), t.end());
  out.makeCompressed();
  return out;
}

void CheckLength(const Eigen::VectorXd& v, int n, const char* what) {
  if (v.size() != n) {
    std::ostringstream msg;
    msg << what << " has " << v.size() << " entries, expected " << n;
    throw InputError("basis matrix", msg.str());
  }
}

}  // namespace

BasisMatrix::BasisMatrix(const Sparse& full) : n_(static_cast<int>(full.rows())) {
  if (full.rows() != full.cols()) {
    std::ostringstream msg;
    msg << "is " << full.rows() << " x " << full.cols() << ", expected a square matrix";
    throw InputError("basis matrix", msg.str());
  }
  // The DOFs of the pattern: every row and column with a stored entry.
  std::vector<int> local_of(static_cast<std::size_t>(n_), -1);
  for (Eigen::Index c = 0; c < full.outerSize(); ++c) {
    for (Sparse::InnerIterator it(full, c); it; ++it) {
      local_of[static_cast<std::size_t>(it.row())] = 0;
      local_of[static_cast<std::size_t>(it.col())] = 0;
    }
  }
  for (int d = 0; d < n_; ++d) {
    if (local_of[static_cast<std::size_t>(d)] == 0) {
      local_of[static_cast<std::size_t>(d)] = static_cast<int>(dofs_.size());
      dofs_.push_back(d);
    }
  }
  local_ = Renumbered(full, local_of, static_cast<Eigen::Index>(dofs_.size()));
}

BasisMatrix::BasisMatrix(int n, std::vector<int> dofs, const Sparse& local)
    : n_(n), dofs_(std::move(dofs)) {
  const auto k = static_cast<Eigen::Index>(dofs_.size());
  if (n < 0) throw InputError("basis matrix", "has a negative number of DOFs");
  if (local.rows() != k || local.cols() != k) {
    std::ostringstream msg;
    msg << "local matrix is " << local.rows() << " x " << local.cols() << ", expected "
        << k << " x " << k << " (one row and column per DOF listed)";
    throw InputError("basis matrix", msg.str());
  }
  for (int d : dofs_) {
    if (d < 0 || d >= n) {
      std::ostringstream msg;
      msg << "DOF " << d << " is outside [0, " << n << ")";
      throw InputError("basis matrix", msg.str());
    }
  }
  // Sort the DOFs and permute the local matrix alike.
  std::vector<int> order(dofs_.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return dofs_[a] < dofs_[b]; });
  std::vector<int> rank(dofs_.size());
  std::vector<int> sorted(dofs_.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    rank[static_cast<std::size_t>(order[i])] = static_cast<int>(i);
    sorted[i] = dofs_[static_cast<std::size_t>(order[i])];
    if (i > 0 && sorted[i] == sorted[i - 1]) {
      std::ostringstream msg;
      msg << "DOF " << sorted[i] << " is listed twice";
      throw InputError("basis matrix", msg.str());
    }
  }
  dofs_.swap(sorted);
  local_ = Renumbered(local, rank, k);
}

BasisMatrix BasisMatrix::FromTriplets(
    int n, std::vector<Eigen::Triplet<double>>::const_iterator first,
    std::vector<Eigen::Triplet<double>>::const_iterator last) {
  BasisMatrix b;
  b.n_ = n;
  for (auto it = first; it != last; ++it) {
    if (it->row() < 0 || it->row() >= n || it->col() < 0 || it->col() >= n) {
      std::ostringstream msg;
      msg << "entry (" << it->row() << ", " << it->col() << ") is outside a " << n
          << " x " << n << " matrix";
      throw InputError("basis matrix", msg.str());
    }
    b.dofs_.push_back(static_cast<int>(it->row()));
    b.dofs_.push_back(static_cast<int>(it->col()));
  }
  std::sort(b.dofs_.begin(), b.dofs_.end());
  b.dofs_.erase(std::unique(b.dofs_.begin(), b.dofs_.end()), b.dofs_.end());
  const auto local_of = [&](Eigen::Index d) {
    return static_cast<int>(
        std::lower_bound(b.dofs_.begin(), b.dofs_.end(), static_cast<int>(d)) -
        b.dofs_.begin());
  };
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(last - first));
  for (auto it = first; it != last; ++it)
    t.emplace_back(local_of(it->row()), local_of(it->col()), it->value());
  const auto k = static_cast<Eigen::Index>(b.dofs_.size());
  b.local_.resize(k, k);
  b.local_.setFromTriplets(t.begin(), t.end());
  b.local_.makeCompressed();
  return b;
}

BasisMatrix::BasisMatrix(BasisMatrix&& other) noexcept { swap(other); }

BasisMatrix& BasisMatrix::operator=(BasisMatrix&& other) noexcept {
  if (this != &other) {
    BasisMatrix empty;
    swap(empty);
    swap(other);
  }
  return *this;
}

void BasisMatrix::swap(BasisMatrix& other) noexcept {
  std::swap(n_, other.n_);
  dofs_.swap(other.dofs_);
  local_.swap(other.local_);
}

BasisMatrix::Sparse BasisMatrix::ToSparse() const {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(local_.nonZeros()));
  AppendTriplets(1.0, &t);
  Sparse full(n_, n_);
  full.setFromTriplets(t.begin(), t.end());
  full.makeCompressed();
  return full;
}

Eigen::MatrixXd BasisMatrix::RestrictedProduct(
    const Eigen::Ref<const Eigen::MatrixXd>& x) const {
  if (x.rows() != n_) {
    std::ostringstream msg;
    msg << "product with a matrix of " << x.rows() << " rows, expected " << n_;
    throw InputError("basis matrix", msg.str());
  }
  const Eigen::MatrixXd rows = x(dofs_, Eigen::all);
  return local_ * rows;
}

double BasisMatrix::Form(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const {
  CheckLength(x, n_, "form: x");
  CheckLength(y, n_, "form: y");
  const Eigen::VectorXd xl = x(dofs_), yl = y(dofs_);
  return xl.dot(local_ * yl);
}

void BasisMatrix::AddProductTo(double scale, const Eigen::VectorXd& x,
                               Eigen::VectorXd* y) const {
  CheckLength(x, n_, "product: x");
  CheckLength(*y, n_, "product: y");
  const Eigen::VectorXd xl = x(dofs_);
  const Eigen::VectorXd product = local_ * xl;
  for (std::size_t i = 0; i < dofs_.size(); ++i)
    (*y)[dofs_[i]] += scale * product[static_cast<Eigen::Index>(i)];
}

void BasisMatrix::AppendTriplets(double scale,
                                 std::vector<Eigen::Triplet<double>>* out) const {
  for (Eigen::Index c = 0; c < local_.outerSize(); ++c) {
    for (Sparse::InnerIterator it(local_, c); it; ++it) {
      out->emplace_back(dofs_[static_cast<std::size_t>(it.row())],
                        dofs_[static_cast<std::size_t>(c)], scale * it.value());
    }
  }
}

}  // namespace femup
