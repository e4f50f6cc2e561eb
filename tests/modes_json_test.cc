// The modes.json of `femup identify`, as a study's modes_file reads it
// (studies/src/modes_json.h): good files give the modes, everything else an
// InputError naming the file and the field; never nlohmann's own exceptions.
#include "modes_json.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "scratch_dir.h"

namespace femup {
namespace {

using internal::FileModes;
using internal::ParseModesJson;
using internal::ReadModesJson;

// Expects ParseModesJson(text, "m.json") to throw an InputError naming the
// file whose message contains every needle.
void ExpectError(const std::string& text, const std::vector<std::string>& needles) {
  try {
    ParseModesJson(text, "m.json");
    ADD_FAILURE() << "no error for " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "m.json");
    for (const std::string& n : needles)
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos)
          << n << " in " << e.what();
  }
}

TEST(ModesJson, ReadsTheModesOfFemupIdentify) {
  const FileModes m = ParseModesJson(R"({
  "command": "identify",
  "data": {"kind": "impulse", "channels": ["a1", "a2"], "samples": 100},
  "modes": [
    {"frequency_hz": 6.5, "damping_ratio": 0.01, "shape": [1.0, -0.5], "order": 10},
    {"frequency_hz": 41, "shape": [0.25, 1]}
  ],
  "notes": []
})",
                                     "m.json");
  EXPECT_EQ(m.channels, (std::vector<std::string>{"a1", "a2"}));
  ASSERT_EQ(m.frequencies_hz.size(), 2u);
  EXPECT_EQ(m.frequencies_hz[1], 41.0);
  ASSERT_EQ(m.shapes.size(), 2u);
  EXPECT_EQ(m.shapes[0][1], -0.5);
  EXPECT_EQ(m.shapes[1][0], 0.25);
}

// Fuzzing (issue 25): a number too large for a double escaped as nlohmann's
// out_of_range ("internal error", exit 4). fuzz/regressions/modes_json/.
TEST(ModesJson, NumberOverflowIsAnInputError) {
  ExpectError(
      R"({"data": {"channels": ["a"]}, "modes": [{"frequency_hz": 9e550, "shape": [1]}]})",
      {"m.json: a number does not fit a double", "9e550"});
  ExpectError(R"({"modes": [{"frequency_hz": 1, "shape": [-1e400]}]})",
              {"does not fit a double"});
}

TEST(ModesJson, SyntaxAndTypeErrorsNameTheField) {
  ExpectError("{\"modes\": [", {"not valid JSON"});
  ExpectError("", {"not valid JSON"});
  ExpectError("[1, 2]", {"top level: expected an object", "found array"});
  ExpectError("{}", {"modes: missing"});
  ExpectError(R"({"modes": {"a": 1}})",
              {"modes: expected a list of modes, found object"});
  ExpectError(R"({"modes": [3]})", {"modes[1]: expected an object", "found number"});
  ExpectError(R"({"modes": [{"shape": [1]}]})",
              {"modes[1].frequency_hz: expected a number, found none"});
  ExpectError(R"({"modes": [{"frequency_hz": "6.5", "shape": [1]}]})",
              {"modes[1].frequency_hz: expected a number, found string"});
  ExpectError(R"({"modes": [{"frequency_hz": -1, "shape": [1]}]})",
              {"modes[1].frequency_hz: expected a positive frequency, found -1"});
  ExpectError(R"({"modes": [{"frequency_hz": 1, "shape": 5}]})",
              {"modes[1].shape: expected a list of numbers, found number"});
  ExpectError(
      R"({"modes": [{"frequency_hz": 1, "shape": [1]}, {"frequency_hz": 2, "shape": [1, "x"]}]})",
      {"modes[2].shape[2]: expected a number (null is a lost value), found string"});
  ExpectError(R"({"modes": [{"frequency_hz": 1, "shape": [null]}]})",
              {"modes[1].shape[1]: expected a number", "found null"});
  ExpectError(R"({"data": {"channels": "a1"}, "modes": []})",
              {"data.channels: expected a list of channel names, found string"});
  ExpectError(R"({"data": {"channels": ["a1", 7]}, "modes": []})",
              {"data.channels[2]: expected a channel name (text), found number"});
}

TEST(ModesJson, ReadsFilesAndNamesAMissingOne) {
  const testing::ScratchDir dir;
  try {
    ReadModesJson(dir.path() + "/none.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir.path() + "/none.json");
  }
}

}  // namespace
}  // namespace femup
