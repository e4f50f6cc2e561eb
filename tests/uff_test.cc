// Universal File Format datasets 15, 55 and 58/58b: real files (measured FRFs
// of the pyuff repository, an HBM catman time history, a pyuff mode shape),
// round trips of every dataset variant in ASCII and binary, the tolerated
// irregularities, and malformed files.
#include "femup/core/io/uff.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "scratch_dir.h"

namespace femup {
namespace {

namespace fs = std::filesystem;

const std::string kRealData = std::string(FEMUP_TEST_DATA_DIR) + "/realdata";

using testing::ScratchDir;

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string ToCrlf(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n') out += '\r';
    out += c;
  }
  return out;
}

// Every line with its trailing blanks removed.
std::string TrimLines(const std::string& text) {
  std::string out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

// The file's lines (LF), 1-based access by index - 1.
std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

// Parses `text` as a file called `name`, expecting an InputError whose message
// holds each of `parts`; returns the message.
std::string ExpectError(const std::string& text, const std::string& name,
                        const std::vector<std::string>& parts) {
  try {
    ParseUff(text, name);
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos)
          << "message: " << message << "\nlacks: " << part;
    }
    return message;
  }
  ADD_FAILURE() << "no InputError for " << name;
  return "";
}

// One value per line in Python complex syntax, "(-0.0774+2.68e-08j)", as the
// pyuff repository stores the measured FRFs.
std::vector<std::complex<double>> ReadPythonComplex(const std::string& path) {
  std::vector<std::complex<double>> out;
  std::istringstream in(ReadText(path));
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    EXPECT_EQ(line.front(), '(') << line;
    EXPECT_EQ(line.back(), ')') << line;
    const char* first = line.data() + 1;
    const char* last = line.data() + line.size() - 1;
    double re = 0.0;
    double im = 0.0;
    auto r = std::from_chars(first, last, re);
    EXPECT_EQ(r.ec, std::errc()) << line;
    const char* p = r.ptr;
    if (p != last && *p == '+') ++p;
    r = std::from_chars(p, last, im);
    EXPECT_EQ(r.ec, std::errc()) << line;
    EXPECT_TRUE(r.ptr + 1 == last && *r.ptr == 'j') << line;
    out.emplace_back(re, im);
  }
  return out;
}

// Indices of the spectral peaks of `a`: the largest value within +-15 bins
// that also stands out by a factor 3 over the median of +-40 bins.
std::vector<Eigen::Index> Peaks(const Eigen::VectorXd& a) {
  std::vector<Eigen::Index> out;
  const Eigen::Index n = a.size();
  for (Eigen::Index k = 1; k + 1 < n; ++k) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, k - 15);
    const Eigen::Index hi = std::min<Eigen::Index>(n - 1, k + 15);
    if (a.segment(lo, hi - lo + 1).maxCoeff() != a(k)) continue;
    const Eigen::Index wlo = std::max<Eigen::Index>(0, k - 40);
    const Eigen::Index whi = std::min<Eigen::Index>(n - 1, k + 40);
    std::vector<double> window(a.data() + wlo, a.data() + whi + 1);
    std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
    if (a(k) > 3.0 * window[window.size() / 2]) out.push_back(k);
  }
  return out;
}

void ExpectSameAxis(const UffAxis& a, const UffAxis& b) {
  EXPECT_EQ(a.specific_data_type, b.specific_data_type);
  EXPECT_EQ(a.length_exponent, b.length_exponent);
  EXPECT_EQ(a.force_exponent, b.force_exponent);
  EXPECT_EQ(a.temperature_exponent, b.temperature_exponent);
  EXPECT_EQ(a.label, b.label);
  EXPECT_EQ(a.units, b.units);
}

// Headers equal exactly; values to `rel` of the largest magnitude (and the
// abscissa of uneven data to `rel_x`).
void ExpectSameFunction(const UffFunction& a, const UffFunction& b, double rel,
                        double rel_x) {
  EXPECT_EQ(a.id_lines, b.id_lines);
  EXPECT_EQ(a.function_type, b.function_type);
  EXPECT_EQ(a.function_id, b.function_id);
  EXPECT_EQ(a.version, b.version);
  EXPECT_EQ(a.load_case, b.load_case);
  EXPECT_EQ(a.response_entity, b.response_entity);
  EXPECT_EQ(a.response_node, b.response_node);
  EXPECT_EQ(a.response_direction, b.response_direction);
  EXPECT_EQ(a.reference_entity, b.reference_entity);
  EXPECT_EQ(a.reference_node, b.reference_node);
  EXPECT_EQ(a.reference_direction, b.reference_direction);
  EXPECT_EQ(a.ordinate_type, b.ordinate_type);
  EXPECT_EQ(a.even_spacing, b.even_spacing);
  EXPECT_EQ(a.binary, b.binary);
  if (a.even_spacing) {
    EXPECT_DOUBLE_EQ(a.abscissa_start, b.abscissa_start);
    EXPECT_DOUBLE_EQ(a.abscissa_increment, b.abscissa_increment);
  }
  EXPECT_DOUBLE_EQ(a.z_axis_value, b.z_axis_value);
  ExpectSameAxis(a.abscissa_axis, b.abscissa_axis);
  ExpectSameAxis(a.ordinate_axis, b.ordinate_axis);
  ExpectSameAxis(a.denominator_axis, b.denominator_axis);
  ExpectSameAxis(a.z_axis, b.z_axis);
  ASSERT_EQ(a.y.size(), b.y.size());
  ASSERT_EQ(a.x.size(), b.x.size());
  for (Eigen::Index k = 0; k < a.y.size(); ++k) {
    const std::complex<double> ya = a.y(k);
    const std::complex<double> yb = b.y(k);
    EXPECT_LE(std::abs(ya.real() - yb.real()), rel * std::abs(ya.real()))
        << "point " << k;
    EXPECT_LE(std::abs(ya.imag() - yb.imag()), rel * std::abs(ya.imag()))
        << "point " << k;
    EXPECT_LE(std::abs(a.x(k) - b.x(k)), rel_x * std::abs(a.x(k)) + 1e-300)
        << "point " << k;
  }
}

