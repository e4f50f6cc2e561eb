// Private to femup_core: small text helpers shared by the file readers.
#pragma once

#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace femup::internal {

// Space, tab, CR, form feed or vertical tab.
inline bool IsBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

// Splits the next line off `text` at `*position` (LF or CRLF ends a line; the
// terminator is not part of `*line`) and moves `*position` past it; false at
// the end of the text.
inline bool NextTextLine(std::string_view text, size_t* position,
                         std::string_view* line) {
  if (*position >= text.size()) return false;
  size_t end = text.find('\n', *position);
  if (end == std::string_view::npos) end = text.size();
  std::string_view out = text.substr(*position, end - *position);
  if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
  *line = out;
  *position = end + 1;
  return true;
}

// Where text starts after a UTF-8 byte order mark, if any.
inline size_t AfterByteOrderMark(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
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

// `v` with the fewest of 15 or 17 significant digits that reads back exactly
// ("0.9", not "0.90000000000000002"): numbers quoted in error messages.
inline std::string ShortestDecimal(double v) {
  for (int digits : {15, 17}) {
    std::ostringstream out;
    out.precision(digits);
    out << v;
    if (digits == 17 || std::strtod(out.str().c_str(), nullptr) == v) return out.str();
  }
  return {};
}

}  // namespace femup::internal
