#include "femup/solvers/identifiability.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {
namespace {

std::string NameOf(const std::vector<std::string>& names, int i) {
  return i < static_cast<int>(names.size()) ? names[i] : "x" + std::to_string(i + 1);
}

std::string GroupOf(const std::vector<std::string>& groups, int i) {
  return i < static_cast<int>(groups.size()) ? groups[i] : "";
}

// "0.31 mass[1] + 0.30 mass[2] - 0.02 stiffness[3] (+ 4 terms below 0.01)".
std::string Combination(const Eigen::VectorXd& v, const std::vector<std::string>& names) {
  std::vector<int> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return std::abs(v[a]) > std::abs(v[b]); });
  std::ostringstream out;
  out << std::fixed << std::setprecision(3);
  int shown = 0, hidden = 0;
  for (int i : order) {
    if (std::abs(v[i]) < 0.01 || shown >= 12) {
      if (v[i] != 0) ++hidden;
      continue;
    }
    out << (shown == 0 ? (v[i] < 0 ? "-" : "") : (v[i] < 0 ? " - " : " + "))
        << std::abs(v[i]) << " " << NameOf(names, i);
    ++shown;
  }
  if (hidden > 0) out << " (+ " << hidden << " smaller terms)";
  return out.str();
}

NullDirection Describe(Eigen::VectorXd v, double sigma,
                       const std::vector<std::string>& names,
                       const std::vector<std::string>& groups) {
  v.normalize();
  Eigen::Index imax = 0;
  const double vmax = v.cwiseAbs().maxCoeff(&imax);
  if (v[imax] < 0) v = -v;
  NullDirection d;
  d.coefficients = v;
  d.singular_value = sigma;
  d.best_to_fix = NameOf(names, static_cast<int>(imax));

  bool has_mass = false, has_stiffness = false, all_same_sign = true, added = false;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    const std::string g = GroupOf(groups, static_cast<int>(i));
    const bool significant = std::abs(v[i]) >= 0.05 * vmax;
    if (g == "mass" || g == "stiffness") {
      (g == "mass" ? has_mass : has_stiffness) = true;
      if (!significant || v[i] < 0) all_same_sign = false;
    } else if (g == "added_mass" && significant) {
      added = true;
      if (v[i] < 0) all_same_sign = false;
    }
  }
  d.common_scaling = has_mass && has_stiffness && all_same_sign;
  std::ostringstream text;
  if (d.common_scaling) {
    text << "common scaling: all mass and stiffness factors"
         << (added ? " and the added-mass factors" : "")
         << " move together. K and M scaled by one number leave every eigenvalue and "
            "mode shape unchanged, so measured modes cannot fix the overall scale. "
            "Fix one factor to a known value (best conditioned: "
         << d.best_to_fix << "), or measure mass-normalised modes. Direction: ";
  } else {
    text << "the data cannot separate the combination ";
  }
  text << Combination(v, names);
  d.description = text.str();
  return d;
}

}  // namespace

namespace {

void CheckInput(const Eigen::MatrixXd& a, double relative_tolerance) {
  if (a.cols() == 0) throw InputError("identifiability", "the matrix has no column");
  if (!a.allFinite())
    throw InputError("identifiability", "the matrix has a NaN or Inf entry");
  if (!(relative_tolerance > 0) || !(relative_tolerance < 1)) {
    throw InputError("identifiability", "relative tolerance must be in (0, 1)");
  }
}

// The analysis from the column-scaled matrix's singular values `s` (up to n,
// descending) and the right singular vectors of the smallest ones: `trailing`
// (n x t) holds those of singular values n - t, ..., n - 1. A negative
// `unscaled_condition` is computed here from A's own singular values.
Identifiability FromSpectrum(const Eigen::MatrixXd& a, const Eigen::VectorXd& s,
                             const Eigen::MatrixXd& trailing, double unscaled_condition,
                             const std::vector<std::string>& names,
                             const std::vector<std::string>& groups,
                             double relative_tolerance, bool scale_columns) {
  const Eigen::Index n = a.cols();
  const Eigen::Index first = n - trailing.cols();  // singular value of trailing.col(0)
  Identifiability out;
  for (Eigen::Index j = 0; j < n; ++j) {
    if (a.col(j).squaredNorm() == 0) {
      out.unseen.push_back(NameOf(names, static_cast<int>(j)));
      out.warnings.push_back(NameOf(names, static_cast<int>(j)) +
                             " appears in no equation (its column is zero): no "
                             "measurement is sensitive to it");
    }
  }
  const Eigen::VectorXd scale = IdentifiabilityScale(a, scale_columns);
  // Singular values of an m < n matrix: pad with zeros to n.
  out.singular_values = Eigen::VectorXd::Zero(n);
  out.singular_values.head(s.size()) = s;
  const double smax = out.singular_values.maxCoeff();
  out.tolerance = relative_tolerance * smax;
  out.rank = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (out.singular_values[i] > out.tolerance) ++out.rank;
  }
  const double smin = out.singular_values[n - 1];
  // Infinite when the matrix is rank deficient at the tolerance: a ratio like
  // 1e17 from rounding noise would be a number nobody should quote.
  out.condition_number =
      (smin > 0 && out.rank == n) ? smax / smin : std::numeric_limits<double>::infinity();
  out.condition_number_in_rank = out.rank > 0 ? smax / out.singular_values[out.rank - 1]
                                              : std::numeric_limits<double>::infinity();
  if (unscaled_condition >= 0) {
    out.condition_number_unscaled = unscaled_condition;
  } else {
    const Eigen::VectorXd raw = Eigen::BDCSVD<Eigen::MatrixXd>(a).singularValues();
    const double raw_min = a.cols() > a.rows() ? 0.0 : raw[raw.size() - 1];
    out.condition_number_unscaled =
        raw_min > 0 ? raw[0] / raw_min : std::numeric_limits<double>::infinity();
  }
  const bool weakest_needed = out.rank == n && out.condition_number > 1e8;
  if (first > std::min<Eigen::Index>(out.rank, weakest_needed ? n - 1 : n)) {
    throw InputError(
        "identifiability",
        "the singular vectors given stop at value " + std::to_string(first) +
            "; the analysis needs them from value " +
            std::to_string(std::min<Eigen::Index>(out.rank, weakest_needed ? n - 1 : n)));
  }
  for (Eigen::Index k = out.rank; k < n; ++k) {
    // Back to the unknowns' own units: x = S^-1 x_scaled.
    const Eigen::VectorXd dir =
        scale.cwiseInverse().asDiagonal() * trailing.col(k - first);
    out.null_directions.push_back(Describe(dir, out.singular_values[k], names, groups));
  }
  if (out.rank < n) {
    std::ostringstream w;
    w << "rank " << out.rank << " of " << n << " unknowns: " << n - out.rank
      << " direction(s) are not determined by the data";
    out.warnings.push_back(w.str());
  } else if (weakest_needed) {
    std::ostringstream w;
    w << "full rank but ill-conditioned (condition number " << std::setprecision(3)
      << out.condition_number << "); weakest direction: "
      << Describe(scale.cwiseInverse().asDiagonal() * trailing.col(n - 1 - first), smin,
                  names, groups)
             .description;
    out.warnings.push_back(w.str());
  }
  return out;
}

}  // namespace

