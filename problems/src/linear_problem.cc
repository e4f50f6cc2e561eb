#include "femup/problems/linear_problem.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cmath>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {

Invalid LinearProblem::Validate() const {
  // Checks of the whole problem: the message names what is wrong, the field stays empty.
  std::ostringstream msg;
  if (A.rows() != b.size()) {
    msg << "A has " << A.rows() << " rows but b has " << b.size() << " entries";
    return {"", msg.str()};
  }
  if (A.cols() == 0) return {"", "the problem has no unknown"};
  if (A.rows() == 0) return {"", "the problem has no equation"};
  if (!names.empty() && static_cast<Eigen::Index>(names.size()) != A.cols()) {
    msg << names.size() << " names for " << A.cols() << " unknowns";
    return {"", msg.str()};
  }
  if (!groups.empty() && static_cast<Eigen::Index>(groups.size()) != A.cols()) {
    msg << groups.size() << " groups for " << A.cols() << " unknowns";
    return {"", msg.str()};
  }
  if (!row_labels.empty() && static_cast<Eigen::Index>(row_labels.size()) != A.rows()) {
    msg << row_labels.size() << " row labels for " << A.rows() << " rows";
    return {"", msg.str()};
  }
  if (!A.allFinite()) return {"", "A has a NaN or infinite entry"};
  if (!b.allFinite()) return {"", "b has a NaN or infinite entry"};
  if (source_rows != 0 && source_rows < A.rows()) {
    msg << "source_rows is " << source_rows << "; expected 0 or at least A's " << A.rows()
        << " rows";
    return {"", msg.str()};
  }
  if (!(residual_offset >= 0) || !std::isfinite(residual_offset)) {
    msg << "residual_offset is " << residual_offset << "; expected finite and >= 0";
    return {"", msg.str()};
  }
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    const int i = fixed[k].first;
    if (i < 0 || i >= A.cols()) {
      msg << "fixed unknown index " << i << " is outside 0.." << A.cols() - 1;
      return {"", msg.str()};
    }
    if (!std::isfinite(fixed[k].second)) {
      msg << "fixed value of unknown " << (names.empty() ? std::to_string(i) : names[i])
          << " is not finite";
      return {"", msg.str()};
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (fixed[j].first == i) {
        msg << "unknown " << (names.empty() ? std::to_string(i) : names[i])
            << " is fixed twice";
        return {"", msg.str()};
      }
    }
  }
  if (static_cast<Eigen::Index>(fixed.size()) >= A.cols())
    return {"", "every unknown is fixed"};

  const Eigen::Index m = A.rows(), n = A.cols();
  auto label = [&](Eigen::Index i) {
    return names.empty() ? "unknown " + std::to_string(i) : names[i];
  };
  if (row_weights.size() > 0 && data_covariance.size() > 0)
    return {"", "give row_weights or data_covariance, not both"};
  if (row_weights.size() > 0) {
    if (row_weights.size() != m) {
      msg << row_weights.size() << " row weights for " << m << " rows";
      return {"", msg.str()};
    }
    for (Eigen::Index i = 0; i < m; ++i) {
      if (!(row_weights[i] > 0) || !std::isfinite(row_weights[i])) {
        msg << "row weight " << i << " is " << row_weights[i]
            << "; weights must be positive and finite";
        return {"", msg.str()};
      }
    }
  }
  if (data_covariance.size() > 0) {
    if (data_covariance.rows() != m || data_covariance.cols() != m) {
      msg << "data_covariance is " << data_covariance.rows() << " x "
          << data_covariance.cols() << "; expected " << m << " x " << m;
      return {"", msg.str()};
    }
    if (!data_covariance.allFinite())
      return {"", "data_covariance has a NaN or infinite entry"};
    const double asym =
        (data_covariance - data_covariance.transpose()).cwiseAbs().maxCoeff();
    if (asym > 1e-12 * data_covariance.cwiseAbs().maxCoeff())
      return {"", "data_covariance is not symmetric"};
    Eigen::LLT<Eigen::MatrixXd> llt(data_covariance);
    if (llt.info() != Eigen::Success)
      return {"", "data_covariance is not positive definite"};
  }
  for (const auto* bound : {&lower, &upper}) {
    const char* which = bound == &lower ? "lower" : "upper";
    if (bound->size() == 0) continue;
    if (bound->size() != n) {
      msg << which << " bounds have " << bound->size() << " entries for " << n
          << " unknowns";
      return {"", msg.str()};
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      if (std::isnan((*bound)[i])) {
        msg << which << " bound of " << label(i) << " is NaN";
        return {"", msg.str()};
      }
      if (std::isinf((*bound)[i]) && ((*bound)[i] > 0) == (bound == &lower)) {
        msg << which << " bound of " << label(i) << " is "
            << ((*bound)[i] > 0 ? "+" : "-")
            << "inf: no value satisfies it (a missing bound is "
            << (bound == &lower ? "-inf" : "+inf") << ")";
        return {"", msg.str()};
      }
    }
  }
  if (lower.size() > 0 && upper.size() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (lower[i] > upper[i]) {
        msg << "lower bound " << lower[i] << " of " << label(i)
            << " exceeds its upper bound " << upper[i];
        return {"", msg.str()};
      }
    }
  }
  for (const auto& [i, value] : fixed) {
    if ((lower.size() > 0 && value < lower[i]) ||
        (upper.size() > 0 && value > upper[i])) {
      msg << "fixed value " << value << " of " << label(i) << " is outside its bounds";
      return {"", msg.str()};
    }
  }
  if (equality_matrix.size() > 0 || equality_rhs.size() > 0) {
    if (equality_matrix.cols() != n) {
      msg << "equality matrix has " << equality_matrix.cols() << " columns for " << n
          << " unknowns";
      return {"", msg.str()};
    }
    if (equality_rhs.size() != equality_matrix.rows()) {
      msg << "equality matrix has " << equality_matrix.rows()
          << " rows but its right-hand side " << equality_rhs.size() << " entries";
      return {"", msg.str()};
    }
    if (!equality_matrix.allFinite() || !equality_rhs.allFinite())
      return {"", "the equalities have a NaN or infinite entry"};
    // Consistency on the free unknowns, fixed ones moved to the right.
    const std::vector<int> free = FreeUnknowns();
    Eigen::MatrixXd c(equality_matrix.rows(), free.size());
    for (std::size_t k = 0; k < free.size(); ++k) c.col(k) = equality_matrix.col(free[k]);
    Eigen::VectorXd d = equality_rhs;
    for (const auto& [i, value] : fixed) d -= equality_matrix.col(i) * value;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(c);
    cod.setThreshold(1e-12);
    const Eigen::VectorXd xp = cod.solve(d);
    const double violation = (c * xp - d).norm();
    if (violation > 1e-9 * (1.0 + d.norm())) {
      msg << "the equalities are inconsistent: no x satisfies C x = d (least violation "
          << violation << ")";
      return {"", msg.str()};
    }
    if (cod.rank() >= static_cast<Eigen::Index>(free.size()))
      return {"", "the equalities leave no free unknown"};
  }
  if (regulariser.size() > 0) {
    if (regulariser.cols() != n) {
      msg << "regulariser has " << regulariser.cols() << " columns for " << n
          << " unknowns";
      return {"", msg.str()};
    }
    if (!regulariser.allFinite()) return {"", "regulariser has a NaN or infinite entry"};
  }
  if (prior.size() > 0) {
    if (prior.size() != n) {
      msg << "prior has " << prior.size() << " entries for " << n << " unknowns";
      return {"", msg.str()};
    }
    if (!prior.allFinite()) return {"", "prior has a NaN or infinite entry"};
  }
  return {};
}

