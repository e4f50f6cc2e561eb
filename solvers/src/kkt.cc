#include "femup/solvers/kkt.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace femup {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string IndexList(const std::vector<int>& indices) {
  std::ostringstream out;
  out << "[";
  for (std::size_t k = 0; k < indices.size(); ++k) out << (k ? ", " : "") << indices[k];
  out << "]";
  return out.str();
}

}  // namespace

double KktReport::residual() const {
  if (std::isnan(stationarity) || std::isnan(sign) || std::isnan(feasibility)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return std::max({stationarity, sign, feasibility});
}

std::string KktReport::Describe() const {
  std::ostringstream out;
  out << "KKT residual " << residual() << " (stationarity " << stationarity << ", sign "
      << sign << ", feasibility " << feasibility << "); active lower bounds "
      << IndexList(active_lower) << ", active upper bounds " << IndexList(active_upper);
  return out.str();
}

KktReport CheckKkt(const Eigen::VectorXd& x, const Eigen::VectorXd& gradient,
                   const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                   const Eigen::MatrixXd& equality_matrix,
                   const Eigen::VectorXd& equality_rhs,
                   const std::vector<std::pair<int, double>>& fixed, double scale,
                   double active_tolerance) {
  const auto n = x.size();
  const auto q = equality_matrix.rows();
  const double s = scale > 0 ? scale : 1.0;
  KktReport report;
  report.bound_multipliers = Eigen::VectorXd::Zero(n);
  report.equality_multipliers = Eigen::VectorXd::Zero(q);

  std::vector<bool> is_fixed(n, false);
  for (const auto& [i, v] : fixed) {
    if (i < 0 || i >= n) continue;
    is_fixed[i] = true;
    report.feasibility = std::max(report.feasibility, std::abs(x[i] - v));
  }
  if (q > 0) {
    report.feasibility = std::max(
        report.feasibility, (equality_matrix * x - equality_rhs).cwiseAbs().maxCoeff());
  }

  // Classify the free unknowns: on a bound (within the tolerance) or inside.
  std::vector<int> inactive;
  std::vector<bool> at_lower(n, false), at_upper(n, false);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double lo = lower.size() == n ? lower[i] : -kInf;
    const double hi = upper.size() == n ? upper[i] : kInf;
    report.feasibility = std::max({report.feasibility, lo - x[i], x[i] - hi});
    if (is_fixed[i]) continue;
    at_lower[i] =
        std::isfinite(lo) && x[i] - lo <= active_tolerance * std::max(1.0, std::abs(lo));
    at_upper[i] =
        std::isfinite(hi) && hi - x[i] <= active_tolerance * std::max(1.0, std::abs(hi));
    if (!at_lower[i] && !at_upper[i]) inactive.push_back(static_cast<int>(i));
  }
  if (!x.allFinite()) report.feasibility = std::numeric_limits<double>::quiet_NaN();

  // Equality multipliers: g = C' mu on the free unknowns off their bounds, in the
  // least-squares sense (minimum norm when these columns do not determine mu).
  if (q > 0 && !inactive.empty()) {
    Eigen::MatrixXd ct(inactive.size(), q);
    Eigen::VectorXd g(inactive.size());
    for (std::size_t k = 0; k < inactive.size(); ++k) {
      ct.row(k) = equality_matrix.col(inactive[k]).transpose();
      g[k] = gradient[inactive[k]];
    }
    report.equality_multipliers =
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(ct).solve(g);
  }
  const Eigen::VectorXd reduced =
      q > 0 ? Eigen::VectorXd(gradient -
                              equality_matrix.transpose() * report.equality_multipliers)
            : gradient;

  double stationarity = 0;
  for (int i : inactive) stationarity = std::max(stationarity, std::abs(reduced[i]));
  if (!reduced.allFinite()) stationarity = std::numeric_limits<double>::quiet_NaN();

  // Bound multipliers take up what is left at active bounds: z >= 0 at a lower
  // bound, z <= 0 at an upper one (both signs when lower = upper).
  double wrong_sign = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!at_lower[i] && !at_upper[i]) continue;
    const double z = reduced[i];
    report.bound_multipliers[i] = z;
    const int index = static_cast<int>(i);
    if (at_lower[i] && at_upper[i]) {
      (z >= 0 ? report.active_lower : report.active_upper).push_back(index);
    } else if (at_lower[i]) {
      report.active_lower.push_back(index);
      wrong_sign = std::max(wrong_sign, -z);
    } else {
      report.active_upper.push_back(index);
      wrong_sign = std::max(wrong_sign, z);
    }
  }
  report.stationarity = stationarity / s;
  report.sign = wrong_sign / s;
  return report;
}

}  // namespace femup
