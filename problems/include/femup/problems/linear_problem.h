// LinearProblem: find x with A x ~= b, some entries of x fixed to known values.
// Every linear solver takes this one type.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace femup {

struct LinearProblem {
  Eigen::MatrixXd A;                // m x n
  Eigen::VectorXd b;                // m
  std::vector<std::string> names;   // n unknown names ("mass[3]")
  std::vector<std::string> groups;  // n group names ("mass", "stiffness"); may be empty
  std::vector<std::string> row_labels;        // m, may be empty
  std::vector<std::pair<int, double>> fixed;  // (unknown index, known value)

  int num_rows() const { return static_cast<int>(A.rows()); }
  int num_unknowns() const { return static_cast<int>(A.cols()); }
  // Empty when consistent; otherwise what is wrong (sizes, NaN, a fixed index
  // out of range or listed twice).
  std::string Validate() const;
  // Fixes the unknown called `name` at `value`; throws InputError when no
  // unknown has that name.
  void Fix(const std::string& name, double value);
  std::vector<int> FreeUnknowns() const;  // indices not fixed, ascending
  bool IsFixed(int index) const;
};

}  // namespace femup
