// Private to femup_studies: the descriptions of a UFF file's datasets
// (file_info_uff.cc) that file_info.cc's report and JSON list, and the number
// format both use (defined in file_info.cc).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "femup/core/io/uff.h"

namespace femup::file_info {

// `v` with `digits` significant digits.
std::string Num(double v, int digits = 6);

// Text and JSON of every dataset of a UFF file, in file order.
void DescribeUff(const UffFile& uff, std::vector<std::string>* lines,
                 nlohmann::json* datasets);

}  // namespace femup::file_info
