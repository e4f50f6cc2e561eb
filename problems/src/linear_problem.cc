#include "femup/problems/linear_problem.h"

#include <cmath>
#include <sstream>

#include "femup/errors.h"

namespace femup {

std::string LinearProblem::Validate() const {
  std::ostringstream msg;
  if (A.rows() != b.size()) {
    msg << "A has " << A.rows() << " rows but b has " << b.size() << " entries";
    return msg.str();
  }
  if (A.cols() == 0) return "the problem has no unknown";
  if (A.rows() == 0) return "the problem has no equation";
  if (!names.empty() && static_cast<Eigen::Index>(names.size()) != A.cols()) {
    msg << names.size() << " names for " << A.cols() << " unknowns";
    return msg.str();
  }
  if (!groups.empty() && static_cast<Eigen::Index>(groups.size()) != A.cols()) {
    msg << groups.size() << " groups for " << A.cols() << " unknowns";
    return msg.str();
  }
  if (!row_labels.empty() && static_cast<Eigen::Index>(row_labels.size()) != A.rows()) {
    msg << row_labels.size() << " row labels for " << A.rows() << " rows";
    return msg.str();
  }
  if (!A.allFinite()) return "A has a NaN or infinite entry";
  if (!b.allFinite()) return "b has a NaN or infinite entry";
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    const int i = fixed[k].first;
    if (i < 0 || i >= A.cols()) {
      msg << "fixed unknown index " << i << " is outside 0.." << A.cols() - 1;
      return msg.str();
    }
    if (!std::isfinite(fixed[k].second)) {
      msg << "fixed value of unknown " << (names.empty() ? std::to_string(i) : names[i])
          << " is not finite";
      return msg.str();
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (fixed[j].first == i) {
        msg << "unknown " << (names.empty() ? std::to_string(i) : names[i])
            << " is fixed twice";
        return msg.str();
      }
    }
  }
  if (static_cast<Eigen::Index>(fixed.size()) >= A.cols())
    return "every unknown is fixed";
  return "";
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
