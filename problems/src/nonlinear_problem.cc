#include "femup/problems/nonlinear_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {

namespace {

// "x1" when the problem names its parameters, else "parameter 0".
std::string ParameterName(const NonlinearProblem& problem, int index) {
  if (index >= 0 && index < static_cast<int>(problem.names.size())) {
    return problem.names[index];
  }
  return "parameter " + std::to_string(index);
}

}  // namespace

bool NonlinearProblem::has_bounds() const {
  for (int i = 0; i < num_parameters(); ++i) {
    if (IsFixed(i)) continue;
    if (i < lower.size() && std::isfinite(lower[i])) return true;
    if (i < upper.size() && std::isfinite(upper[i])) return true;
  }
  return false;
}

bool NonlinearProblem::IsFixed(int index) const {
  for (const auto& f : fixed) {
    if (f.first == index) return true;
  }
  return false;
}

std::vector<int> NonlinearProblem::FreeUnknowns() const {
  std::vector<int> out;
  for (int i = 0; i < num_parameters(); ++i) {
    if (!IsFixed(i)) out.push_back(i);
  }
  return out;
}

Invalid NonlinearProblem::Validate() const {
  // Checks of the whole problem: the message names what is wrong, the field stays empty.
  const int n = num_parameters();
  std::ostringstream msg;
  if (n == 0) return {"", "the problem has no parameter (initial is empty)"};
  if (num_residuals <= 0) {
    msg << "num_residuals must be positive, got " << num_residuals;
    return {"", msg.str()};
  }
  if (!evaluate) return {"", "no evaluate function"};
  if (!names.empty() && static_cast<int>(names.size()) != n) {
    msg << names.size() << " names for " << n << " parameters";
    return {"", msg.str()};
  }
  if (!groups.empty() && static_cast<int>(groups.size()) != n) {
    msg << groups.size() << " groups for " << n << " parameters";
    return {"", msg.str()};
  }
  if (!residual_labels.empty() &&
      static_cast<int>(residual_labels.size()) != num_residuals) {
    msg << residual_labels.size() << " residual labels for " << num_residuals
        << " residuals";
    return {"", msg.str()};
  }
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    const int i = fixed[k].first;
    if (i < 0 || i >= n) {
      msg << "fixed parameter index " << i << " is outside 0.." << n - 1;
      return {"", msg.str()};
    }
    if (!std::isfinite(fixed[k].second)) {
      msg << "fixed value of " << ParameterName(*this, i) << " is not finite";
      return {"", msg.str()};
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (fixed[j].first == i) {
        msg << ParameterName(*this, i) << " is fixed twice";
        return {"", msg.str()};
      }
    }
  }
  if (static_cast<int>(fixed.size()) >= n) return {"", "every parameter is fixed"};
  for (int i = 0; i < n; ++i) {
    if (!IsFixed(i) && !std::isfinite(initial[i])) {
      msg << "the start of " << ParameterName(*this, i) << " is " << initial[i];
      return {"", msg.str()};
    }
  }
  if ((lower.size() != 0 && lower.size() != n) ||
      (upper.size() != 0 && upper.size() != n)) {
    msg << "bounds have " << lower.size() << " lower and " << upper.size()
        << " upper entries for " << n << " parameters (each must be " << n
        << " or empty)";
    return {"", msg.str()};
  }
  // Bounds may be infinite but not NaN; a fixed value and the start of a free
  // parameter must lie within them.
  std::vector<double> fixed_value(n, std::numeric_limits<double>::quiet_NaN());
  for (const auto& [i, v] : fixed) fixed_value[i] = v;
  for (int i = 0; i < n; ++i) {
    const double lo = lower.size() ? lower[i] : -std::numeric_limits<double>::infinity();
    const double hi = upper.size() ? upper[i] : std::numeric_limits<double>::infinity();
    if (std::isnan(lo) || std::isnan(hi)) {
      msg << "a bound of " << ParameterName(*this, i) << " is NaN";
      return {"", msg.str()};
    }
    if (lo > hi) {
      msg << ParameterName(*this, i) << ": lower bound " << lo << " > upper bound " << hi;
      return {"", msg.str()};
    }
    const bool is_fixed = IsFixed(i);
    const double v = is_fixed ? fixed_value[i] : initial[i];
    if (v < lo || v > hi) {
      msg << (is_fixed ? "the fixed value " : "the start ") << v << " of "
          << ParameterName(*this, i) << " is outside its bounds [" << lo << ", " << hi
          << "]";
      return {"", msg.str()};
    }
  }
  const auto q = equality_matrix.rows();
  if (q > 0 || equality_rhs.size() > 0) {
    if (equality_matrix.cols() != n || equality_rhs.size() != q) {
      msg << "equality_matrix is " << q << " x " << equality_matrix.cols()
          << " and equality_rhs has " << equality_rhs.size() << " entries; expected q x "
          << n << " and q";
      return {"", msg.str()};
    }
    if (!equality_matrix.allFinite() || !equality_rhs.allFinite()) {
      return {"", "the equalities have a NaN or infinite entry"};
    }
  }
  return {};
}

NonlinearProblem AsNonlinear(const LinearProblem& problem, const Eigen::VectorXd& start) {
  const int n = problem.num_unknowns();
  if (start.size() != 0 && start.size() != n) {
    throw InputError("AsNonlinear start", "has " + std::to_string(start.size()) +
                                              " entries for " + std::to_string(n) +
                                              " unknowns");
  }
  // Shared so that copies of the problem (and of its evaluate function) do not
  // copy the weighted matrix.
  const auto weighted = std::make_shared<const WeightedSystem>(Weighted(problem));

  NonlinearProblem out;
  out.num_residuals = problem.num_rows();
  out.initial = start.size() ? start : Eigen::VectorXd::Zero(n);
  if (problem.lower.size() == n) out.initial = out.initial.cwiseMax(problem.lower);
  if (problem.upper.size() == n) out.initial = out.initial.cwiseMin(problem.upper);
  for (const auto& [i, v] : problem.fixed) {
    if (i >= 0 && i < n) out.initial[i] = v;
  }
  out.names = problem.names;
  out.groups = problem.groups;
  out.residual_labels = problem.row_labels;
  out.fixed = problem.fixed;
  out.lower = problem.lower;
  out.upper = problem.upper;
  out.equality_matrix = problem.equality_matrix;
  out.equality_rhs = problem.equality_rhs;
  out.residuals_whitened = problem.noise_known();
  out.evaluate = [weighted](const Eigen::VectorXd& x, Eigen::VectorXd* residuals,
                            Eigen::MatrixXd* jacobian, std::string*) {
    *residuals = weighted->A * x - weighted->b;
    if (jacobian != nullptr) *jacobian = weighted->A;
    return true;
  };
  return out;
}

}  // namespace femup
