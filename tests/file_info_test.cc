// `femup info` (femup/studies/file_info.h): what DescribeFile finds in a UFF
// file of every dataset kind written here, in the bundled vendor files, in a
// CSV series with units and in Matrix Market files; bad input named.
#include "femup/studies/file_info.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "expect_error.h"
#include "femup/core/errors.h"
#include "scratch_dir.h"

namespace femup {
namespace {

const std::string kData = std::string(FEMUP_TEST_DATA_DIR);

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

using testing::ExpectError;

void ExpectHas(const std::string& text, const std::string& needle) {
  EXPECT_NE(text.find(needle), std::string::npos) << "'" << needle << "' in:\n" << text;
}

// Nodes, a normal and a complex mode, a time history and an FRF, and a
// dataset femup does not read.
std::string MixedUff() {
  UffNodes nodes;
  nodes.nodes = {{1, 0, 0, 0, {0.0, 0.0, 0.0}},
                 {2, 0, 0, 0, {2.0, -1.0, 0.0}},
                 {3, 0, 0, 0, {1.0, 0.5, 3.0}}};
  UffModeShape normal;
  normal.mode_number = 3;
  normal.frequency_hz = 142.0625;
  normal.viscous_damping_ratio = 0.0125;
  normal.modal_mass = 2.5;
  normal.nodes = {1, 2, 3};
  normal.values = Eigen::MatrixXcd::Ones(3, 3);
  UffModeShape complex_mode = normal;
  complex_mode.analysis_type = UffAnalysisType::kComplexFirstOrder;
  complex_mode.complex_data = true;
  complex_mode.mode_number = 4;
  // lambda = -6 + 120 i rad/s: |lambda| = sqrt(14436) = 120.1499..., by hand
  // 19.122452 Hz and damping 6 / 120.1499 = 0.0499376.
  complex_mode.eigenvalue = {-6.0, 120.0};
  complex_mode.values(1, 2) = {0.5, 0.25};
  UffFunction time;
  time.function_type = 1;
  time.response_node = 5;
  time.response_direction = 2;
  time.abscissa_increment = 0.01;
  time.abscissa_axis = {17, 0, 0, 0, "Time", "s"};
  time.ordinate_axis = {12, 1, 0, 0, "Acceleration", "m/s^2"};
  time.y = Eigen::VectorXcd::Ones(4);
  UffFunction frf;
  frf.function_type = 4;
  frf.ordinate_type = UffOrdinateType::kComplexSingle;
  frf.response_node = 1;
  frf.response_direction = 1;
  frf.reference_node = 3;
  frf.reference_direction = -3;
  frf.abscissa_increment = 0.5;
  frf.abscissa_axis = {18, 0, 0, 0, "Frequency", "Hz"};
  frf.ordinate_axis = {12, 1, 0, 0, "Accel", "m/s^2"};
  frf.denominator_axis = {13, 0, 1, 0, "Force", "N"};
  frf.y = Eigen::VectorXcd::Constant(8, {1.0, -1.0});
  frf.binary = true;
  return FormatUff({nodes, normal, complex_mode, time, frf}, "mixed.uff") +
         "    -1\n  2412\n         1        91         1         1         0         3\n"
         "         1         2         3\n    -1\n";
}

TEST(FileInfo, UffDatasetsOfEveryKind) {
  testing::ScratchDir dir;
  const std::string path = dir.File("mixed.uff");
  WriteText(path, MixedUff());
  const FileInfo info = DescribeFile(path);
  EXPECT_EQ(info.format, "uff");
  ASSERT_TRUE(info.uff.has_value());
  ASSERT_EQ(info.uff->headers.size(), 6u);
  const std::string text = FileInfoReport(info);
  ExpectHas(text, path + ": Universal File Format, 6 dataset(s), 5 read, 1 skipped");
  ExpectHas(text,
            "dataset 15 (line 2): nodes (single precision): 3 (1-3); X 0 .. 2, Y -1 .. "
            "0.5, Z 0 .. 3; coordinate systems 0");
  ExpectHas(text,
            "normal mode 3: 142.062 Hz, damping 1.25 %, modal mass 2.5; 3 nodes "
            "(1-3) x 3 values (+X +Y +Z), translations, displacement, real");
  ExpectHas(text,
            "complex mode (first order) 4: 19.1225 Hz, damping 4.994 % (eigenvalue "
            "-6 + 120i rad/s)");
  ExpectHas(text,
            "time response: response 5 +Y, reference 0 scalar; 4 points, real "
            "double, sample rate 100 Hz (step 0.01 s from 0 s); ordinate "
            "'Acceleration' [m/s^2], abscissa 'Time' [s]");
  ExpectHas(text, "dataset 58b (line");
  ExpectHas(text,
            "frequency response function: response 1 +X, reference 3 -Z; 8 "
            "points, complex single (binary), frequency step 0.5 Hz from 0 Hz; "
            "ordinate 'Accel' [m/s^2] / 'Force' [N], abscissa 'Frequency' [Hz]");
  ExpectHas(text, "dataset 2412 (line ");
  ExpectHas(text, "not read");
  EXPECT_EQ(text.find("note:"), std::string::npos) << text;  // the skip is said above

  const nlohmann::json j = nlohmann::json::parse(FileInfoJson(info));
  EXPECT_EQ(j["format"], "uff");
  ASSERT_EQ(j["datasets"].size(), 6u);
  EXPECT_EQ(j["datasets"][0]["line"], 2);
  EXPECT_EQ(j["datasets"][0]["nodes"], 3);
  EXPECT_EQ(j["datasets"][0]["extent"]["max"][2], 3.0);
  EXPECT_EQ(j["datasets"][1]["analysis_type"], 2);
  EXPECT_NEAR(j["datasets"][1]["frequency_hz"].get<double>(), 142.0625, 1e-3);
  EXPECT_EQ(j["datasets"][1]["directions"], nlohmann::json({"+X", "+Y", "+Z"}));
  EXPECT_EQ(j["datasets"][1]["nodes"], nlohmann::json({1, 2, 3}));
  EXPECT_NEAR(j["datasets"][2]["frequency_hz"].get<double>(), 19.12245151033719, 1e-12);
  EXPECT_NEAR(j["datasets"][2]["damping_ratio"].get<double>(), 0.04993761694389223,
              1e-15);
  EXPECT_EQ(j["datasets"][3]["function_type"], 1);
  EXPECT_NEAR(j["datasets"][3]["sample_rate_hz"].get<double>(), 100.0, 1e-9);
  EXPECT_EQ(j["datasets"][3]["response"]["direction"], "+Y");
  EXPECT_EQ(j["datasets"][3]["axes"]["ordinate"]["units"], "m/s^2");
  EXPECT_EQ(j["datasets"][4]["binary"], true);
  EXPECT_NEAR(j["datasets"][4]["frequency_step_hz"].get<double>(), 0.5, 1e-12);
  EXPECT_EQ(j["datasets"][4]["points"], 8);
  EXPECT_EQ(j["datasets"][5]["dataset"], 2412);
  EXPECT_EQ(j["datasets"][5]["read"], false);
  EXPECT_EQ(j["notes"].size(), 1u);
}

TEST(FileInfo, VendorFiles) {
  // 2411 among datasets femup skips (tests/data/uff/README.md).
  const FileInfo vki = DescribeFile(kData + "/uff/vki_heat_engine_housing.unv");
  const std::string text = FileInfoReport(vki);
  ExpectHas(text, "5 dataset(s), 1 read, 4 skipped");
  ExpectHas(text,
            "dataset 2411 (line 18): nodes (double precision): 10 (1-10); X "
            "-171.176 .. -147.676, Y 96.997 .. 103.64, Z 138.483 .. 147.483");
  ExpectHas(text, "dataset 151 (line 2): not read");
  // A complex mode: 6.5430603 Hz and 0.27027 % by hand (uff_modes_test.cc).
  const FileInfo c = DescribeFile(kData + "/uff/pyuff_uff55_complex_mode.uff");
  const std::string ct = FileInfoReport(c);
  ExpectHas(ct,
            "complex mode (first order) 1: 6.54306 Hz, damping 0.2703 % (eigenvalue "
            "-0.111111 + 41.1111i rad/s); 2 nodes (60101, 111111) x 3 values (+X +Y "
            "+Z), translations, displacement, complex");
  ExpectHas(ct, "modes_file");
  // pyuff's normal mode with rotations.
  const std::string rt =
      FileInfoReport(DescribeFile(kData + "/realdata/uff55_translation_rotation.uff"));
  ExpectHas(rt,
            "normal mode 0: 97.013 Hz, damping 0 %, modal mass 0; 43 nodes (1-43) x 6 "
            "values (+X +Y +Z +RX +RY +RZ), translations and rotations, displacement");
}

TEST(FileInfo, CsvChannelsWithUnits) {
  testing::ScratchDir dir;
  const std::string path = dir.File("log.csv");
  WriteText(path,
            "time [s];acc1 [m/s^2];acc2 (g);force\n0;1;2;3\n0.002;1;2;3\n0.004;1;2;3\n");
  const FileInfo info = DescribeFile(path);
  ASSERT_TRUE(info.csv.has_value());
  EXPECT_EQ(info.csv->names, (std::vector<std::string>{"acc1", "acc2", "force"}));
  EXPECT_EQ(info.csv->units, (std::vector<std::string>{"m/s^2", "g", ""}));
  EXPECT_EQ(info.csv->time_units, "s");
  const std::string text = FileInfoReport(info);
  ExpectHas(text,
            "CSV time series, 3 rows, 3 channel(s), sample rate 500 Hz (step 0.002 s)");
  ExpectHas(text, "channel 1: acc1 [m/s^2]");
  ExpectHas(text, "channel 3: force\n");
  const nlohmann::json j = nlohmann::json::parse(FileInfoJson(info));
  EXPECT_EQ(j["rows"], 3);
  EXPECT_NEAR(j["sample_rate_hz"].get<double>(), 500.0, 1e-9);
  EXPECT_EQ(j["channels"][1]["units"], "g");
  EXPECT_EQ(j["delimiter"], ";");

  std::string name, units;
  SplitNameAndUnits(" v [mm/s] ", &name, &units);
  EXPECT_EQ(name, "v");
  EXPECT_EQ(units, "mm/s");
  SplitNameAndUnits("[s]", &name, &units);  // nothing before: a name, not units
  EXPECT_EQ(name, "[s]");
  EXPECT_EQ(units, "");
  SplitNameAndUnits("a ()", &name, &units);
  EXPECT_EQ(units, "");
}

TEST(FileInfo, MatrixMarket) {
  const FileInfo info = DescribeFile(kData + "/mm/symmetric_lower.mtx");
  ASSERT_TRUE(info.matrix.has_value());
  const MatrixMarketInfo& m = *info.matrix;
  EXPECT_EQ(m.format, "coordinate");
  EXPECT_EQ(m.field, "real");
  EXPECT_EQ(m.symmetry, "symmetric");
  EXPECT_EQ(m.rows, 4);
  EXPECT_EQ(m.cols, 4);
  EXPECT_EQ(m.entries, 8);
  EXPECT_TRUE(m.readable);
  EXPECT_EQ(m.nonzeros, 12);  // 8 stored, 4 of them on the diagonal
  ExpectHas(FileInfoReport(info),
            "Matrix Market matrix, 4 x 4, coordinate, real, symmetric, 8 stored entries");
  const FileInfo array = DescribeFile(kData + "/mm/array_general.mtx");
  EXPECT_EQ(array.matrix->entries, 6);
  EXPECT_TRUE(array.matrix->readable);

  testing::ScratchDir dir;
  WriteText(dir.File("c.mtx"),
            "%%MatrixMarket matrix coordinate complex hermitian\n"
            "% a comment\n2 2 1\n1 1 1.0 0.0\n");
  const FileInfo c = DescribeFile(dir.File("c.mtx"));
  EXPECT_FALSE(c.matrix->readable);
  EXPECT_EQ(c.matrix->field, "complex");
  ExpectHas(FileInfoReport(c), "femup does not read it: femup reads real or integer");
  const nlohmann::json j = nlohmann::json::parse(FileInfoJson(c));
  EXPECT_EQ(j["readable"], false);
  EXPECT_EQ(j["rows"], 2);
  // A readable header over a broken body: why, with the reader's line.
  WriteText(dir.File("short.mtx"),
            "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 1\n");
  const FileInfo s = DescribeFile(dir.File("short.mtx"));
  EXPECT_FALSE(s.matrix->readable);
  ExpectHas(s.matrix->problem, "short.mtx");

  WriteText(dir.File("bad.mtx"), "MatrixMarket matrix\n1 1 1\n");
  ExpectError([&] { DescribeFile(dir.File("bad.mtx")); },
              {dir.File("bad.mtx") + ": line 1", "banner"});
  WriteText(dir.File("nosize.mtx"),
            "%%MatrixMarket matrix coordinate real general\n% c\n");
  ExpectError([&] { DescribeFile(dir.File("nosize.mtx")); },
              {dir.File("nosize.mtx"), "before the size line"});
  WriteText(dir.File("badsize.mtx"),
            "%%MatrixMarket matrix coordinate real general\n2 x\n");
  ExpectError([&] { DescribeFile(dir.File("badsize.mtx")); },
              {dir.File("badsize.mtx") + ": line 2", "rows, columns, entries"});
}

TEST(FileInfo, UnknownOrUnreadableFilesAreNamed) {
  ExpectError([] { DescribeFile("/nowhere/x.wav"); },
              {"/nowhere/x.wav", "'.wav'", ".mtx"});
  ExpectError([] { DescribeFile("/nowhere/x.uff"); }, {"/nowhere/x.uff", "not found"});
  ExpectError([] { DescribeFile("/nowhere/x.mtx"); }, {"/nowhere/x.mtx", "not found"});
  ExpectError([] { DescribeFile("/nowhere/x.csv"); }, {"/nowhere/x.csv"});
  testing::ScratchDir dir;
  WriteText(dir.File("broken.uff"), "    -1\n    55\nNONE\n");
  ExpectError([&] { DescribeFile(dir.File("broken.uff")); },
              {dir.File("broken.uff") + ": line", "dataset 55"});
}

}  // namespace
}  // namespace femup
