#include "femup/core/invalid.h"

#include "femup/core/errors.h"

namespace femup {

Invalid Invalid::Under(const std::string& prefix) const {
  if (ok() || prefix.empty()) return *this;
  return {field.empty() ? prefix : prefix + "." + field, message};
}

std::string Invalid::ToString() const {
  if (ok()) return "";
  return field.empty() ? message : field + ": " + message;
}

void ThrowIfInvalid(const Invalid& bad, const std::string& prefix) {
  if (bad) {
    const Invalid at = bad.Under(prefix);
    throw InputError(at.field, at.message);
  }
}

}  // namespace femup
