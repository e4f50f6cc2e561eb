// Errors for bad input, and the one numerical failure a caller may let stop a
// job. Outcomes of numerical work (non-convergence, rank deficiency) are
// status values (SolverSummary, EigenSolution from TrySolveModes): input that
// cannot be used (a missing file, a wrong size, NaN, an unknown key) throws
// InputError; NumericalError is thrown only by the convenience wrappers that
// return a result without its status (SolveModes over TrySolveModes), for
// callers that cannot go on without it. Fits use the status and go on.
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

// A numerical method failed on valid input: an eigensolver that did not
// converge, a mode without positive modal mass. Not an InputError: the
// input was usable; the command line reports it apart (exit code 3) and a fit
// that meets one treats that evaluation as failed.
class NumericalError : public std::runtime_error {
 public:
  NumericalError(const std::string& where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what), where_(where) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

}  // namespace femup