bool LinearProblem::has_bounds() const {
  for (int i = 0; i < num_unknowns(); ++i) {
    if (IsFixed(i)) continue;
    if (lower.size() > 0 && std::isfinite(lower[i])) return true;
    if (upper.size() > 0 && std::isfinite(upper[i])) return true;
  }
  return false;
}

int LinearProblem::IndexOf(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

WeightedSystem Weighted(const LinearProblem& problem) {
  WeightedSystem out;
  if (problem.row_weights.size() > 0) {
    out.A = problem.row_weights.asDiagonal() * problem.A;
    out.b = problem.row_weights.cwiseProduct(problem.b);
  } else if (problem.data_covariance.size() > 0) {
    const Eigen::LLT<Eigen::MatrixXd> llt(problem.data_covariance);
    out.A = llt.matrixL().solve(problem.A);
    out.b = llt.matrixL().solve(problem.b);
  } else {
    out.A = problem.A;
    out.b = problem.b;
  }
  return out;
}

Eigen::MatrixXd DifferenceOperator(int n, int order,
                                   const std::vector<std::string>& groups) {
  if (n < 1) throw InputError("regulariser", "needs at least one unknown");
  if (order < 0 || order > 2)
    throw InputError("regulariser",
                     "difference order must be 0, 1 or 2, got " + std::to_string(order));
  if (!groups.empty() && static_cast<int>(groups.size()) != n)
    throw InputError("regulariser", std::to_string(groups.size()) + " group labels for " +
                                        std::to_string(n) + " unknowns");
  if (order == 0) return Eigen::MatrixXd::Identity(n, n);
  auto same = [&](int i, int j) { return groups.empty() || groups[i] == groups[j]; };
  std::vector<Eigen::RowVectorXd> rows;
  for (int i = 0; i + order < n; ++i) {
    bool ok = true;
    for (int k = 1; k <= order; ++k) ok = ok && same(i, i + k);
    if (!ok) continue;
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
    if (order == 1) {
      row[i] = -1;
      row[i + 1] = 1;
    } else {
      row[i] = 1;
      row[i + 1] = -2;
      row[i + 2] = 1;
    }
    rows.push_back(row);
  }
  if (rows.empty())
    throw InputError("regulariser",
                     "no " + std::to_string(order + 1) +
                         " neighbouring unknowns of one group to difference");
  Eigen::MatrixXd l(rows.size(), n);
  for (std::size_t r = 0; r < rows.size(); ++r) l.row(r) = rows[r];
  return l;
}

void LinearProblem::Fix(const std::string& name, double value) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) {
      fixed.emplace_back(static_cast<int>(i), value);
      return;
    }
  }
  std::string known;
  for (std::size_t i = 0; i < names.size(); ++i) known += (i ? ", " : "") + names[i];
  throw InputError("fix",
                   "no parameter is called '" + name + "' (parameters: " + known + ")");
}

bool LinearProblem::IsFixed(int index) const {
  for (const auto& f : fixed) {
    if (f.first == index) return true;
  }
  return false;
}

std::vector<int> LinearProblem::FreeUnknowns() const {
  std::vector<int> out;
  for (int i = 0; i < num_unknowns(); ++i) {
    if (!IsFixed(i)) out.push_back(i);
  }
  return out;
}

}  // namespace femup