UffFunction MakeFunction(UffOrdinateType type, bool even, bool binary, int points) {
  UffFunction f;
  f.id_lines = {"Test function", "second id line", "21-Nov-24 08:00:00", "NONE", "NONE"};
  f.function_type = 4;
  f.function_id = 7;
  f.version = 2;
  f.load_case = 3;
  f.response_entity = "beam";
  f.response_node = 101;
  f.response_direction = -3;
  f.reference_entity = "hammer";
  f.reference_node = 2;
  f.reference_direction = 1;
  f.ordinate_type = type;
  f.even_spacing = even;
  f.abscissa_start = even ? 2.5 : 0.0;
  f.abscissa_increment = even ? 0.125 : 0.0;
  f.z_axis_value = 1.5;
  f.abscissa_axis = {18, 0, 0, 0, "Frequency", "Hz"};
  f.ordinate_axis = {12, 1, 0, 0, "Acceleration", "m/s^2"};
  f.denominator_axis = {13, 0, 1, 0, "Force", "N"};
  f.z_axis = {0, 0, 0, 0, "NONE", "NONE"};
  f.binary = binary;
  const bool complex = f.IsComplex();
  const bool single = !f.IsDoublePrecision();
  f.x.resize(points);
  f.y.resize(points);
  for (int k = 0; k < points; ++k) {
    f.x(k) = even ? f.abscissa_start + k * f.abscissa_increment : 0.37 * k * k + 0.1;
    double re = std::sin(0.7 * k + 0.3) * std::pow(10.0, (k % 7) - 3);
    double im = complex ? std::cos(1.3 * k) * std::pow(10.0, 2 - (k % 5)) : 0.0;
    if (!single && k == 3) re = -1.5e-150;  // a three-digit exponent fills E20.12
    if (!single && k == 4) im = complex ? 2.25e+123 : 0.0;
    if (single) {  // values a float holds exactly, so binary compares exactly
      re = static_cast<float>(re);
      im = static_cast<float>(im);
    }
    f.y(k) = {re, im};
  }
  return f;
}

// ---------------------------------------------------------------------------
// Real data.

TEST(LabelRanges, SortsDropsRepeatsAndJoinsRuns) {
  EXPECT_EQ(LabelRanges({}), "none");
  EXPECT_EQ(LabelRanges({7}), "7");
  EXPECT_EQ(LabelRanges({3, 1, 2, 10, 15, 11, 2}), "1-3, 10-11, 15");
  EXPECT_EQ(LabelRanges({-2, -1, 0, 5}), "-2-0, 5");
}

TEST(UffRealData, MeasuredFrfsRoundTripAsciiAndBinaryAndKeepTheBeamPeaks) {
  // Accelerance FRFs of pyuff's data/meas_point_{1,2,3}.txt: 0..1000 Hz at
  // 1 Hz, one response point and three reference points. Written the way
  // pyuff's own test writes them (the second one binary), then read back.
  std::vector<UffDataset> datasets;
  for (int p = 1; p <= 3; ++p) {
    const auto frf =
        ReadPythonComplex(kRealData + "/meas_point_" + std::to_string(p) + ".txt");
    ASSERT_EQ(frf.size(), 1001u);
    UffFunction f;
    f.id_lines[0] = "meas_point_" + std::to_string(p);
    f.function_type = 4;
    f.response_entity = "TestCase";
    f.response_node = 1;
    f.response_direction = 1;
    f.reference_entity = "TestCase";
    f.reference_node = p;
    f.reference_direction = 1;
    f.ordinate_type = UffOrdinateType::kComplexDouble;
    f.even_spacing = true;
    f.abscissa_start = 0.0;
    f.abscissa_increment = 1.0;
    f.abscissa_axis = {18, 0, 0, 0, "Frequency", "Hz"};
    f.ordinate_axis = {12, 1, 0, 0, "Acceleration", "m/s^2"};
    f.denominator_axis = {13, 0, 1, 0, "Force", "N"};
    f.x = Eigen::VectorXd::LinSpaced(1001, 0.0, 1000.0);
    f.y = Eigen::Map<const Eigen::VectorXcd>(frf.data(),
                                             static_cast<Eigen::Index>(frf.size()));
    f.binary = p == 2;
    datasets.emplace_back(f);
  }
  EXPECT_NEAR(std::get<UffFunction>(datasets[0]).y(0).real(), -0.0774752256830106, 1e-16);

  ScratchDir dir;
  const std::string path = dir.File("measurement.uff");
  WriteUff(path, datasets);
  const UffFile file = ReadUff(path);
  EXPECT_TRUE(file.notes.empty());
  ASSERT_EQ(file.datasets.size(), 3u);
  const auto functions = file.Functions();
  ASSERT_EQ(functions.size(), 3u);
  const std::vector<Eigen::Index> expected_peaks = {52, 142, 279, 460, 687, 959};
  for (size_t i = 0; i < 3; ++i) {
    const UffFunction& f = *functions[i];
    const UffFunction& original = std::get<UffFunction>(datasets[i]);
    SCOPED_TRACE("meas_point_" + std::to_string(i + 1));
    EXPECT_EQ(f.function_type, 4);
    EXPECT_EQ(f.binary, i == 1);
    EXPECT_EQ(f.reference_node, static_cast<int>(i) + 1);
    ASSERT_EQ(f.y.size(), 1001);
    EXPECT_TRUE(f.even_spacing);
    EXPECT_EQ(f.abscissa_increment, 1.0);
    EXPECT_EQ(f.x(0), 0.0);
    EXPECT_EQ(f.x(1000), 1000.0);
    // Binary keeps the doubles; ASCII E20.12 keeps 12 significant digits.
    ExpectSameFunction(original, f, f.binary ? 0.0 : 1e-11, 0.0);

    const std::vector<Eigen::Index> peaks = Peaks(f.y.cwiseAbs());
    ASSERT_EQ(peaks.size(), expected_peaks.size());
    for (size_t k = 0; k < peaks.size(); ++k) {
      EXPECT_NEAR(f.x(peaks[k]), static_cast<double>(expected_peaks[k]), 3.0);
    }
  }
}

