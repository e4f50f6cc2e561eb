// Test helper: an Eigen vector from a list of numbers, e.g. a parameter vector
// written in place (VectorOf({std::log(0.4), 1.2})).
#pragma once

#include <Eigen/Dense>
#include <initializer_list>

namespace femup {
namespace fixtures {

inline Eigen::VectorXd VectorOf(std::initializer_list<double> values) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) out[i++] = x;
  return out;
}

}  // namespace fixtures
}  // namespace femup
