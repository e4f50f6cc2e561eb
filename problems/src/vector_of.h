// Private to femup_problems: a vector from a brace list, for the effect
// families' ranges and starts ({lower, upper}, {theta1, theta2}).
#pragma once

#include <Eigen/Core>
#include <initializer_list>

namespace femup::internal {

inline Eigen::VectorXd VectorOf(std::initializer_list<double> values) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) out[i++] = x;
  return out;
}

}  // namespace femup::internal
