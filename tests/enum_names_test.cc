// One table per enum, read both ways (core/include/femup/core/enum_names.h).
#include "femup/core/enum_names.h"

#include <gtest/gtest.h>

#include <string>

namespace femup {
namespace {

enum class Colour { kRed, kGreen, kBlue };

constexpr EnumName<Colour> kColours[] = {{Colour::kRed, "red"},
                                         {Colour::kGreen, "green"}};

TEST(EnumNames, NameOfEachValueInTheTable) {
  EXPECT_STREQ(NameIn(kColours, Colour::kRed, "unknown"), "red");
  EXPECT_STREQ(NameIn(kColours, Colour::kGreen, "unknown"), "green");
  static_assert(NameIn(kColours, Colour::kGreen, "?")[0] == 'g', "usable in constexpr");
}

TEST(EnumNames, ValueMissingFromTheTableGetsTheFallback) {
  EXPECT_STREQ(NameIn(kColours, Colour::kBlue, "unknown"), "unknown");
}

TEST(EnumNames, NameBackToItsValue) {
  Colour c = Colour::kBlue;
  EXPECT_TRUE(ValueIn(kColours, std::string("green"), &c));
  EXPECT_EQ(c, Colour::kGreen);
  EXPECT_TRUE(ValueIn(kColours, "red", &c));
  EXPECT_EQ(c, Colour::kRed);
}

TEST(EnumNames, UnknownNameLeavesTheValueUntouched) {
  Colour c = Colour::kBlue;
  EXPECT_FALSE(ValueIn(kColours, "Red", &c));  // names are exact, case included
  EXPECT_FALSE(ValueIn(kColours, "", &c));
  EXPECT_FALSE(ValueIn(kColours, "green ", &c));
  EXPECT_EQ(c, Colour::kBlue);
}

}  // namespace
}  // namespace femup
