// Universal File Format datasets 15, 55, 58/58b and 2411: reader and writer.
// This file holds the entry points (ParseUff, ReadUff, FormatUff, WriteUff and
// UffFile's selectors) and the text helpers the reader and writer share; the
// reader is in uff_reader.cc, the writer in uff_writer.cc, and the records of
// each dataset family in uff_datasets_*.cc.
#include "femup/core/io/uff.h"

#include <algorithm>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "io/file_io.h"
#include "io/uff_internal.h"
#include "text_util.h"

namespace femup {
namespace uff_internal {

// ---------------------------------------------------------------------------
// Text helpers.

namespace {

bool IsUtf8Continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// Byte offset of character `column` (0-based) in `line`, or line.size().
size_t ByteOffsetOfChar(std::string_view line, size_t column) {
  size_t chars = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    if (IsUtf8Continuation(line[i])) continue;
    if (chars == column) return i;
    ++chars;
  }
  return line.size();
}

}  // namespace

using internal::IsBlank;

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

std::string_view TrimRight(std::string_view s) {
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

std::string Quote(std::string_view text) {
  constexpr size_t kMax = 60;
  if (text.size() > kMax) return "'" + std::string(text.substr(0, kMax)) + "...'";
  return "'" + std::string(text) + "'";
}

size_t CharCount(std::string_view text) {
  size_t n = 0;
  for (char c : text) n += IsUtf8Continuation(c) ? 0 : 1;
  return n;
}

std::string_view CharSlice(std::string_view line, size_t first, int width) {
  const size_t begin = ByteOffsetOfChar(line, first);
  if (width < 0) return line.substr(begin);
  const size_t end = ByteOffsetOfChar(line, first + static_cast<size_t>(width));
  return line.substr(begin, end - begin);
}

}  // namespace uff_internal

namespace {

using uff_internal::Reader;
using uff_internal::Writer;

template <typename T>
std::vector<const T*> Select(const std::vector<UffDataset>& datasets) {
  std::vector<const T*> out;
  for (const auto& d : datasets) {
    if (const T* p = std::get_if<T>(&d)) out.push_back(p);
  }
  return out;
}

}  // namespace

std::vector<const UffNodes*> UffFile::Nodes() const { return Select<UffNodes>(datasets); }
std::vector<const UffModeShape*> UffFile::ModeShapes() const {
  return Select<UffModeShape>(datasets);
}
std::vector<const UffFunction*> UffFile::Functions() const {
  return Select<UffFunction>(datasets);
}

UffFile ParseUff(std::string_view contents, const std::string& name) {
  return Reader(contents, name).Read();
}

UffFile ReadUff(const std::string& path) {
  const std::string text = internal::ReadFileText(path, "UFF file");
  return ParseUff(text, path);
}

std::string FormatUff(const std::vector<UffDataset>& datasets, const std::string& name) {
  return Writer(name).Format(datasets);
}

void WriteUff(const std::string& path, const std::vector<UffDataset>& datasets) {
  internal::WriteFileAtomically(path, FormatUff(datasets, path));
}

std::string LabelRanges(std::vector<int> labels) {
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  std::string out;
  for (std::size_t i = 0; i < labels.size();) {
    std::size_t j = i;
    while (j + 1 < labels.size() && labels[j + 1] == labels[j] + 1) ++j;
    if (!out.empty()) out += ", ";
    out += std::to_string(labels[i]);
    if (j > i) out += "-" + std::to_string(labels[j]);
    i = j + 1;
  }
  return out.empty() ? "none" : out;
}

}  // namespace femup
