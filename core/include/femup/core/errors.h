// Errors for bad input. Outcomes of numerical work (non-convergence, rank
// deficiency) are reported as status values, never thrown; only input that
// cannot be used (a missing file, a wrong size, NaN, an unknown key) throws.
#pragma once

#include <stdexcept>
#include <string>

namespace femup {

// Bad input: the message names the file, the field or the value, and says what
// was expected. `where` is a location such as "study.yaml: model.section.E".
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what), where_(where) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

}  // namespace femup