Eigen::VectorXd IdentifiabilityScale(const Eigen::MatrixXd& a, bool scale_columns) {
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(a.cols());
  if (!scale_columns) return scale;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    const double norm = a.col(j).norm();
    if (norm > 0) scale[j] = norm;
  }
  return scale;
}

Identifiability AnalyseIdentifiability(const Eigen::MatrixXd& a,
                                       const std::vector<std::string>& names,
                                       const std::vector<std::string>& groups,
                                       double relative_tolerance, bool scale_columns) {
  CheckInput(a, relative_tolerance);
  const Eigen::VectorXd scale = IdentifiabilityScale(a, scale_columns);
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(a * scale.cwiseInverse().asDiagonal(),
                                           Eigen::ComputeFullV);
  return FromSpectrum(a, svd.singularValues(), svd.matrixV(), -1, names, groups,
                      relative_tolerance, scale_columns);
}

Identifiability AnalyseIdentifiability(const Eigen::MatrixXd& a,
                                       const Eigen::BDCSVD<Eigen::MatrixXd>& scaled_svd,
                                       const std::vector<std::string>& names,
                                       const std::vector<std::string>& groups,
                                       double relative_tolerance, bool scale_columns) {
  CheckInput(a, relative_tolerance);
  if (!scaled_svd.computeV() || scaled_svd.matrixV().rows() != a.cols() ||
      scaled_svd.matrixV().cols() != a.cols()) {
    throw InputError("identifiability",
                     "the SVD given does not hold all of V for the matrix's " +
                         std::to_string(a.cols()) + " columns");
  }
  return FromSpectrum(a, scaled_svd.singularValues(), scaled_svd.matrixV(), -1, names,
                      groups, relative_tolerance, scale_columns);
}

Identifiability AnalyseIdentifiability(const Eigen::MatrixXd& a,
                                       const Eigen::VectorXd& singular_values,
                                       const Eigen::MatrixXd& trailing_vectors,
                                       double condition_number_unscaled,
                                       const std::vector<std::string>& names,
                                       const std::vector<std::string>& groups,
                                       double relative_tolerance, bool scale_columns) {
  CheckInput(a, relative_tolerance);
  if (singular_values.size() > a.cols() || trailing_vectors.rows() != a.cols() ||
      trailing_vectors.cols() > a.cols()) {
    throw InputError("identifiability",
                     "the spectrum given does not fit the matrix's " +
                         std::to_string(a.cols()) + " columns (" +
                         std::to_string(singular_values.size()) + " singular values, " +
                         std::to_string(trailing_vectors.rows()) + " x " +
                         std::to_string(trailing_vectors.cols()) + " vectors)");
  }
  if (!(condition_number_unscaled >= 0)) {
    throw InputError("identifiability",
                     "the unscaled condition number must be >= 0 (inf allowed)");
  }
  return FromSpectrum(a, singular_values, trailing_vectors, condition_number_unscaled,
                      names, groups, relative_tolerance, scale_columns);
}

}  // namespace femup
