// Private to femup_core: what the UFF files share. The Reader (uff_reader.cc,
// and the uff_datasets_*.cc file of each dataset family) and the Writer
// (uff_writer.cc and the same family files), with the text helpers of uff.cc.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/io/uff.h"
#include "text_util.h"

namespace femup::uff_internal {

// uff.cc: text helpers.
std::string_view Trim(std::string_view s);
std::string_view TrimRight(std::string_view s);
// Quoted for messages, shortened when long.
std::string Quote(std::string_view text);
// Number of characters (UTF-8 code points) in `text`.
size_t CharCount(std::string_view text);
// Characters [first, first + width) of `line` (0-based character columns);
// width < 0: to the end of the line.
std::string_view CharSlice(std::string_view line, size_t first, int width);

// ---------------------------------------------------------------------------
// Record layouts (each uff_datasets_*.cc file holds its own).

struct Field {
  const char* name;
  int width;  // columns of the Fortran layout
  bool integer;
};

// One parsed numeric value of a record.
struct Value {
  double real = 0.0;
  int integer = 0;
};

// ---------------------------------------------------------------------------
// Reader.

class Reader {
 public:
  Reader(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {}
  UffFile Read();

 private:
  // Header of a dataset: its number and, for binary datasets, the fields after
  // the 'b'.
  struct Header {
    int number = 0;
    bool binary = false;
    int byte_ordering = 0;
    int fp_format = 0;
    int ascii_lines = 0;
    long long bytes = 0;
    long long line = 0;
  };

  std::string Where(long long line) const {
    return name_ + ": line " + std::to_string(line);
  }
  [[noreturn]] void Fail(long long line, const std::string& what) const {
    throw InputError(Where(line), what);
  }
  // A failure inside the current dataset, e.g. "dataset 58 record 7: ...".
  [[noreturn]] void FailIn(long long line, const std::string& record,
                           const std::string& what) const {
    Fail(line, dataset_ + " " + record + ": " + what);
  }
  void Note(long long line, const std::string& what) {
    file_.notes.push_back(Where(line) + ": " + what);
  }

  // Next line without its terminator (LF or CRLF); false at the end of the text.
  bool NextLine(std::string_view* line) {
    if (!internal::NextTextLine(text_, &position_, line)) return false;
    ++line_;
    return true;
  }

  // uff_reader.cc: lines, dataset headers, skipping, generic records.
  std::string_view RecordLine(const std::string& record);
  bool NextLineBeforeEnd(std::string_view* line);
  void ExpectEnd(const std::string& after);
  Header ReadHeader();
  void ReadDataset();
  void Skip(const Header& header);
  void SkipBytes(size_t count, const std::string& what);
  std::vector<Value> NumericRecord(std::string_view line,
                                   const std::vector<Field>& fields,
                                   const std::string& record);
  static std::string ParseField(std::string_view token, const Field& field, size_t index,
                                Value* value);
  static bool ByColumns(std::string_view line, const std::vector<Field>& fields,
                        std::vector<Value>* values);
  void ValueLine(std::string_view line, const std::vector<int>& widths, size_t wanted,
                 size_t first_index, const std::string& record, std::vector<double>* out);
  std::vector<double> ValueBlock(size_t count, const std::vector<int>& widths,
                                 const std::string& record, const std::string& what);
  std::array<std::string, 5> IdLines();
  int IntColumn(std::string_view line, size_t first, int width, const char* name,
                int index, const std::string& record);

  // uff_datasets_nodes.cc: datasets 15 and 2411.
  UffNodes Read15();
  UffNodes Read2411();

  // uff_datasets_mode_shapes.cc: dataset 55.
  bool Read55(UffModeShape* shape);

  // uff_datasets_functions.cc: dataset 58 and 58b.
  UffAxis AxisRecord(int axis);
  UffFunction Read58(const Header& header);
  std::vector<double> BinaryValues(const Header& header, size_t count, size_t size,
                                   const std::string& record);

  std::string_view text_;
  std::string name_;
  size_t position_ = 0;
  long long line_ = 0;
  std::string dataset_;
  UffFile file_;
};

// ---------------------------------------------------------------------------
// Writer.

// uff_writer.cc: printf to the end of `out`.
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void AppendF(std::string* out, const char* format, ...);

class Writer {
 public:
  explicit Writer(std::string name) : name_(std::move(name)) {}
  std::string Format(const std::vector<UffDataset>& datasets);

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(name_, "dataset " + std::to_string(index_) + " (" +
                                std::to_string(number_) + "): " + what);
  }
  // uff_writer.cc: fields, dataset frames, value lines.
  std::string Text(const std::string& text, size_t width, const std::string& field) const;
  std::string LastText(const std::string& text, size_t width,
                       const std::string& field) const;
  int Int(long long value, int width, const std::string& field) const;
  double Real(double value, const std::string& field) const;
  void Begin(int number, const char* suffix = "");
  void End() { out_ += "    -1\n"; }
  void IdLines(const std::array<std::string, 5>& ids);
  void Lines(const std::vector<double>& values, size_t per_line, const char* format);

  // uff_datasets_nodes.cc, uff_datasets_mode_shapes.cc, uff_datasets_functions.cc.
  void Write(const UffNodes& d);
  void Write(const UffModeShape& d);
  void AxisLine(const UffAxis& axis, int index);
  void Write(const UffFunction& d);

  std::string name_;
  std::string out_;
  size_t index_ = 0;
  int number_ = 0;
};

}  // namespace femup::uff_internal
