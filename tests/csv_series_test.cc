// CSV time series: delimiter detection, tolerated forms, round trips, and the
// checks (uniform step, row width, whole finite numbers) with their messages.
#include "femup/core/io/csv_series.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/io/uff.h"
#include "scratch_dir.h"

namespace femup {
namespace {

namespace fs = std::filesystem;

const std::string kRealData = std::string(FEMUP_TEST_DATA_DIR) + "/realdata";

using testing::ScratchDir;

// Parses `text` as a file called `name`, expecting an InputError whose message
// holds each of `parts`.
void ExpectError(const std::string& text, const std::string& name,
                 const std::vector<std::string>& parts) {
  try {
    ParseCsvSeries(text, name);
    ADD_FAILURE() << "no InputError for " << name;
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos)
          << "message: " << message << "\nlacks: " << part;
    }
  }
}

CsvSeries MakeSeries(char delimiter) {
  CsvSeries s;
  s.time_name = "time [s]";
  s.channel_names = {"acc 1", "force; N", "say \"hi\""};
  s.delimiter = delimiter;
  const int n = 50;
  s.time.resize(n);
  s.values.resize(n, 3);
  for (int k = 0; k < n; ++k) {
    s.time(k) = 0.25 + k / 2048.0;
    s.values(k, 0) = std::sin(0.1 * k) * 1e-7;
    s.values(k, 1) = -1.0 / (k + 3.0);
    s.values(k, 2) = std::exp(0.3 * k);
  }
  return s;
}

TEST(CsvSeries, RoundTripWithEachDelimiterIsExact) {
  ScratchDir dir;
  for (char delimiter : {',', ';', '\t'}) {
    const CsvSeries s = MakeSeries(delimiter);
    const std::string path = dir.File("series.csv");
    WriteCsvSeries(path, s);
    const CsvSeries r = ReadCsvSeries(path);
    EXPECT_EQ(r.delimiter, delimiter);
    EXPECT_EQ(r.time_name, s.time_name);
    EXPECT_EQ(r.channel_names, s.channel_names);
    EXPECT_EQ(r.time, s.time);
    EXPECT_EQ(r.values, s.values);
    EXPECT_DOUBLE_EQ(r.sample_rate_hz, 2048.0);
    EXPECT_DOUBLE_EQ(r.time_step, 1.0 / 2048.0);
  }
}

TEST(CsvSeries, CommentsBlankLinesCrlfBomQuotesAndBlanks) {
  const std::string text =
      "\xEF\xBB\xBF# logger export\r\n"
      "# sample rate 1 kHz\r\n"
      "\r\n"
      " time , \"acc, x\" ,acc_y\r\n"
      "0.000, 1.5e-3,  -2\r\n"
      "# a comment between rows\r\n"
      "0.001,+2.5E-3,-3.0\r\n"
      "\r\n"
      "0.002,3.5e-3,-4";  // no line break at the end
  const CsvSeries s = ParseCsvSeries(text, "log.csv");
  EXPECT_EQ(s.delimiter, ',');
  EXPECT_EQ(s.time_name, "time");
  ASSERT_EQ(s.channel_names.size(), 2u);
  EXPECT_EQ(s.channel_names[0], "acc, x");
  EXPECT_EQ(s.channel_names[1], "acc_y");
  ASSERT_EQ(s.time.size(), 3);
  EXPECT_DOUBLE_EQ(s.values(1, 0), 2.5e-3);
  EXPECT_DOUBLE_EQ(s.values(2, 1), -4.0);
  EXPECT_NEAR(s.sample_rate_hz, 1000.0, 1e-9);
}

TEST(CsvSeries, DetectsSemicolonAndTab) {
  const CsvSeries a = ParseCsvSeries("t;a;b\n0;1;2\n0.5;3;4\n1.0;5;6\n", "a.csv");
  EXPECT_EQ(a.delimiter, ';');
  EXPECT_EQ(a.channel_names.size(), 2u);
  EXPECT_DOUBLE_EQ(a.sample_rate_hz, 2.0);
  // Tab-separated with names that hold commas.
  const CsvSeries b = ParseCsvSeries("t\tacc (m/s2, x)\n0\t1\n0.1\t2\n", "b.csv");
  EXPECT_EQ(b.delimiter, '\t');
  ASSERT_EQ(b.channel_names.size(), 1u);
  EXPECT_EQ(b.channel_names[0], "acc (m/s2, x)");
}