TEST(UffRealData, CatmanTimeHistory) {
  // Exported by HBM catman (id line 2): single precision, 13 samples at
  // 20 kHz on three lines, the last one short, lines blank-padded to 80
  // columns, three-digit exponents in record 7, UTF-8 units "m/s²".
  const std::string path = kRealData + "/catman_time_history.uff";
  const UffFile file = ReadUff(path);
  EXPECT_TRUE(file.notes.empty());
  ASSERT_EQ(file.datasets.size(), 1u);
  const UffFunction& f = std::get<UffFunction>(file.datasets[0]);
  EXPECT_EQ(f.id_lines[0], "1x : m/s²");
  EXPECT_EQ(f.id_lines[1], "UFF58 file created by HBM catman");
  EXPECT_EQ(f.id_lines[2], "30-Apr-20 19:12:52");
  EXPECT_EQ(f.id_lines[3], "NONE");
  EXPECT_EQ(f.function_type, 1);
  EXPECT_EQ(f.response_entity, "NONE");
  EXPECT_EQ(f.response_node, 0);
  EXPECT_EQ(f.ordinate_type, UffOrdinateType::kRealSingle);
  EXPECT_FALSE(f.binary);
  EXPECT_TRUE(f.even_spacing);
  EXPECT_EQ(f.abscissa_start, 0.0);
  EXPECT_DOUBLE_EQ(f.abscissa_increment, 5e-5);
  EXPECT_EQ(f.abscissa_axis.specific_data_type, 17);
  EXPECT_EQ(f.abscissa_axis.label, "Time");
  EXPECT_EQ(f.abscissa_axis.units, "s");
  EXPECT_EQ(f.ordinate_axis.specific_data_type, 1);
  EXPECT_EQ(f.ordinate_axis.label, "1x");
  EXPECT_EQ(f.ordinate_axis.units, "m/s²");
  EXPECT_EQ(f.denominator_axis.label, "NONE");
  ASSERT_EQ(f.y.size(), 13);
  EXPECT_DOUBLE_EQ(f.y(0).real(), -3.81956);
  EXPECT_DOUBLE_EQ(f.y(6).real(), -3.90210);
  EXPECT_DOUBLE_EQ(f.y(12).real(), -5.84096);
  EXPECT_EQ(f.y.imag().cwiseAbs().maxCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(f.x(12), 12 * 5e-5);

  // Tolerated forms of the same file read the same.
  const std::string text = ReadText(path);
  for (const std::string& variant :
       {ToCrlf(text), TrimLines(text), ToCrlf(TrimLines(text))}) {
    const UffFile again = ParseUff(variant, "variant.uff");
    ASSERT_EQ(again.datasets.size(), 1u);
    ExpectSameFunction(f, std::get<UffFunction>(again.datasets[0]), 0.0, 0.0);
  }

  // Round trip through the writer, ASCII and binary.
  for (bool binary : {false, true}) {
    UffFunction g = f;
    g.binary = binary;
    const UffFile back = ParseUff(FormatUff({g}, "catman.uff"), "catman.uff");
    ASSERT_EQ(back.datasets.size(), 1u);
    // Single precision: the printed 6 digits survive both ways.
    ExpectSameFunction(g, std::get<UffFunction>(back.datasets[0]), binary ? 1e-7 : 1e-12,
                       0.0);
  }
}

TEST(UffRealData, ModeShapeWithTranslationsAndRotations) {
  // pyuff's data/uff55_translation_rotation.uff: one normal mode, 6 values
  // per node (rotations zero), 43 nodes, fields of 13 columns with 4 decimals.
  const UffFile file = ReadUff(kRealData + "/uff55_translation_rotation.uff");
  EXPECT_TRUE(file.notes.empty());
  ASSERT_EQ(file.ModeShapes().size(), 1u);
  const UffModeShape& m = *file.ModeShapes()[0];
  EXPECT_EQ(m.id_lines[0], "NONE");
  EXPECT_EQ(m.model_type, 1);
  EXPECT_EQ(m.analysis_type, UffAnalysisType::kNormalMode);
  EXPECT_EQ(m.data_characteristic, 3);
  EXPECT_EQ(m.specific_data_type, 8);
  EXPECT_FALSE(m.complex_data);
  EXPECT_EQ(m.load_case, 0);
  EXPECT_EQ(m.mode_number, 0);
  EXPECT_DOUBLE_EQ(m.frequency_hz, 97.013);
  EXPECT_EQ(m.modal_mass, 0.0);
  ASSERT_EQ(m.nodes.size(), 43u);
  ASSERT_EQ(m.values.rows(), 43);
  ASSERT_EQ(m.values.cols(), 6);
  for (size_t i = 0; i < 43; ++i) EXPECT_EQ(m.nodes[i], static_cast<int>(i) + 1);
  EXPECT_DOUBLE_EQ(m.values(0, 0).real(), 5.3569e-02);
  EXPECT_DOUBLE_EQ(m.values(15, 0).real(), -1.0);  // node 16: the normalising entry
  EXPECT_DOUBLE_EQ(m.values(42, 2).real(), -8.1751e-01);
  EXPECT_EQ(m.values.rightCols(3).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(m.values.imag().cwiseAbs().maxCoeff(), 0.0);
  // The largest translation is that normalising entry.
  EXPECT_DOUBLE_EQ(m.values.real().leftCols(3).cwiseAbs().maxCoeff(), 1.0);

  const UffFile back = ParseUff(FormatUff({m}, "m.uff"), "m.uff");
  ASSERT_EQ(back.ModeShapes().size(), 1u);
  const UffModeShape& b = *back.ModeShapes()[0];
  EXPECT_EQ(b.nodes, m.nodes);
  EXPECT_EQ(b.data_characteristic, 3);
  EXPECT_DOUBLE_EQ(b.frequency_hz, 97.013);
  EXPECT_TRUE(b.values.isApprox(m.values, 1e-12));  // 5 digits, written with 6
}

// ---------------------------------------------------------------------------
// Round trips.

TEST(UffRoundTrip, Nodes) {
  UffNodes nodes;
  nodes.nodes = {{1, 0, 0, 11, {0.0, 0.0, 0.0}},
                 {2, 1, 2, 8, {1.25, -3.5e-3, 7.0e+4}},
                 {1000001, 0, 0, 0, {-0.123456, 9.87654e-12, 1.0}}};
  ScratchDir dir;
  WriteUff(dir.File("nodes.uff"), {nodes});
  const std::string text = ReadText(dir.File("nodes.uff"));
  const auto lines = Lines(text);
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(lines[0], "    -1");
  EXPECT_EQ(lines[1].substr(0, 6), "    15");
  EXPECT_EQ(
      lines[3],
      "         2         1         2         8  1.25000E+00 -3.50000E-03  7.00000E+04");
  EXPECT_EQ(lines[5], "    -1");
  const UffFile file = ReadUff(dir.File("nodes.uff"));
  ASSERT_EQ(file.Nodes().size(), 1u);
  const auto& read = file.Nodes()[0]->nodes;
  ASSERT_EQ(read.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(read[i].label, nodes.nodes[i].label);
    EXPECT_EQ(read[i].definition_cs, nodes.nodes[i].definition_cs);
    EXPECT_EQ(read[i].displacement_cs, nodes.nodes[i].displacement_cs);
    EXPECT_EQ(read[i].color, nodes.nodes[i].color);
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_NEAR(read[i].xyz[c], nodes.nodes[i].xyz[c],
                  5e-6 * std::abs(nodes.nodes[i].xyz[c]));
    }
  }
}

UffModeShape MakeShape(UffAnalysisType type, bool complex, int per_node) {
  UffModeShape m;
  m.id_lines = {"mode shape", "NONE", "NONE", "NONE", "NONE"};
  m.analysis_type = type;
  m.data_characteristic = per_node == 6 ? 3 : 2;
  m.specific_data_type = 8;
  m.complex_data = complex;
  m.load_case = 4;
  m.mode_number = 3;
  if (type == UffAnalysisType::kNormalMode) {
    m.frequency_hz = 142.0625;
    m.modal_mass = 2.5;
    m.viscous_damping_ratio = 0.0125;
    m.hysteretic_damping_ratio = 0.002;
  } else if (type == UffAnalysisType::kFrequencyResponse) {
    m.frequency_hz = 52.5;
  } else {
    m.eigenvalue = {-4.5, 892.25};
    m.modal_a = {0.25, -1.5e-3};
    m.modal_b = {-12.5, 3.0};
  }
  m.nodes = {1, 2, 5, 17};
  m.values.resize(4, per_node);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < per_node; ++j) {
      const double re = std::sin(1.0 + i + 0.5 * j);
      m.values(i, j) = {re, complex ? std::cos(2.0 * i - j) * 1e-3 : 0.0};
    }
  }
  return m;
}

