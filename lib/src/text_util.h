// Private to femup_core: small text helpers shared by the file readers.
#pragma once

#include <string_view>
#include <vector>

namespace femup::internal {

// Space, tab, CR, form feed or vertical tab.
inline bool IsBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

// The blank-separated fields of `line` (views into it).
inline std::vector<std::string_view> Tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsBlank(line[i])) ++i;
    size_t j = i;
    while (j < line.size() && !IsBlank(line[j])) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

}  // namespace femup::internal
