#include "femup/solvers/extended_precision.h"

#include <Eigen/QR>
#include <cmath>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {

namespace {
const char kWhere[] = "extended precision least squares";
}  // namespace

Invalid ExtendedPrecisionOptions::Validate() const {
  if (!(relative_rank_tolerance >= 0 && relative_rank_tolerance < 1)) {
    std::ostringstream msg;
    msg << "must be in [0, 1), got " << relative_rank_tolerance;
    return {"relative_rank_tolerance", msg.str()};
  }
  return {};
}

ExtendedPrecisionSolution ExtendedPrecisionLeastSquares(
    const MatrixLD& a, const VectorLD& b, const ExtendedPrecisionOptions& options) {
  if (const Invalid bad = options.Validate()) throw InputError(kWhere, bad.ToString());
  const Eigen::Index m = a.rows(), n = a.cols();
  if (m == 0 || n == 0) throw InputError(kWhere, "A is empty");
  if (b.size() != m) {
    std::ostringstream msg;
    msg << "A is " << m << " x " << n << " but b has " << b.size() << " entries";
    throw InputError(kWhere, msg.str());
  }
  if (!a.allFinite() || !b.allFinite()) {
    throw InputError(kWhere, "A or b has a NaN or infinite entry");
  }

  VectorLD scale = VectorLD::Ones(n);
  if (options.scale_columns) {
    scale = a.colwise().norm().transpose();
    for (Eigen::Index j = 0; j < n; ++j) {
      if (scale[j] == 0) scale[j] = 1;
    }
  }
  const MatrixLD scaled = a * scale.cwiseInverse().asDiagonal();
  Eigen::ColPivHouseholderQR<MatrixLD> qr(m, n);
  if (options.relative_rank_tolerance > 0) {
    qr.setThreshold(static_cast<long double>(options.relative_rank_tolerance));
  }
  qr.compute(scaled);

  // Solve on the pivots rank() keeps (Eigen's own solve uses a different,
  // epsilon-based cut), so the answer and the reported rank agree.
  ExtendedPrecisionSolution solution;
  const auto rank = qr.rank();
  solution.rank = static_cast<int>(rank);
  VectorLD z = VectorLD::Zero(n);
  if (rank > 0) {
    const VectorLD c = qr.householderQ().adjoint() * b;
    const VectorLD y = qr.matrixR()
                           .topLeftCorner(rank, rank)
                           .template triangularView<Eigen::Upper>()
                           .solve(c.head(rank));
    for (Eigen::Index k = 0; k < rank; ++k) z[qr.colsPermutation().indices()[k]] = y[k];
    const long double r00 = std::fabs(qr.matrixR()(0, 0));
    solution.pivot_ratio =
        static_cast<double>(r00 / std::fabs(qr.matrixR()(rank - 1, rank - 1)));
  }
  solution.x = z.cwiseQuotient(scale);
  solution.residual = a * solution.x - b;

  std::ostringstream msg;
  if (rank == n) {
    msg << "QR in long double: full column rank (" << n << ")";
  } else {
    msg << "QR in long double: rank " << rank << " of " << n
        << " (pivots at or below the threshold " << qr.threshold()
        << " relative); the basic solution is zero on the dropped columns";
  }
  solution.message = msg.str();
  return solution;
}

}  // namespace femup