void ExpectSameShape(const UffModeShape& a, const UffModeShape& b) {
  const double rel = 5e-6;  // E13.5
  EXPECT_EQ(a.id_lines, b.id_lines);
  EXPECT_EQ(a.model_type, b.model_type);
  EXPECT_EQ(a.analysis_type, b.analysis_type);
  EXPECT_EQ(a.data_characteristic, b.data_characteristic);
  EXPECT_EQ(a.specific_data_type, b.specific_data_type);
  EXPECT_EQ(a.complex_data, b.complex_data);
  EXPECT_EQ(a.load_case, b.load_case);
  EXPECT_EQ(a.mode_number, b.mode_number);
  EXPECT_NEAR(a.frequency_hz, b.frequency_hz, rel * std::abs(a.frequency_hz));
  EXPECT_NEAR(a.modal_mass, b.modal_mass, rel * std::abs(a.modal_mass));
  EXPECT_NEAR(a.viscous_damping_ratio, b.viscous_damping_ratio,
              rel * a.viscous_damping_ratio);
  EXPECT_NEAR(a.hysteretic_damping_ratio, b.hysteretic_damping_ratio,
              rel * a.hysteretic_damping_ratio);
  EXPECT_LE(std::abs(a.eigenvalue - b.eigenvalue), rel * std::abs(a.eigenvalue));
  EXPECT_LE(std::abs(a.modal_a - b.modal_a), rel * std::abs(a.modal_a));
  EXPECT_LE(std::abs(a.modal_b - b.modal_b), rel * std::abs(a.modal_b));
  EXPECT_EQ(a.nodes, b.nodes);
  ASSERT_EQ(a.values.rows(), b.values.rows());
  ASSERT_EQ(a.values.cols(), b.values.cols());
  for (Eigen::Index i = 0; i < a.values.rows(); ++i) {
    for (Eigen::Index j = 0; j < a.values.cols(); ++j) {
      EXPECT_NEAR(a.values(i, j).real(), b.values(i, j).real(),
                  rel * std::abs(a.values(i, j).real()));
      EXPECT_NEAR(a.values(i, j).imag(), b.values(i, j).imag(),
                  rel * std::abs(a.values(i, j).imag()));
    }
  }
}

TEST(UffRoundTrip, ModeShapesOfEveryAnalysisType) {
  const std::vector<UffModeShape> shapes = {
      MakeShape(UffAnalysisType::kNormalMode, false, 3),
      MakeShape(UffAnalysisType::kNormalMode, false, 6),
      MakeShape(UffAnalysisType::kComplexFirstOrder, true, 3),
      MakeShape(UffAnalysisType::kComplexSecondOrder, true, 6),  // 12 values: two lines
      MakeShape(UffAnalysisType::kFrequencyResponse, true, 3),
  };
  std::vector<UffDataset> datasets(shapes.begin(), shapes.end());
  ScratchDir dir;
  WriteUff(dir.File("modes.uff"), datasets);
  const UffFile file = ReadUff(dir.File("modes.uff"));
  EXPECT_TRUE(file.notes.empty());
  ASSERT_EQ(file.ModeShapes().size(), shapes.size());
  for (size_t i = 0; i < shapes.size(); ++i) {
    SCOPED_TRACE(i);
    ExpectSameShape(shapes[i], *file.ModeShapes()[i]);
  }
  // The normal-mode records as the format lays them out.
  const auto lines = Lines(ReadText(dir.File("modes.uff")));
  EXPECT_EQ(lines[7], "         1         2         2         8         2         3");
  EXPECT_EQ(lines[8], "         2         4         4         3");
  EXPECT_EQ(lines[9], "  1.42062E+02  2.50000E+00  1.25000E-02  2.00000E-03");
  EXPECT_EQ(lines[10], "         1");
}

