// Private to femup_studies: reading the modes.json that `femup identify` writes
// (the modes a study's modes_file names). Internal, but declared here so that
// the tests and the fuzzer (fuzz/modes_json_fuzzer.cc) can reach the parser.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace femup::internal {

// The identified modes: frequencies_hz[k] and shapes[k] (one value per record
// channel) for mode k; channels are the record's channel names (may be empty).
struct FileModes {
  std::vector<std::string> channels;
  std::vector<double> frequencies_hz;
  std::vector<Eigen::VectorXd> shapes;
};

// Reads `path`. Throws InputError naming the file (and the field, e.g.
// "modes[2].shape[3]") for a missing file, text that is not JSON, a number that
// does not fit a double, a missing "modes" list, a mode that is not an object,
// a frequency that is not a positive number, a shape entry that is not a number,
// a channel name that is not text.
FileModes ReadModesJson(const std::string& path);
// The same for text already in memory; `name` stands for the file in messages.
FileModes ParseModesJson(std::string_view text, const std::string& name);

}  // namespace femup::internal
