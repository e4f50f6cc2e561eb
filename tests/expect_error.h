// Test helpers: expect a call to throw an InputError whose message holds every
// one of a list of needles, or get the message of the one it throws.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "femup/core/errors.h"

namespace femup::testing {

// Expects `f` to throw an InputError whose message holds every needle; `none`
// is the failure's message when it throws nothing.
template <typename F>
void ExpectInputError(F f, const std::vector<std::string>& needles,
                      const std::string& none = "no exception") {
  try {
    f();
    ADD_FAILURE() << none;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& n : needles)
      EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
  }
}

// The message of the InputError `f` throws, or "" when it throws nothing.
template <typename F>
std::string InputErrorMessage(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// ExpectInputError, saying which needle it expected when nothing is thrown.
template <typename F>
void ExpectError(F f, const std::vector<std::string>& needles) {
  ExpectInputError(f, needles, "no error; expected " + needles[0]);
}

}  // namespace femup::testing