TEST(UffRoundTrip, FunctionsOfEveryOrdinateTypeAndSpacingAsciiAndBinary) {
  const UffOrdinateType types[] = {
      UffOrdinateType::kRealSingle, UffOrdinateType::kRealDouble,
      UffOrdinateType::kComplexSingle, UffOrdinateType::kComplexDouble};
  ScratchDir dir;
  for (UffOrdinateType type : types) {
    for (bool even : {true, false}) {
      for (bool binary : {false, true}) {
        const UffFunction f = MakeFunction(type, even, binary, 11);
        SCOPED_TRACE("type " + std::to_string(static_cast<int>(type)) +
                     (even ? " even" : " uneven") + (binary ? " binary" : " ascii"));
        const std::string path = dir.File("f.uff");
        WriteUff(path, {f});
        const UffFile file = ReadUff(path);
        EXPECT_TRUE(file.notes.empty());
        ASSERT_EQ(file.Functions().size(), 1u);
        const UffFunction& g = *file.Functions()[0];
        const bool single = !f.IsDoublePrecision();
        // Binary: exact (the single precision test values are floats). ASCII:
        // E13.5 keeps 6 significant digits, E20.12 keeps 12; uneven abscissa
        // values are E13.5 in every ASCII layout.
        const double rel = binary ? 0.0 : single ? 5e-6 : 5e-12;
        const double rel_x = binary ? (single ? 1e-7 : 0.0) : 5e-6;
        ExpectSameFunction(f, g, rel, rel_x);
        // The binary header counts the bytes that follow records 1-11.
        if (binary) {
          const std::string text = ReadText(path);
          const size_t values = 11 * ((f.IsComplex() ? 2 : 1) + (even ? 0 : 1));
          const std::string header = Lines(text)[1];
          char expected[128];
          std::snprintf(expected, sizeof expected, "    58b%6d%6d%12d%12zu%6d%6d%12d%12d",
                        1, 2, 11, values * (single ? 4 : 8), 0, 0, 0, 0);
          EXPECT_EQ(header, expected);
        }
      }
    }
  }
}

TEST(UffRoundTrip, AsciiLayoutOfTheRecords) {
  const UffFunction f = MakeFunction(UffOrdinateType::kComplexDouble, true, false, 3);
  const auto lines = Lines(FormatUff({f}, "f.uff"));
  ASSERT_EQ(lines.size(), 13u + 2u + 1u);
  EXPECT_EQ(lines[0], "    -1");
  EXPECT_EQ(lines[1], "    58" + std::string(74, ' '));
  EXPECT_EQ(lines[2], "Test function" + std::string(67, ' '));
  // 2(I5,I10),2(1X,10A1,I10,I4)
  EXPECT_EQ(
      lines[7],
      "    4         7    2         3 beam             101  -3 hammer             2   1");
  // 3I10,3E13.5
  EXPECT_EQ(lines[8],
            "         6         3         1  2.50000E+00  1.25000E-01  1.50000E+00");
  // I10,3I5,2(1X,20A1)
  EXPECT_EQ(lines[9],
            "        18    0    0    0 Frequency            Hz                  ");
  EXPECT_EQ(lines[10],
            "        12    1    0    0 Acceleration         m/s^2               ");
  // 4E20.12: two complex values on the first line, one on the second.
  EXPECT_EQ(lines[13].size(), 80u);
  EXPECT_EQ(lines[14].size(), 40u);
  EXPECT_EQ(lines[15], "    -1");
}

TEST(UffRoundTrip, MixedFileKeepsOrderAndSkipsUnsupportedDatasetsWithANote) {
  UffNodes nodes;
  nodes.nodes = {{1, 0, 0, 0, {0.0, 0.0, 0.0}}, {2, 0, 0, 0, {1.0, 0.0, 0.0}}};
  const UffModeShape shape = MakeShape(UffAnalysisType::kNormalMode, false, 3);
  const UffFunction f = MakeFunction(UffOrdinateType::kRealDouble, true, true, 5);
  std::string text = FormatUff({nodes, shape}, "a.uff");
  // An unsupported dataset (2412, elements), a 55 of a transient analysis,
  // and an unsupported binary dataset skipped by its header counts, with blank
  // lines between datasets.
  text +=
      "\n    -1\n  2412\n         1        91         1         1         0         3\n"
      "         1         2         3\n"
      "    -1\n\n";
  text +=
      "    -1\n    55\nNONE\nNONE\nNONE\nNONE\nNONE\n"
      "         1         4         2         8         2         3\n"
      "         2         1         1        10\n  1.00000E-01\n         1\n"
      "  1.00000E+00  2.00000E+00  3.00000E+00\n    -1\n";
  text += "    -1\n  2414b     1     2           1           8\nheader line\n";
  text += std::string("\x01\x02\n\x04-1\x06\x07", 8) + "\n    -1\n";
  text += FormatUff({f}, "a.uff");
  const UffFile file = ParseUff(text, "mixed.uff");
  ASSERT_EQ(file.datasets.size(), 3u);
  EXPECT_TRUE(std::holds_alternative<UffNodes>(file.datasets[0]));
  EXPECT_TRUE(std::holds_alternative<UffModeShape>(file.datasets[1]));
  EXPECT_TRUE(std::holds_alternative<UffFunction>(file.datasets[2]));
  EXPECT_EQ(file.Nodes().size(), 1u);
  EXPECT_EQ(file.ModeShapes().size(), 1u);
  EXPECT_EQ(file.Functions().size(), 1u);
  ExpectSameFunction(f, *file.Functions()[0], 0.0, 0.0);
  ASSERT_EQ(file.notes.size(), 3u);
  EXPECT_NE(file.notes[0].find("mixed.uff: line"), std::string::npos) << file.notes[0];
  EXPECT_NE(file.notes[0].find("dataset 2412 is not supported"), std::string::npos);
  EXPECT_NE(file.notes[1].find("analysis type 4"), std::string::npos) << file.notes[1];
  EXPECT_NE(file.notes[2].find("dataset 2414b is not supported"), std::string::npos)
      << file.notes[2];
  // Every dataset is listed with its line, read or skipped.
  ASSERT_EQ(file.headers.size(), 6u);
  const int numbers[6] = {15, 55, 2412, 55, 2414, 58};
  const int indices[6] = {0, 1, -1, -1, -1, 2};
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(file.headers[i].number, numbers[i]) << i;
    EXPECT_EQ(file.headers[i].index, indices[i]) << i;
  }
  EXPECT_TRUE(file.headers[4].binary);
  EXPECT_EQ(file.headers[0].line, 2);
  EXPECT_EQ(std::get<UffNodes>(file.datasets[0]).line, 2);
  EXPECT_EQ(std::get<UffNodes>(file.datasets[0]).nodes[1].line, 4);
  EXPECT_EQ(std::get<UffModeShape>(file.datasets[1]).line, file.headers[1].line);
  EXPECT_EQ(std::get<UffFunction>(file.datasets[2]).line, file.headers[5].line);
  for (size_t i = 1; i < 6; ++i)
    EXPECT_GT(file.headers[i].line, file.headers[i - 1].line);
}

