// BuildRitzBasis: the lowest modes of a pencil at a point and their static
// corrections for its unknowns, made M-orthonormal (ritz_basis.h).
#include "femup/problems/ritz_basis.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "femup/core/errors.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/linalg/sparse_cholesky.h"
#include "femup/problems/eigen_sensitivity.h"

namespace femup {

std::shared_ptr<const RitzBasis> BuildRitzBasis(const ParametrisedPencil& pencil,
                                                const std::vector<ModalData>& states,
                                                const EigenSensitivityOptions& options,
                                                const Eigen::VectorXd& x0) {
  if (const Invalid bad = options.Validate())
    throw InputError("eigen sensitivity options", bad.ToString());
  const int n = pencil.num_dofs();
  const int num_parameters = pencil.num_parameters();
  if (states.empty()) throw InputError("states", "no measured state is given");
  if (x0.size() != num_parameters || !x0.allFinite()) {
    throw InputError("start", "has " + std::to_string(x0.size()) +
                                  " entries or a NaN; expected " +
                                  std::to_string(num_parameters) + " finite ones");
  }
  auto basis = std::make_shared<RitzBasis>();
  for (const bool wet : {false, true}) {
    int paired = 0;  // the most modes a state of this immersion pairs
    for (std::size_t i = 0; i < states.size(); ++i) {
      if ((states[i].immersion == Immersion::kWet) != wet) continue;
      states[i].Validate(n, "states." + std::to_string(i + 1));
      paired = std::max(paired, std::min(n, states[i].num_modes() + options.extra_modes));
    }
    if (paired == 0) continue;
    SparseMatrix k, m;
    pencil.Assemble(x0, wet, &k, &m);
    EigenOptions eigen = options.eigen;
    eigen.num_modes = paired + options.extra_modes;
    if (eigen.num_modes >= n) {  // the whole space: every mode, densely
      eigen.method = EigenOptions::Method::kDense;
      eigen.num_modes = n;
    }
    const Modes modes = SolveModes(k, m, eigen);
    PencilDerivatives derivatives;
    pencil.Derivatives(x0, wet, &derivatives);

    // Static corrections of the paired modes, by one factorisation of
    // K - sigma M, positive definite for sigma below the lowest eigenvalue.
    const double top = std::max(modes.eigenvalues.cwiseAbs().maxCoeff(), 1e-300);
    const double sigma = -0.5 * std::max(modes.eigenvalues[0], 1e-3 * top);
    std::vector<Eigen::VectorXd> loads;
    const int corrected = std::min(paired, modes.size());
    for (int i = 0; i < corrected; ++i) {
      const Eigen::VectorXd phi = modes.shapes.col(i);
      for (int p = 0; p < num_parameters; ++p) {
        for (const BasisMatrix* b : {derivatives.stiffness[p], derivatives.mass[p]}) {
          if (b == nullptr) continue;
          Eigen::VectorXd load = Eigen::VectorXd::Zero(n);
          b->AddProductTo(1.0, phi, &load);
          if (load.squaredNorm() > 0) loads.push_back(std::move(load));
        }
      }
    }
    Eigen::MatrixXd columns(n, modes.size() + static_cast<Eigen::Index>(loads.size()));
    columns.leftCols(modes.size()) = modes.shapes;
    if (!loads.empty()) {
      Eigen::MatrixXd rhs(n, static_cast<Eigen::Index>(loads.size()));
      for (std::size_t j = 0; j < loads.size(); ++j)
        rhs.col(static_cast<Eigen::Index>(j)) = loads[j];
      const SparseMatrix shifted = k - sigma * m;
      SparseCholeskyOptions chol;
      chol.name = std::string(wet ? "wet" : "dry") + " K - sigma M at the basis point";
      columns.rightCols(rhs.cols()) = SparseCholesky(shifted, chol).Solve(rhs);
    }
    // M-orthonormal columns: each to unit M-norm, then the Gram matrix's
    // eigenvectors; directions of relative norm below 1e-6 are dropped.
    Eigen::MatrixXd mass_columns = m.selfadjointView<Eigen::Lower>() * columns;
    for (Eigen::Index j = 0; j < columns.cols(); ++j) {
      const double norm2 = columns.col(j).dot(mass_columns.col(j));
      if (!(norm2 > 0) || !std::isfinite(norm2)) {
        throw InputError("ritz basis", "a basis vector has M-norm " +
                                           std::to_string(norm2) +
                                           "; the mass matrix is not positive definite");
      }
      columns.col(j) /= std::sqrt(norm2);
      mass_columns.col(j) /= std::sqrt(norm2);
    }
    Eigen::MatrixXd gram = columns.transpose() * mass_columns;
    gram = (0.5 * (gram + gram.transpose())).eval();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(gram);
    const Eigen::VectorXd& s = eig.eigenvalues();  // ascending
    const double keep_above = 1e-12 * s.maxCoeff();
    Eigen::Index first = 0;
    while (first < s.size() && !(s[first] > keep_above)) ++first;
    const Eigen::Index r = s.size() - first;
    const Eigen::MatrixXd scale = eig.eigenvectors().rightCols(r) *
                                  s.tail(r).cwiseSqrt().cwiseInverse().asDiagonal();
    (wet ? basis->wet : basis->dry) = columns * scale;
    (wet ? basis->mass_times_wet : basis->mass_times_dry) = mass_columns * scale;
  }
  return basis;
}

}  // namespace femup
