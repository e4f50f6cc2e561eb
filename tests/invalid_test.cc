// What is wrong with an input (core/include/femup/core/invalid.h): ok and its bool,
// putting a field under a prefix, the one rendering, and the InputError that
// ThrowIfInvalid makes of it.
#include "femup/core/invalid.h"

#include <gtest/gtest.h>

#include <string>

#include "femup/core/errors.h"

namespace femup {
namespace {

TEST(Invalid, DefaultMeansNothingIsWrong) {
  const Invalid none;
  EXPECT_TRUE(none.ok());
  EXPECT_FALSE(static_cast<bool>(none));
  EXPECT_EQ(none.ToString(), "");
  if (const Invalid bad = none) ADD_FAILURE() << "an ok Invalid tests true";
}

TEST(Invalid, AMessageMeansSomethingIsWrong) {
  const Invalid bad{"order", "must be >= 1"};
  EXPECT_FALSE(bad.ok());
  EXPECT_TRUE(static_cast<bool>(bad));
  const Invalid no_field{"", "the problem has no unknown"};
  EXPECT_FALSE(no_field.ok());
  EXPECT_TRUE(static_cast<bool>(no_field));
  // The message decides: a field alone says nothing is wrong.
  EXPECT_TRUE((Invalid{"order", ""}.ok()));
}

TEST(Invalid, ToStringIsFieldColonMessage) {
  EXPECT_EQ((Invalid{"order", "must be >= 1"}.ToString()), "order: must be >= 1");
  EXPECT_EQ((Invalid{"legs.Iy", "must be positive"}.ToString()),
            "legs.Iy: must be positive");
  EXPECT_EQ((Invalid{"", "no evaluate function"}.ToString()), "no evaluate function");
  // A message with colons of its own is not split again.
  EXPECT_EQ((Invalid{"priors.mass.m", "normal: sigma must be positive"}.ToString()),
            "priors.mass.m: normal: sigma must be positive");
}

TEST(Invalid, UnderPutsThePrefixInFrontOfTheField) {
  const Invalid bad{"first_sample", "must be >= 0"};
  const Invalid under = bad.Under("era");
  EXPECT_EQ(under.field, "era.first_sample");
  EXPECT_EQ(under.message, "must be >= 0");
  EXPECT_EQ(under.Under("stabilisation").field, "stabilisation.era.first_sample");
  EXPECT_EQ(under.ToString(), "era.first_sample: must be >= 0");
  // Without a field the prefix becomes the field.
  const Invalid whole = Invalid{"", "level must be below 1"}.Under("noise");
  EXPECT_EQ(whole.field, "noise");
  EXPECT_EQ(whole.message, "level must be below 1");
  // An empty prefix changes nothing.
  EXPECT_EQ(bad.Under("").field, "first_sample");
}

TEST(Invalid, UnderKeepsOkOk) {
  const Invalid ok = Invalid().Under("solver");
  EXPECT_TRUE(ok.ok());
  EXPECT_EQ(ok.field, "");
  EXPECT_EQ(ok.ToString(), "");
}

TEST(Invalid, ThrowIfInvalidReturnsWhenOk) {
  EXPECT_NO_THROW(ThrowIfInvalid(Invalid()));
  EXPECT_NO_THROW(ThrowIfInvalid(Invalid(), "solver"));
}

TEST(Invalid, ThrowIfInvalidNamesThePrefixedField) {
  try {
    ThrowIfInvalid({"max_iterations", "must be positive, got 0"}, "solver");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "solver.max_iterations");
    EXPECT_STREQ(e.what(), "solver.max_iterations: must be positive, got 0");
  }
  try {
    ThrowIfInvalid({"max_iterations", "must be positive, got 0"});
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "max_iterations");
    EXPECT_STREQ(e.what(), "max_iterations: must be positive, got 0");
  }
  try {
    ThrowIfInvalid({"", "has no sample"}, "time_response");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "time_response");
    EXPECT_STREQ(e.what(), "time_response: has no sample");
  }
  try {
    ThrowIfInvalid({"", "every parameter is fixed"});
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "");
    EXPECT_STREQ(e.what(), "every parameter is fixed");
  }
}

}  // namespace
}  // namespace femup
