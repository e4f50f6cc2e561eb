// UFF dataset 55 (a mode shape or a frequency response at nodes): its record
// layouts, reading (Reader::Read55) and writing (Writer::Write(const
// UffModeShape&)).
#include <complex>
#include <string>
#include <vector>

#include "io/uff_internal.h"

namespace femup::uff_internal {
namespace {

// Dataset 55: record 6.
const std::vector<Field> k55Record6 = {
    {"model type", 10, true},          {"analysis type", 10, true},
    {"data characteristic", 10, true}, {"specific data type", 10, true},
    {"data type", 10, true},           {"number of values per node", 10, true}};

// Record 8 of dataset 55 by analysis type.
const std::vector<Field> k55NormalMode = {{"frequency", 13, false},
                                          {"modal mass", 13, false},
                                          {"modal viscous damping ratio", 13, false},
                                          {"modal hysteretic damping ratio", 13, false}};
const std::vector<Field> k55ComplexMode = {
    {"real part of the eigenvalue", 13, false},
    {"imaginary part of the eigenvalue", 13, false},
    {"real part of modal A", 13, false},
    {"imaginary part of modal A", 13, false},
    {"real part of modal B", 13, false},
    {"imaginary part of modal B", 13, false}};
const std::vector<Field> k55FrequencyResponse = {{"frequency", 13, false}};

}  // namespace

// --- Dataset 55 -------------------------------------------------------------

// False when the analysis type is not supported (skipped with a note).
bool Reader::Read55(UffModeShape* shape) {
  shape->id_lines = IdLines();
  const std::string r6 = "record 6";
  const auto v6 = NumericRecord(RecordLine(r6), k55Record6, r6);
  const long long line6 = line_;
  shape->model_type = v6[0].integer;
  const int analysis = v6[1].integer;
  shape->data_characteristic = v6[2].integer;
  shape->specific_data_type = v6[3].integer;
  const int data_type = v6[4].integer;
  const int per_node = v6[5].integer;
  if (analysis != 2 && analysis != 3 && analysis != 5 && analysis != 7) {
    Note(line6, dataset_ + " with analysis type " + std::to_string(analysis) +
                    " is not supported (only 2 normal mode, 3 and 7 complex mode, 5 "
                    "frequency response); skipped");
    Skip(Header());  // an ASCII dataset: up to the next "-1"
    return false;
  }
  shape->analysis_type = static_cast<UffAnalysisType>(analysis);
  if (data_type != 2 && data_type != 5) {
    FailIn(line6, r6,
           "field 5 (data type): expected 2 (real) or 5 (complex), found " +
               std::to_string(data_type));
  }
  shape->complex_data = data_type == 5;
  if (per_node < 1 || per_node > 9) {
    FailIn(line6, r6,
           "field 6 (number of values per node): expected 1 to 9, found " +
               std::to_string(per_node));
  }
  const bool complex_mode = analysis == 3 || analysis == 7;
  const int reals = analysis == 2 ? 4 : complex_mode ? 6 : 1;
  const char* number_name = analysis == 5 ? "frequency step number" : "mode number";

  const std::string r7 = "record 7";
  const std::vector<Field> f7 = {{"number of integer values", 10, true},
                                 {"number of real values", 10, true},
                                 {"load case", 10, true},
                                 {number_name, 10, true}};
  const auto v7 = NumericRecord(RecordLine(r7), f7, r7);
  if (v7[0].integer != 2) {
    FailIn(line_, r7,
           "field 1 (number of integer values): expected 2, found " +
               std::to_string(v7[0].integer));
  }
  if (v7[1].integer != reals) {
    FailIn(line_, r7,
           "field 2 (number of real values): expected " + std::to_string(reals) +
               " for analysis type " + std::to_string(analysis) + ", found " +
               std::to_string(v7[1].integer));
  }
  shape->load_case = v7[2].integer;
  shape->mode_number = v7[3].integer;

  const std::string r8 = "record 8";
  const std::vector<Field>& f8 = analysis == 2  ? k55NormalMode
                                 : complex_mode ? k55ComplexMode
                                                : k55FrequencyResponse;
  const auto v8 = NumericRecord(RecordLine(r8), f8, r8);
  if (analysis == 2) {
    shape->frequency_hz = v8[0].real;
    shape->modal_mass = v8[1].real;
    shape->viscous_damping_ratio = v8[2].real;
    shape->hysteretic_damping_ratio = v8[3].real;
  } else if (complex_mode) {
    shape->eigenvalue = {v8[0].real, v8[1].real};
    shape->modal_a = {v8[2].real, v8[3].real};
    shape->modal_b = {v8[4].real, v8[5].real};
  } else {
    shape->frequency_hz = v8[0].real;
  }

  // Records 9 and 10 until the end marker.
  const size_t count = static_cast<size_t>(per_node) * (shape->complex_data ? 2 : 1);
  std::vector<std::vector<double>> rows;
  std::string_view line;
  while (NextLineBeforeEnd(&line)) {
    const std::string r9 = "record 9 (node " + std::to_string(rows.size() + 1) + ")";
    const auto v9 = NumericRecord(line, {{"node number", 10, true}}, r9);
    shape->nodes.push_back(v9[0].integer);
    shape->node_lines.push_back(line_);
    const std::string r10 =
        "record 10 (values of node " + std::to_string(v9[0].integer) + ")";
    rows.push_back(ValueBlock(count, {13}, r10, "values"));
  }
  shape->values.resize(static_cast<Eigen::Index>(rows.size()), per_node);
  for (size_t i = 0; i < rows.size(); ++i) {
    for (int j = 0; j < per_node; ++j) {
      const auto k = static_cast<size_t>(j);
      shape->values(static_cast<Eigen::Index>(i), j) =
          shape->complex_data ? std::complex<double>(rows[i][2 * k], rows[i][2 * k + 1])
                              : std::complex<double>(rows[i][k], 0.0);
    }
  }
  return true;
}

// --- 55 ---
void Writer::Write(const UffModeShape& d) {
  number_ = 55;
  const auto analysis = static_cast<int>(d.analysis_type);
  if (analysis != 2 && analysis != 3 && analysis != 5 && analysis != 7) {
    Fail("analysis type " + std::to_string(analysis) + " is not supported");
  }
  const auto rows = static_cast<size_t>(d.values.rows());
  const auto per_node = static_cast<int>(d.values.cols());
  if (rows != d.nodes.size()) {
    Fail("values has " + std::to_string(rows) + " rows for " +
         std::to_string(d.nodes.size()) + " nodes");
  }
  if (per_node < 1 || per_node > 9) {
    Fail("values has " + std::to_string(per_node) + " columns; expected 1 to 9 per node");
  }
  if (!d.complex_data && rows > 0 && d.values.imag().cwiseAbs().maxCoeff() != 0.0) {
    Fail("values have imaginary parts but complex_data is false");
  }
  Int(d.model_type, 10, "model type");
  Int(d.data_characteristic, 10, "data characteristic");
  Int(d.specific_data_type, 10, "specific data type");
  Int(d.load_case, 10, "load case");
  Int(d.mode_number, 10, "mode number");

  std::vector<double> header;
  if (analysis == 2) {
    header = {d.frequency_hz, d.modal_mass, d.viscous_damping_ratio,
              d.hysteretic_damping_ratio};
  } else if (analysis == 5) {
    header = {d.frequency_hz};
  } else {
    header = {d.eigenvalue.real(), d.eigenvalue.imag(), d.modal_a.real(),
              d.modal_a.imag(),    d.modal_b.real(),    d.modal_b.imag()};
  }
  for (double v : header) Real(v, "record 8");

  Begin(55);
  out_ += std::string(74, ' ') + "\n";
  IdLines(d.id_lines);
  AppendF(&out_, "%10d%10d%10d%10d%10d%10d\n", d.model_type, analysis,
          d.data_characteristic, d.specific_data_type, d.complex_data ? 5 : 2, per_node);
  AppendF(&out_, "%10d%10d%10d%10d\n", 2, static_cast<int>(header.size()), d.load_case,
          d.mode_number);
  Lines(header, 6, "%13.5E");
  std::vector<double> row;
  for (size_t i = 0; i < rows; ++i) {
    Int(d.nodes[i], 10, "node " + std::to_string(i + 1));
    AppendF(&out_, "%10d\n", d.nodes[i]);
    row.clear();
    for (int j = 0; j < per_node; ++j) {
      const std::complex<double> v = d.values(static_cast<Eigen::Index>(i), j);
      row.push_back(Real(v.real(), "values of node " + std::to_string(d.nodes[i])));
      if (d.complex_data) {
        row.push_back(Real(v.imag(), "values of node " + std::to_string(d.nodes[i])));
      }
    }
    Lines(row, 6, "%13.5E");
  }
  End();
}

}  // namespace femup::uff_internal
