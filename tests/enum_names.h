// Test helper shared by the tests of femup's named enums (ToString and
// <Enum>FromString): the names written and read back.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace femup::testing {

// Expects ToString of every value in `names` to give its name; then, starting
// from `start`, expects `parse` to read every name in `reads` into its value,
// in order, and to refuse `unknown`. Returns the value after the refusal.
template <typename E, typename Parse>
E ExpectEnumNames(const std::vector<std::pair<E, std::string>>& names, Parse parse,
                  E start, const std::vector<std::pair<std::string, E>>& reads,
                  const std::string& unknown) {
  for (const auto& [value, name] : names) EXPECT_EQ(ToString(value), name);
  E value = start;
  for (const auto& [name, expected] : reads) {
    EXPECT_TRUE(parse(name, &value)) << name;
    EXPECT_EQ(value, expected) << name;
  }
  EXPECT_FALSE(parse(unknown, &value)) << unknown;
  return value;
}

}  // namespace femup::testing
