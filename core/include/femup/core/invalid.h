// What is wrong with an input, as data. Every options or spec struct's
// Validate() returns one, so that a caller can put the field under where the
// options sit ("solver.", "model.") or find the study file's key for it
// without splitting a "field: message" string again.
#pragma once

#include <string>

namespace femup {

// What is wrong with an input: the field (dotted path, may be empty) and what
// was expected. A default-constructed Invalid means "nothing is wrong".
struct Invalid {
  std::string field;
  std::string message;

  // Nothing is wrong (the message is empty).
  bool ok() const { return message.empty(); }
  // Something IS wrong: `if (auto bad = options.Validate()) ...`.
  explicit operator bool() const { return !ok(); }
  // The same fault one level down: the field becomes "prefix.field" (prefix
  // alone when the field is empty); ok stays ok.
  Invalid Under(const std::string& prefix) const;
  // "field: message", the message alone when the field is empty, "" when ok.
  std::string ToString() const;
};

// Throws InputError with where() = "prefix.field" (as Under) and the message
// when `bad` says something is wrong; returns otherwise.
void ThrowIfInvalid(const Invalid& bad, const std::string& prefix = "");

}  // namespace femup