TEST(UffRoundTrip, Nodes2411InDoublePrecision) {
  UffNodes nodes;
  nodes.dataset = 2411;
  nodes.nodes = {{1, 0, 0, 11, {0.1, -171.1755676269531, 1.0 / 3.0}},
                 {20000000, 1, 2, 8, {1.25e-30, 9.87654321012345e+20, -0.0}}};
  const std::string text = FormatUff({nodes}, "n.unv");
  const auto lines = Lines(text);
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[1].substr(0, 6), "  2411");
  EXPECT_EQ(lines[2], "         1         0         0        11");
  EXPECT_EQ(
      lines[3],
      "   1.0000000000000001E-01  -1.7117556762695310E+02   3.3333333333333331E-01");
  const UffFile file = ParseUff(text, "n.unv");
  ASSERT_EQ(file.Nodes().size(), 1u);
  const UffNodes& read = *file.Nodes()[0];
  EXPECT_EQ(read.dataset, 2411);
  ASSERT_EQ(read.nodes.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(read.nodes[i].label, nodes.nodes[i].label);
    EXPECT_EQ(read.nodes[i].definition_cs, nodes.nodes[i].definition_cs);
    EXPECT_EQ(read.nodes[i].displacement_cs, nodes.nodes[i].displacement_cs);
    EXPECT_EQ(read.nodes[i].color, nodes.nodes[i].color);
    for (size_t c = 0; c < 3; ++c) EXPECT_EQ(read.nodes[i].xyz[c], nodes.nodes[i].xyz[c]);
  }
  EXPECT_EQ(read.nodes[1].line, 5);
  // Fortran D exponents, as Permas writes them; a truncated node.
  const UffFile d = ParseUff(
      "    -1\n  2411\n         7         0         0        11\n"
      "   9.4999999999999996D-01   5.0000000000000003D-02   0.0000000000000000D+00\n"
      "    -1\n",
      "permas.unv");
  ASSERT_EQ(d.Nodes().size(), 1u);
  EXPECT_DOUBLE_EQ(d.Nodes()[0]->nodes[0].xyz[0], 0.95);
  EXPECT_DOUBLE_EQ(d.Nodes()[0]->nodes[0].xyz[1], 0.05);
  try {
    ParseUff("    -1\n  2411\n         7         0         0        11\n    -1\n",
             "t.unv");
    ADD_FAILURE() << "truncated 2411 accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("t.unv: line 4: dataset 2411 record 2 (coordinates of node 7)"),
              std::string::npos)
        << msg;
  }
}

TEST(UffRealData, VkiNodes2411AmongOtherDatasets) {
  // tests/data/uff/vki_heat_engine_housing.unv (README there): datasets 151,
  // 164, 2411 (10 nodes), 2412 and 2414, CRLF line endings. Node 1 at
  // (-171.1755676269531, 103.6403427124023, 138.4829101562500), node 10 at
  // (-147.6755676269531, 101.9969635009766, 147.4829101562500).
  const UffFile file =
      ReadUff(std::string(FEMUP_TEST_DATA_DIR) + "/uff/vki_heat_engine_housing.unv");
  ASSERT_EQ(file.headers.size(), 5u);
  const int numbers[5] = {151, 164, 2411, 2412, 2414};
  const long long lines[5] = {2, 12, 18, 41, 60};
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(file.headers[i].number, numbers[i]);
    EXPECT_EQ(file.headers[i].line, lines[i]);
    EXPECT_EQ(file.headers[i].index, i == 2 ? 0 : -1);
  }
  EXPECT_EQ(file.notes.size(), 4u);
  ASSERT_EQ(file.Nodes().size(), 1u);
  const UffNodes& n = *file.Nodes()[0];
  EXPECT_EQ(n.dataset, 2411);
  ASSERT_EQ(n.nodes.size(), 10u);
  EXPECT_EQ(n.nodes[0].color, 11);
  EXPECT_DOUBLE_EQ(n.nodes[0].xyz[0], -171.1755676269531);
  EXPECT_DOUBLE_EQ(n.nodes[0].xyz[1], 103.6403427124023);
  EXPECT_DOUBLE_EQ(n.nodes[0].xyz[2], 138.4829101562500);
  EXPECT_EQ(n.nodes[9].label, 10);
  EXPECT_DOUBLE_EQ(n.nodes[9].xyz[0], -147.6755676269531);
  EXPECT_DOUBLE_EQ(n.nodes[9].xyz[2], 147.4829101562500);
  EXPECT_EQ(n.nodes[9].line, 37);
}

TEST(UffRealData, ComplexModeWithValuesRunTogether) {
  // tests/data/uff/pyuff_uff55_complex_mode.uff: analysis type 3, data type 5,
  // 3 values per node, mode 1; record 8 "-1.111111E-01 4.111111E+01
  // 4.111111E+03-3.111111E+03-1.111110E+05-2.111110E+05" (the last fields run
  // together); a record 10 with "0.000000E+00-4.111111E-02".
  const UffFile file =
      ReadUff(std::string(FEMUP_TEST_DATA_DIR) + "/uff/pyuff_uff55_complex_mode.uff");
  ASSERT_EQ(file.ModeShapes().size(), 1u);
  const UffModeShape& m = *file.ModeShapes()[0];
  EXPECT_EQ(m.analysis_type, UffAnalysisType::kComplexFirstOrder);
  EXPECT_TRUE(m.complex_data);
  EXPECT_EQ(m.mode_number, 1);
  EXPECT_EQ(m.id_lines[0], "TESTTEST:Cfg=0:C1:trans:111121");
  EXPECT_EQ(m.eigenvalue, std::complex<double>(-1.111111e-01, 4.111111e+01));
  EXPECT_EQ(m.modal_a, std::complex<double>(4.111111e+03, -3.111111e+03));
  EXPECT_EQ(m.modal_b, std::complex<double>(-1.111110e+05, -2.111110e+05));
  EXPECT_EQ(m.nodes, (std::vector<int>{111111, 60101}));
  EXPECT_EQ(m.node_lines, (std::vector<long long>{11, 13}));
  EXPECT_EQ(m.values(0, 1), std::complex<double>(1.111111e-01, 9.111111e-02));
  EXPECT_EQ(m.values(1, 2), std::complex<double>(-4.111111e-02, -1.111111e-02));
}

// ---------------------------------------------------------------------------
// Tolerance.

