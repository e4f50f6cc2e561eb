// Private: Eigen <-> JSON helpers. Non-finite numbers become null (JSON has no NaN).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <nlohmann/json.hpp>

namespace femup {
namespace json_util {

inline nlohmann::json Number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

inline nlohmann::json Vector(const Eigen::VectorXd& v) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(Number(v[i]));
  return out;
}

}  // namespace json_util

}  // namespace femup
