// UFF dataset 58 and 58b (a function of one variable: time record, spectrum,
// FRF, ...): its record layouts, reading ASCII and binary values
// (Reader::Read58, BinaryValues) and writing (Writer::Write(const UffFunction&)).
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "io/uff_internal.h"
#include "text_util.h"

namespace femup::uff_internal {
namespace {

using internal::IsBlank;

// Dataset 58: record 7.
const std::vector<Field> k58Record7 = {
    {"ordinate data type", 10, true},  {"number of points", 10, true},
    {"abscissa spacing", 10, true},    {"abscissa minimum", 13, false},
    {"abscissa increment", 13, false}, {"z-axis value", 13, false}};

// Records 8-11 of dataset 58.
const char* const kAxisNames[4] = {"abscissa", "ordinate (numerator)",
                                   "ordinate denominator", "z-axis"};

}  // namespace

// --- Dataset 58 -------------------------------------------------------------

UffAxis Reader::AxisRecord(int axis) {
  const std::string record = "record " + std::to_string(8 + axis) + " (" +
                             kAxisNames[axis] + " data characteristics)";
  const std::string_view line = RecordLine(record);
  // I10,3I5,2(1X,20A1)
  UffAxis out;
  out.specific_data_type = IntColumn(line, 0, 10, "specific data type", 1, record);
  out.length_exponent = IntColumn(line, 10, 5, "length units exponent", 2, record);
  out.force_exponent = IntColumn(line, 15, 5, "force units exponent", 3, record);
  out.temperature_exponent =
      IntColumn(line, 20, 5, "temperature units exponent", 4, record);
  out.label = std::string(Trim(CharSlice(line, 26, 20)));
  out.units = std::string(Trim(CharSlice(line, 47, -1)));
  return out;
}

UffFunction Reader::Read58(const Header& header) {
  UffFunction f;
  f.binary = header.binary;
  if (header.binary) {
    const std::string where = "header";
    if (header.byte_ordering != 1 && header.byte_ordering != 2) {
      FailIn(header.line, where,
             "field 1 (byte ordering): expected 1 (little-endian) or 2 (big-endian), "
             "found " +
                 std::to_string(header.byte_ordering));
    }
    if (header.fp_format != 2) {
      const char* known = header.fp_format == 1   ? " (DEC VMS)"
                          : header.fp_format == 3 ? " (IBM 5/370)"
                                                  : "";
      FailIn(header.line, where,
             "field 2 (floating-point format): " + std::to_string(header.fp_format) +
                 std::string(known) + " is not supported; only 2 (IEEE 754) is read");
    }
    if (header.ascii_lines != 11) {
      FailIn(header.line, where,
             "field 3 (number of ASCII lines): expected 11 (records 1-11), found " +
                 std::to_string(header.ascii_lines));
    }
  }
  f.id_lines = IdLines();

  // Record 6: 2(I5,I10),2(1X,10A1,I10,I4)
  const std::string r6 = "record 6";
  const std::string_view line6 = RecordLine(r6);
  f.function_type = IntColumn(line6, 0, 5, "function type", 1, r6);
  f.function_id = IntColumn(line6, 5, 10, "function identification number", 2, r6);
  f.version = IntColumn(line6, 15, 5, "version number", 3, r6);
  f.load_case = IntColumn(line6, 20, 10, "load case", 4, r6);
  f.response_entity = std::string(Trim(CharSlice(line6, 31, 10)));
  f.response_node = IntColumn(line6, 41, 10, "response node", 6, r6);
  f.response_direction = IntColumn(line6, 51, 4, "response direction", 7, r6);
  f.reference_entity = std::string(Trim(CharSlice(line6, 56, 10)));
  f.reference_node = IntColumn(line6, 66, 10, "reference node", 9, r6);
  f.reference_direction = IntColumn(line6, 76, 4, "reference direction", 10, r6);

  // Record 7: 3I10,3E13.5
  const std::string r7 = "record 7";
  const auto v7 = NumericRecord(RecordLine(r7), k58Record7, r7);
  const long long line7 = line_;
  const int type = v7[0].integer;
  if (type != 2 && type != 4 && type != 5 && type != 6) {
    FailIn(line7, r7,
           "field 1 (ordinate data type): expected 2 (real single), 4 (real double), 5 "
           "(complex single) or 6 (complex double), found " +
               std::to_string(type));
  }
  f.ordinate_type = static_cast<UffOrdinateType>(type);
  const int points = v7[1].integer;
  if (points < 1) {
    FailIn(line7, r7,
           "field 2 (number of points): expected at least 1, found " +
               std::to_string(points));
  }
  if (v7[2].integer != 0 && v7[2].integer != 1) {
    FailIn(line7, r7,
           "field 3 (abscissa spacing): expected 0 (uneven) or 1 (even), found " +
               std::to_string(v7[2].integer));
  }
  f.even_spacing = v7[2].integer == 1;
  f.abscissa_start = v7[3].real;
  f.abscissa_increment = v7[4].real;
  f.z_axis_value = v7[5].real;
  if (f.even_spacing && points > 1 && f.abscissa_increment == 0.0) {
    FailIn(line7, r7, "field 5 (abscissa increment): 0 with even spacing");
  }

  f.abscissa_axis = AxisRecord(0);
  f.ordinate_axis = AxisRecord(1);
  f.denominator_axis = AxisRecord(2);
  f.z_axis = AxisRecord(3);

  // Record 12.
  const bool complex = f.IsComplex();
  const bool single = !f.IsDoublePrecision();
  const size_t n = static_cast<size_t>(points);
  const size_t per_point = (complex ? 2 : 1) + (f.even_spacing ? 0 : 1);
  const size_t count = n * per_point;
  std::vector<double> values;
  const std::string r12 = "record 12 (data values)";
  if (header.binary) {
    values = BinaryValues(header, count, single ? 4 : 8, r12);
  } else {
    std::vector<int> widths;
    if (single) {
      widths = {13};
    } else if (f.even_spacing) {
      widths = {20};
    } else if (complex) {
      widths = {13, 20, 20};
    } else {
      widths = {13, 20};
    }
    values = ValueBlock(
        count, widths, r12,
        "values (" + std::to_string(n) + " points of " + std::to_string(per_point) + ")");
  }
  ExpectEnd(std::to_string(count) + " data values");

  f.x.resize(points);
  f.y.resize(points);
  for (size_t k = 0; k < n; ++k) {
    const double* p = values.data() + k * per_point;
    const auto i = static_cast<Eigen::Index>(k);
    if (f.even_spacing) {
      f.x(i) = f.abscissa_start + static_cast<double>(k) * f.abscissa_increment;
    } else {
      f.x(i) = *p++;
    }
    f.y(i) = complex ? std::complex<double>(p[0], p[1]) : std::complex<double>(p[0], 0.0);
  }
  return f;
}

std::vector<double> Reader::BinaryValues(const Header& header, size_t count, size_t size,
                                         const std::string& record) {
  const size_t expected = count * size;
  const long long start_line = line_ + 1;
  const size_t left = text_.size() - std::min(position_, text_.size());
  if (static_cast<size_t>(header.bytes) != expected) {
    // pyuff writes the byte count of a real even function also for complex
    // and uneven ones. Trust record 7 when the end marker follows its count.
    bool end_follows = false;
    if (left >= expected) {
      std::string_view after = text_.substr(position_ + expected, 16);
      while (!after.empty() && (IsBlank(after.front()) || after.front() == '\n')) {
        after.remove_prefix(1);
      }
      end_follows = after.substr(0, 2) == "-1" &&
                    (after.size() == 2 || after[2] == '\n' || IsBlank(after[2]));
    }
    if (!end_follows) {
      FailIn(header.line, "header",
             "field 4 (number of bytes): " + std::to_string(header.bytes) +
                 ", but record 7 declares " + std::to_string(count) + " values of " +
                 std::to_string(size) + " bytes (" + std::to_string(expected) + ")");
    }
    Note(header.line, dataset_ + ": the header declares " + std::to_string(header.bytes) +
                          " bytes, record 7 implies " + std::to_string(expected) +
                          "; read " + std::to_string(expected) +
                          " (the end marker follows them)");
  }
  if (left < expected) {
    FailIn(start_line, record,
           "expected " + std::to_string(expected) +
               " bytes of binary values, the file has " + std::to_string(left) +
               " left; the dataset is truncated");
  }
  const bool little = header.byte_ordering == 1;
  std::vector<double> values(count);
  const auto* bytes = reinterpret_cast<const unsigned char*>(text_.data() + position_);
  for (size_t k = 0; k < count; ++k) {
    const unsigned char* p = bytes + k * size;
    std::uint64_t bits = 0;
    for (size_t b = 0; b < size; ++b) {
      const size_t shift = 8 * (little ? b : size - 1 - b);
      bits |= static_cast<std::uint64_t>(p[b]) << shift;
    }
    double v = 0.0;
    if (size == 4) {
      const auto bits32 = static_cast<std::uint32_t>(bits);
      float f = 0.0f;
      std::memcpy(&f, &bits32, sizeof f);
      v = f;
    } else {
      std::memcpy(&v, &bits, sizeof v);
    }
    if (!std::isfinite(v)) {
      FailIn(start_line, record,
             "binary value " + std::to_string(k + 1) + " of " + std::to_string(count) +
                 " is not finite");
    }
    values[k] = v;
  }
  SkipBytes(expected, record);
  return values;
}

// --- 58 ---
void Writer::AxisLine(const UffAxis& axis, int index) {
  const std::string field = std::string(kAxisNames[index]) + " axis";
  Int(axis.specific_data_type, 10, field + " specific data type");
  Int(axis.length_exponent, 5, field + " length units exponent");
  Int(axis.force_exponent, 5, field + " force units exponent");
  Int(axis.temperature_exponent, 5, field + " temperature units exponent");
  const std::string label = Text(axis.label, 20, field + " label");
  const std::string units = Text(axis.units, 20, field + " units");
  AppendF(&out_, "%10d%5d%5d%5d ", axis.specific_data_type, axis.length_exponent,
          axis.force_exponent, axis.temperature_exponent);
  out_ += label + " " + units + "\n";
}

void Writer::Write(const UffFunction& d) {
  number_ = 58;
  const auto type = static_cast<int>(d.ordinate_type);
  if (type != 2 && type != 4 && type != 5 && type != 6) {
    Fail("ordinate data type " + std::to_string(type) + " is not 2, 4, 5 or 6");
  }
  const auto n = static_cast<size_t>(d.y.size());
  if (n == 0) Fail("no data values");
  Int(static_cast<long long>(n), 10, "number of points");
  if (!d.even_spacing && static_cast<size_t>(d.x.size()) != n) {
    Fail("uneven spacing needs one abscissa value per point: x has " +
         std::to_string(d.x.size()) + ", y has " + std::to_string(n));
  }
  const bool complex = d.IsComplex();
  const bool single = !d.IsDoublePrecision();
  if (d.even_spacing && n > 1 && d.abscissa_increment == 0.0) {
    Fail("abscissa increment is 0 with even spacing");
  }

  // Record 12 values in file order.
  std::vector<double> values;
  values.reserve(n * 3);
  for (size_t k = 0; k < n; ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    const std::string where = "point " + std::to_string(k + 1);
    if (!d.even_spacing) values.push_back(Real(d.x(i), where + " abscissa"));
    values.push_back(Real(d.y(i).real(), where + " ordinate"));
    if (complex) {
      values.push_back(Real(d.y(i).imag(), where + " ordinate"));
    } else if (d.y(i).imag() != 0.0) {
      Fail(where + ": ordinate has an imaginary part but the ordinate data type " +
           std::to_string(type) + " is real");
    }
  }
  if (single) {
    for (size_t k = 0; k < values.size(); ++k) {
      if (std::abs(values[k]) > static_cast<double>(std::numeric_limits<float>::max())) {
        Fail("value " + std::to_string(k + 1) + " does not fit single precision");
      }
    }
  }

  // Fields checked before the records are assembled.
  std::string ids;
  for (size_t i = 0; i < 5; ++i) {
    ids += Text(d.id_lines[i], 80, "ID line " + std::to_string(i + 1)) + "\n";
  }
  Int(d.function_type, 5, "function type");
  Int(d.function_id, 10, "function identification number");
  Int(d.version, 5, "version number");
  Int(d.load_case, 10, "load case");
  const std::string response = Text(d.response_entity, 10, "response entity name");
  Int(d.response_node, 10, "response node");
  Int(d.response_direction, 4, "response direction");
  const std::string reference = Text(d.reference_entity, 10, "reference entity name");
  Int(d.reference_node, 10, "reference node");
  Int(d.reference_direction, 4, "reference direction");
  const double start = d.even_spacing ? Real(d.abscissa_start, "abscissa minimum") : 0.0;
  const double step =
      d.even_spacing ? Real(d.abscissa_increment, "abscissa increment") : 0.0;
  Real(d.z_axis_value, "z-axis value");

  const size_t size = single ? 4 : 8;
  if (d.binary) {
    const size_t bytes = values.size() * size;
    if (bytes > static_cast<size_t>(std::numeric_limits<int>::max())) {
      Fail("too many values for one 58b dataset");
    }
    Begin(58, "");
    AppendF(&out_, "b%6d%6d%12d%12d%6d%6d%12d%12d\n", 1, 2, 11, static_cast<int>(bytes),
            0, 0, 0, 0);
  } else {
    Begin(58);
    out_ += std::string(74, ' ') + "\n";
  }
  out_ += ids;
  AppendF(&out_, "%5d%10d%5d%10d ", d.function_type, d.function_id, d.version,
          d.load_case);
  AppendF(&out_, "%s%10d%4d ", response.c_str(), d.response_node, d.response_direction);
  AppendF(&out_, "%s%10d%4d\n", reference.c_str(), d.reference_node,
          d.reference_direction);
  AppendF(&out_, "%10d%10d%10d%13.5E%13.5E%13.5E\n", type, static_cast<int>(n),
          d.even_spacing ? 1 : 0, start, step, d.z_axis_value);
  AxisLine(d.abscissa_axis, 0);
  AxisLine(d.ordinate_axis, 1);
  AxisLine(d.denominator_axis, 2);
  AxisLine(d.z_axis, 3);

  if (d.binary) {
    // Little-endian IEEE, whatever the host; the end marker follows at once
    // (as pyuff writes and reads it).
    for (double v : values) {
      std::uint64_t bits = 0;
      if (single) {
        const auto f = static_cast<float>(v);
        std::uint32_t bits32 = 0;
        std::memcpy(&bits32, &f, sizeof f);
        bits = bits32;
      } else {
        std::memcpy(&bits, &v, sizeof v);
      }
      for (size_t b = 0; b < size; ++b) {
        out_ += static_cast<char>((bits >> (8 * b)) & 0xFF);
      }
    }
  } else if (single) {
    Lines(values, 6, "%13.5E");
  } else if (d.even_spacing) {
    Lines(values, 4, "%20.11E");
  } else {
    // 2(E13.5,E20.12) for real, E13.5,2E20.12 for complex: the abscissa in
    // the narrow field.
    const size_t per_point = complex ? 3 : 2;
    const size_t per_line = complex ? 3 : 4;
    for (size_t k = 0; k < values.size(); ++k) {
      AppendF(&out_, k % per_point == 0 ? "%13.5E" : "%20.11E", values[k]);
      if ((k + 1) % per_line == 0 || k + 1 == values.size()) out_ += '\n';
    }
  }
  End();
}

}  // namespace femup::uff_internal