TEST(CsvSeries, TimesRoundedToTheirPrintedDigitsPass) {
  // 3 kHz with the time printed to 6 decimals: steps of 0.000333 and 0.000334.
  std::ostringstream text;
  text << "time,x\n";
  char line[64];
  for (int k = 0; k < 3000; ++k) {
    std::snprintf(line, sizeof line, "%.6f,%d\n", k / 3000.0, k % 7);
    text << line;
  }
  const CsvSeries s = ParseCsvSeries(text.str(), "rounded.csv");
  EXPECT_NEAR(s.sample_rate_hz, 3000.0, 0.01);
  // A missing sample is found, at the row after the gap.
  std::string missing = text.str();
  const size_t at = missing.find("0.100000,");
  missing.erase(at, missing.find('\n', at) - at + 1);
  ExpectError(missing, "missing.csv",
              {"missing.csv: line 302", "column 1 (time)", "not uniform"});
}

TEST(CsvSeries, CatmanTimeHistoryThroughCsv) {
  // The real catman export (UFF 58, 20 kHz) written as CSV and read back.
  const UffFile uff = ReadUff(kRealData + "/catman_time_history.uff");
  const UffFunction& f = *uff.Functions().at(0);
  CsvSeries s;
  s.time_name = f.abscissa_axis.label;
  s.channel_names = {f.ordinate_axis.label + " [" + f.ordinate_axis.units + "]"};
  s.time = f.x;
  s.values = f.y.real();
  ScratchDir dir;
  WriteCsvSeries(dir.File("catman.csv"), s);
  const CsvSeries r = ReadCsvSeries(dir.File("catman.csv"));
  EXPECT_NEAR(r.sample_rate_hz, 20000.0, 1e-6);
  EXPECT_EQ(r.channel_names[0], "1x [m/s²]");
  EXPECT_EQ(r.values, s.values);
  EXPECT_EQ(r.time.size(), 13);
}

TEST(CsvSeries, ErrorsNameFileLineAndColumn) {
  ExpectError("time,a,b\n0,1,2\n0.1,1.5x,2\n", "bad.csv",
              {"bad.csv: line 3", "column 2 (a)", "'1.5x'"});
  ExpectError("time,a,b\n0,1,2\n0.1,nan,2\n", "nan.csv",
              {"nan.csv: line 3", "column 2 (a)", "finite", "'nan'"});
  ExpectError("time,a,b\n0,1,2\n0.1,1,\n", "empty.csv",
              {"empty.csv: line 3", "column 3 (b)", "empty field"});
  ExpectError("time,a,b\n0,1,2\n0.1,1\n", "width.csv",
              {"width.csv: line 3", "expected 3 fields", "got 2"});
  ExpectError("time;a\n0;1,5\n1;2,5\n", "comma.csv",
              {"comma.csv: line 2", "column 2 (a)", "decimal separator"});
  ExpectError("time,a\n0,1\n0.1,2\n0.2,3\n0.4,4\n0.5,5\n", "step.csv",
              {"step.csv: line 5", "column 1 (time)", "not uniform"});
  // 1 kHz with times printed to the millisecond: a missing sample is found.
  ExpectError("time,a\n0.000,1\n0.001,2\n0.002,3\n0.004,4\n0.005,5\n", "ms.csv",
              {"ms.csv: line 5", "column 1 (time)", "not uniform"});
  ExpectError("time,a\n0,1\n0.1,2\n0.1,3\n", "repeat.csv",
              {"repeat.csv: line 4", "column 1 (time)", "does not increase"});
  ExpectError("time,a\n0,1\n", "one.csv", {"one.csv: line 2", "at least two"});
  ExpectError("time,a\n", "none.csv", {"none.csv: line 2", "no data rows"});
  ExpectError("time\n0\n1\n", "single.csv", {"single.csv: line 1", "header"});
  ExpectError("# nothing\n", "empty_file.csv", {"empty_file.csv", "no header"});
  ExpectError("time,\"a\n0,1\n", "quote.csv",
              {"quote.csv: line 1", "unterminated quote"});
  try {
    ReadCsvSeries("/nonexistent/series.csv");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/series.csv"), std::string::npos);
  }
}

TEST(CsvSeries, WriterChecks) {
  CsvSeries s = MakeSeries(',');
  s.values(3, 1) = std::nan("");
  EXPECT_THROW(FormatCsvSeries(s, "w.csv"), InputError);
  s = MakeSeries(',');
  s.channel_names.pop_back();
  EXPECT_THROW(FormatCsvSeries(s, "w.csv"), InputError);
  s = MakeSeries('|');
  EXPECT_THROW(FormatCsvSeries(s, "w.csv"), InputError);
}

}  // namespace
}  // namespace femup
