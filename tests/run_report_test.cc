// WriteRunReport: report.html staged with the other outputs, holding the
// summary, every plot (captioned from its gnuplot script), the study file, the
// warnings and the files written; committed with them, or not at all.
#include "femup/reporting/run_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "femup/reporting/html_page.h"
#include "femup/reporting/output_dir.h"
#include "femup/reporting/plot.h"
#include "scratch_dir.h"

namespace femup {
namespace {

namespace fs = std::filesystem;
using testing::ScratchDir;

const std::string kPng = std::string("\x89PNG\r\n\x1a\n", 8) + "fake image data";

std::string Read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

RunReport ExampleReport(const std::string& study_path) {
  RunReport report;
  report.command = "run";
  report.name = "chain";
  report.command_line = "femup run chain.yaml -o out";
  report.version = "femup 0.1.0";
  report.inputs = {study_path};
  report.summary = "parameter   estimate\nmass[1]     -0.0087\n";
  report.warnings = {"solved system: rank 12 of 13"};
  return report;
}

TEST(RunReport, HoldsSummaryPlotsStudyWarningsAndFiles) {
  ScratchDir scratch;
  const std::string study = scratch.File("chain.yaml");
  std::ofstream(study) << "name: chain\nmodel: {type: chain}\n";
  OutputDir dir(scratch.File("out"));
  dir.WriteText("result.json", "{}\n");
  dir.WriteText("factors.png", kPng);
  dir.WriteText("factors.gp",
                "set output 'factors.png'\n# figure panel 1 'chain: correction factors'\n"
                "# figure panel 2 'chain: errors'\n");
  dir.WriteText("shapes.png", kPng);  // no script: captioned by its name
  WriteRunReport(ExampleReport(study), &dir);
  dir.Commit();

  const std::string html = Read(scratch.File("out/report.html"));
  EXPECT_NE(html.find("<h1>femup run: chain</h1>"), std::string::npos);
  EXPECT_NE(html.find("femup run chain.yaml -o out"), std::string::npos);
  EXPECT_NE(html.find("mass[1]     -0.0087"), std::string::npos);
  EXPECT_NE(html.find("<li>solved system: rank 12 of 13</li>"), std::string::npos);
  EXPECT_NE(html.find("model: {type: chain}"), std::string::npos);  // the study itself
  EXPECT_NE(html.find("data:image/png;base64," + Base64Encode(kPng)), std::string::npos);
  EXPECT_NE(html.find("chain: correction factors · chain: errors (factors.png)"),
            std::string::npos);
  EXPECT_NE(html.find("<figcaption>shapes.png</figcaption>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"result.json\">result.json</a>"), std::string::npos);
  EXPECT_NE(html.find("results (JSON)"), std::string::npos);
  // Sections in reading order.
  EXPECT_LT(html.find("id=\"warnings\""), html.find("id=\"summary\""));
  EXPECT_LT(html.find("id=\"summary\""), html.find("id=\"plots\""));
  EXPECT_LT(html.find("id=\"plots\""), html.find("id=\"inputs\""));
  EXPECT_LT(html.find("id=\"inputs\""), html.find("id=\"files\""));
}

TEST(RunReport, LeavesOutWhatARunDidNotHave) {
  ScratchDir scratch;
  OutputDir dir(scratch.File("out"));
  dir.WriteText("result.json", "{}\n");
  dir.Stage("missing.png");  // staged, never rendered (no gnuplot)
  RunReport report = ExampleReport(scratch.File("absent.uff"));
  report.warnings.clear();
  const std::string html = RenderRunReport(report, &dir);
  EXPECT_EQ(html.find("id=\"plots\""), std::string::npos);
  EXPECT_EQ(html.find("id=\"warnings\""), std::string::npos);
  EXPECT_EQ(html.find("missing.png"), std::string::npos);
  // An input that cannot be read is named, not shown.
  EXPECT_NE(html.find("absent.uff"), std::string::npos);
}

TEST(RunReport, NamesADataInputWithItsSizeInsteadOfShowingIt) {
  ScratchDir scratch;
  const std::string data = scratch.File("records.uff");
  std::ofstream(data) << std::string(2048, 'x');
  OutputDir dir(scratch.File("out"));
  RunReport report = ExampleReport(data);
  const std::string html = RenderRunReport(report, &dir);
  EXPECT_NE(html.find("records.uff (2 KiB)"), std::string::npos);
  EXPECT_EQ(html.find("xxxxxxxx"), std::string::npos);
}

TEST(RunReport, IsNotWrittenWhenTheRunIsNotCommitted) {
  ScratchDir scratch;
  {
    OutputDir dir(scratch.File("out"));
    dir.WriteText("result.json", "{}\n");
    WriteRunReport(ExampleReport(scratch.File("chain.yaml")), &dir);
  }  // a failure before Commit
  EXPECT_FALSE(fs::exists(scratch.File("out/report.html")));
  EXPECT_FALSE(fs::exists(scratch.File("out")));
}

TEST(RunReport, EmbedsARealGnuplotFigure) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot is not installed";
  ScratchDir scratch;
  OutputDir dir(scratch.File("out"));
  Figure figure;
  Plot plot;
  plot.title = "frequency errors";
  plot.series.push_back(
      {"model", PlotSeries::Style::kLinesPoints, {1, 2}, {0.5, -1.0}, {}, {}});
  figure.panels.push_back(plot);
  dir.Stage("errors.dat");
  dir.Stage("errors.gp");
  const std::string png_path = dir.Stage("errors.png");
  ASSERT_TRUE(RenderFigure(figure, png_path.substr(0, png_path.size() - 4)).rendered);
  const std::string html = RenderRunReport(ExampleReport(scratch.File("a.yaml")), &dir);
  const std::string png = Read(dir.Stage("errors.png"));
  ASSERT_TRUE(LooksLikePng(png));
  EXPECT_NE(html.find(Base64Encode(png)), std::string::npos);
  EXPECT_NE(html.find("frequency errors (errors.png)"), std::string::npos);
}

}  // namespace
}  // namespace femup