TEST(UffTolerance, FortranExponentsAndWideFields) {
  // D exponents in record 7 and the values, lower case too, an exponent
  // without its letter (Fortran's form for three digits), a leading '+'.
  const std::string text =
      "    -1\n    58\nD exponents\nNONE\nNONE\nNONE\nNONE\n"
      "    1         0    0         0 NONE               0   0 NONE               0   0\n"
      "         4         5         1  0.00000D+00  1.00000D-03  0.00000D+00\n"
      "        17    0    0    0 Time                 s\n"
      "         1    0    0    0 Signal               V\n"
      "         0    0    0    0 NONE                 NONE\n"
      "         0    0    0    0 NONE                 NONE\n"
      "   1.00000000000D+03  -2.50000000000d-01   +3.00000000000E+00\n"
      "   0.12345678901-105  -1.00000000000D+000\n"
      "    -1\n";
  const UffFile file = ParseUff(text, "d.uff");
  ASSERT_EQ(file.Functions().size(), 1u);
  const UffFunction& f = *file.Functions()[0];
  EXPECT_DOUBLE_EQ(f.abscissa_increment, 1e-3);
  ASSERT_EQ(f.y.size(), 5);
  EXPECT_DOUBLE_EQ(f.y(0).real(), 1000.0);
  EXPECT_DOUBLE_EQ(f.y(1).real(), -0.25);
  EXPECT_DOUBLE_EQ(f.y(2).real(), 3.0);
  EXPECT_DOUBLE_EQ(f.y(3).real(), 0.12345678901e-105);
  EXPECT_DOUBLE_EQ(f.y(4).real(), -1.0);
  // Short records: labels shorter than their field, the last line short.
  EXPECT_EQ(f.ordinate_axis.units, "V");

  // Values that fill their field with no blank between them (E20.12 with a
  // three-digit exponent) are read by the columns of the layout.
  const std::string glued = Replace(
      Replace(text, "   1.00000000000D+03  -2.50000000000d-01   +3.00000000000E+00",
              "-1.234567890123E-100-2.500000000000E+01   3.00000000000E+00"),
      "   0.12345678901-105  -1.00000000000D+000",
      "             1.0E+00-9.999999999999E+199");
  const UffFile glued_file = ParseUff(glued, "g.uff");
  const UffFunction& g = *glued_file.Functions().at(0);
  EXPECT_DOUBLE_EQ(g.y(0).real(), -1.234567890123E-100);
  EXPECT_DOUBLE_EQ(g.y(1).real(), -25.0);
  EXPECT_DOUBLE_EQ(g.y(4).real(), -9.999999999999E+199);
}

TEST(UffTolerance, PyuffByteCountForComplexBinaryData) {
  // pyuff writes the byte count of num_pts doubles also for complex data;
  // record 7 and the end marker right after the values settle it.
  const UffFunction f = MakeFunction(UffOrdinateType::kComplexDouble, true, true, 4);
  std::string text = FormatUff({f}, "p.uff");
  text = Replace(text, "          11          64", "          11          32");
  const UffFile file = ParseUff(text, "p.uff");
  ASSERT_EQ(file.Functions().size(), 1u);
  ExpectSameFunction(f, *file.Functions()[0], 0.0, 0.0);
  ASSERT_EQ(file.notes.size(), 1u);
  EXPECT_NE(file.notes[0].find("declares 32 bytes, record 7 implies 64"),
            std::string::npos)
      << file.notes[0];
  // Without the end marker after them the count is an error.
  const std::string broken = text.substr(0, text.size() - 7) + "xx\n    -1\n";
  ExpectError(broken, "p.uff", {"p.uff: line 2", "number of bytes"});
}

TEST(UffTolerance, BigEndianIeeeBinary) {
  const UffFunction f = MakeFunction(UffOrdinateType::kRealSingle, false, true, 6);
  std::string text = FormatUff({f}, "be.uff");
  // Swap each 4-byte value and declare big-endian ordering.
  const size_t end = text.rfind("    -1\n");
  const size_t bytes = 6 * 2 * 4;
  const size_t start = end - bytes;
  for (size_t k = start; k < end; k += 4) {
    std::swap(text[k], text[k + 3]);
    std::swap(text[k + 1], text[k + 2]);
  }
  text = Replace(text, "    58b     1     2", "    58b     2     2");
  const UffFile file = ParseUff(text, "be.uff");
  ASSERT_EQ(file.Functions().size(), 1u);
  ExpectSameFunction(f, *file.Functions()[0], 0.0, 1e-7);
}

TEST(UffTolerance, BinaryValuesFollowedByANewlineAndCrlfRecords) {
  const UffFunction f = MakeFunction(UffOrdinateType::kRealDouble, true, true, 3);
  const std::string text = FormatUff({f}, "n.uff");
  // Records 1-11 end at the 13th line break; the binary values follow.
  size_t binary_start = 0;
  for (int i = 0; i < 13; ++i) binary_start = text.find('\n', binary_start) + 1;
  const size_t end = text.rfind("    -1\n");
  const std::string variant = ToCrlf(text.substr(0, binary_start)) +
                              text.substr(binary_start, end - binary_start) + "\r\n" +
                              ToCrlf(text.substr(end));
  const UffFile file = ParseUff(variant, "n.uff");
  ASSERT_EQ(file.Functions().size(), 1u);
  EXPECT_TRUE(file.notes.empty());
  ExpectSameFunction(f, *file.Functions()[0], 0.0, 0.0);
}

// ---------------------------------------------------------------------------
// Malformed files.

class UffMalformed : public ::testing::Test {
 protected:
  std::string catman_ = ReadText(kRealData + "/catman_time_history.uff");
  std::vector<std::string> lines_ = Lines(catman_);

  // The catman file with lines [first, last] (1-based) replaced by `with`.
  std::string Without(size_t first, size_t last, const std::string& with = "") const {
    std::string out;
    for (size_t i = 1; i <= lines_.size(); ++i) {
      if (i == first) out += with;
      if (i >= first && i <= last) continue;
      out += lines_[i - 1] + "\n";
    }
    return out;
  }
};

