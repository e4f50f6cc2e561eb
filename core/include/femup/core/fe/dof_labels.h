// Private to femup's layers: what a DOF label says about the DOF.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace femup::internal {

// The node and component of a DOF label: "n7:ux" -> ("n7", "ux"); a chain's "x3"
// -> ("x3", "").
inline std::pair<std::string, std::string> SplitDofLabel(const std::string& label) {
  const auto colon = label.find(':');
  if (colon == std::string::npos) return {label, ""};
  return {label.substr(0, colon), label.substr(colon + 1)};
}

// A frame's transverse translation: labels ending in ":ux" ("n3:ux").
inline bool IsTransverseDof(const std::string& label) {
  return label.size() > 3 && label.compare(label.size() - 3, 3, ":ux") == 0;
}

// A rigid unit translation along the transverse DOFs: 1 on every ":ux" DOF, 0
// elsewhere; all ones when no label is transverse (a chain).
inline Eigen::VectorXd TransverseUnitTranslation(const std::vector<std::string>& labels) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(labels.size()));
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (IsTransverseDof(labels[i])) r[static_cast<Eigen::Index>(i)] = 1.0;
  }
  if (r.isZero()) r.setOnes();
  return r;
}

}  // namespace femup::internal
