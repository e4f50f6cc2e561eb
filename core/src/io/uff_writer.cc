// The UFF writer: what every dataset needs (printf to the text, fields checked
// against their Fortran widths, the "-1" frame, ID lines, value lines). The
// records of each dataset family are written in uff_datasets_*.cc.
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "io/uff_internal.h"

namespace femup::uff_internal {

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void AppendF(std::string* out, const char* format, ...) {
  char buffer[256];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  if (n > 0) out->append(buffer, std::min(static_cast<size_t>(n), sizeof buffer - 1));
}

std::string Writer::Format(const std::vector<UffDataset>& datasets) {
  for (size_t i = 0; i < datasets.size(); ++i) {
    index_ = i;
    std::visit([this](const auto& d) { Write(d); }, datasets[i]);
  }
  return std::move(out_);
}

std::string Writer::Text(const std::string& text, size_t width,
                         const std::string& field) const {
  if (text.find_first_of("\r\n") != std::string::npos) {
    Fail(field + ": text contains a line break");
  }
  const std::string value = text.empty() ? std::string("NONE") : text;
  const size_t chars = CharCount(value);
  if (chars > width) {
    Fail(field + ": " + Quote(value) + " has " + std::to_string(chars) +
         " characters, the field holds " + std::to_string(width));
  }
  return value + std::string(width - chars, ' ');
}

// A text field right-trimmed when it ends the line.
std::string Writer::LastText(const std::string& text, size_t width,
                             const std::string& field) const {
  return std::string(TrimRight(Text(text, width, field)));
}

int Writer::Int(long long value, int width, const std::string& field) const {
  const std::string text = std::to_string(value);
  if (static_cast<int>(text.size()) > width) {
    Fail(field + ": " + text + " does not fit " + std::to_string(width) + " columns");
  }
  return static_cast<int>(value);
}

double Writer::Real(double value, const std::string& field) const {
  if (!std::isfinite(value)) Fail(field + ": value is not finite");
  return value;
}

void Writer::Begin(int number, const char* suffix) {
  number_ = number;
  AppendF(&out_, "%6d\n%6d%s", -1, number, suffix);
}

void Writer::IdLines(const std::array<std::string, 5>& ids) {
  for (size_t i = 0; i < 5; ++i) {
    out_ += Text(ids[i], 80, "ID line " + std::to_string(i + 1));
    out_ += '\n';
  }
}

// Values in lines of `per_line` fields of format `format`.
void Writer::Lines(const std::vector<double>& values, size_t per_line,
                   const char* format) {
  for (size_t k = 0; k < values.size(); ++k) {
    AppendF(&out_, format, values[k]);
    if ((k + 1) % per_line == 0 || k + 1 == values.size()) out_ += '\n';
  }
}

}  // namespace femup::uff_internal