TEST_F(UffMalformed, TruncatedRecord) {
  // The file ends after record 9.
  ExpectError(
      Without(12, 17), "cut.uff",
      {"cut.uff: line 12", "dataset 58 record 10", "ordinate denominator", "truncated"});
  // The end marker comes after 12 of the 13 values.
  ExpectError(
      Without(16, 16), "short.uff",
      {"short.uff: line 16", "record 12 (data values)", "after 12 of 13", "truncated"});
  // No end marker at all.
  ExpectError(Without(17, 17), "open.uff", {"open.uff: line", "end", "'    -1'"});
  // A binary dataset whose values stop early.
  const UffFunction f = MakeFunction(UffOrdinateType::kRealDouble, true, true, 8);
  const std::string text = FormatUff({f}, "b.uff");
  ExpectError(text.substr(0, text.size() - 30), "b.uff",
              {"b.uff: line 14", "dataset 58b record 12", "64 bytes", "truncated"});
}

TEST_F(UffMalformed, BadNumber) {
  ExpectError(Replace(catman_, "-3.90210E+00", "-3.9x210E+00"), "bad.uff",
              {"bad.uff: line 15", "dataset 58 record 12 (data values)", "value 7",
               "'-3.9x210E+00'"});
  ExpectError(Replace(catman_, "-3.90210E+00", "         NaN"), "nan.uff",
              {"nan.uff: line 15", "record 12", "finite", "'NaN'"});
  ExpectError(
      Replace(catman_, "5.00000E-005", "5.00000E-0x5"), "r7.uff",
      {"r7.uff: line 9", "record 7", "field 5 (abscissa increment)", "'5.00000E-0x5'"});
  ExpectError(Replace(catman_, "        17    0", "        1x    0"), "r8.uff",
              {"r8.uff: line 10", "record 8 (abscissa data characteristics)",
               "field 1 (specific data type, columns 1-10)", "'1x'"});
  ExpectError(Replace(catman_, "    1         0    0", "    ?         0    0"), "r6.uff",
              {"r6.uff: line 8", "record 6", "field 1 (function type, columns 1-5)"});
}

TEST_F(UffMalformed, WrongFieldCount) {
  ExpectError(
      Without(9, 9, "         2        13         1\n"), "data.uff",
      {"data.uff: line 9", "dataset 58 record 7",
       "expected 6 fields (ordinate data type, number of points, abscissa spacing, "
       "abscissa minimum, abscissa increment, z-axis value), got 3"});
  // A data line holding more values than record 7 declares.
  ExpectError(Replace(catman_, " -5.84096E+00   ", " -5.84096E+00 -1.00000E+00   "),
              "more.uff", {"more.uff: line 16", "record 12", "more values"});
  // Dataset 15 with a missing coordinate.
  ExpectError(
      "    -1\n    15\n         1         0         0         0  1.0  2.0\n    -1\n",
      "n.uff", {"n.uff: line 3", "dataset 15 node record", "expected 7 fields", "got 6"});
}

TEST_F(UffMalformed, InvalidCodes) {
  ExpectError(Replace(catman_, "         2        13", "         3        13"), "t.uff",
              {"t.uff: line 9", "field 1 (ordinate data type)", "found 3"});
  ExpectError(Replace(catman_, "        13         1", "        13         2"), "s.uff",
              {"s.uff: line 9", "field 3 (abscissa spacing)"});
  ExpectError("garbage\n" + catman_, "g.uff", {"g.uff: line 1", "'    -1'", "'garbage'"});
  ExpectError("    -1\n  5x8\n", "h.uff", {"h.uff: line 2", "dataset number"});
  const std::string shape =
      "    -1\n    55\nNONE\nNONE\nNONE\nNONE\nNONE\n"
      "         1         2         2         8         3         3\n";
  ExpectError(shape, "d.uff",
              {"d.uff: line 8", "dataset 55 record 6", "field 5 (data type)"});
}

TEST_F(UffMalformed, Unknown58bFormat) {
  const UffFunction f = MakeFunction(UffOrdinateType::kRealDouble, true, true, 4);
  const std::string text = FormatUff({f}, "b.uff");
  ExpectError(Replace(text, "    58b     1     2", "    58b     1     1"), "vms.uff",
              {"vms.uff: line 2", "dataset 58b header", "field 2 (floating-point format)",
               "1 (DEC VMS) is not supported"});
  ExpectError(Replace(text, "    58b     1     2", "    58b     1     3"), "ibm.uff",
              {"ibm.uff: line 2", "floating-point format", "IBM"});
  ExpectError(Replace(text, "    58b     1     2", "    58b     3     2"), "bo.uff",
              {"bo.uff: line 2", "field 1 (byte ordering)", "found 3"});
  ExpectError(
      Replace(text, "    58b     1     2          11", "    58b     1     2          12"),
      "n.uff", {"n.uff: line 2", "field 3 (number of ASCII lines)", "found 12"});
  ExpectError(
      Replace(text,
              "    58b     1     2          11          32     0     0           0"
              "           0",
              "    58b     1     2"),
      "few.uff", {"few.uff: line 2", "expected at least 4 fields", "got 2"});
}

TEST(UffErrors, MissingFileAndWriterChecks) {
  try {
    ReadUff("/nonexistent/file.uff");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/file.uff"), std::string::npos);
  }
  UffFunction f = MakeFunction(UffOrdinateType::kRealDouble, true, false, 4);
  auto expect_write_error = [](const UffDataset& d, const std::string& part) {
    try {
      FormatUff({d}, "w.uff");
      ADD_FAILURE() << "no error for " << part;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("w.uff"), std::string::npos) << message;
      EXPECT_NE(message.find(part), std::string::npos) << message;
    }
  };
  UffFunction g = f;
  g.y(2) = {1.0, 0.5};
  expect_write_error(g, "imaginary part");
  g = f;
  g.y(1) = std::nan("");
  expect_write_error(g, "not finite");
  g = f;
  g.ordinate_axis.label = "a label longer than twenty characters";
  expect_write_error(g, "ordinate (numerator) axis label");
  g = f;
  g.function_type = 123456;
  expect_write_error(g, "function type: 123456 does not fit 5 columns");
  g = f;
  g.even_spacing = false;
  g.x.resize(2);
  expect_write_error(g, "one abscissa value per point");
  UffModeShape m = MakeShape(UffAnalysisType::kNormalMode, false, 3);
  m.values(1, 1) = {0.0, 1.0};
  expect_write_error(m, "imaginary parts");
  m = MakeShape(UffAnalysisType::kNormalMode, false, 3);
  m.nodes.pop_back();
  expect_write_error(m, "rows for 3 nodes");
}

}  // namespace
}  // namespace femup
