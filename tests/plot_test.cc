#include "femup/reporting/plot.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/errors.h"

namespace femup {
namespace {

using Style = PlotSeries::Style;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

bool FileExists(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteExecutable(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  ASSERT_TRUE(out) << path;
  ASSERT_EQ(::chmod(path.c_str(), 0755), 0) << path;
}

uint32_t BigEndian32(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (size_t i = 0; i < 4; ++i) {
    value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
  }
  return value;
}

// Sets PATH for the scope of a test and restores it afterwards.
class ScopedPath {
 public:
  explicit ScopedPath(const std::string& path) {
    const char* old = std::getenv("PATH");
    had_path_ = old != nullptr;
    if (had_path_) old_path_ = old;
    ::setenv("PATH", path.c_str(), 1);
  }
  ~ScopedPath() {
    if (had_path_) {
      ::setenv("PATH", old_path_.c_str(), 1);
    } else {
      ::unsetenv("PATH");
    }
  }
  ScopedPath(const ScopedPath&) = delete;
  ScopedPath& operator=(const ScopedPath&) = delete;

 private:
  bool had_path_ = false;
  std::string old_path_;
};

PlotSeries Series(const std::string& title, Style style, std::vector<double> x,
                  std::vector<double> y) {
  PlotSeries series;
  series.title = title;
  series.style = style;
  series.x = std::move(x);
  series.y = std::move(y);
  return series;
}

// Two panels using every style: parameter bars with error bars on category
// ticks, and a log-scaled frequency response with a gap.
Figure EveryStyleFigure() {
  Plot parameters;
  parameters.title = "Updated parameters (k_{2}^x)";
  parameters.x_label = "parameter";
  parameters.y_label = "value / initial";
  parameters.x_tick_labels = {"added_mass[e2]", "k_{2}^x", "it's", "E@1 & ~2", "mass[1]"};
  parameters.series.push_back(
      Series("initial", Style::kBars, {1, 2, 3, 4, 5}, {1.0, 1.0, 1.0, 1.0, 1.0}));
  parameters.series.push_back(
      Series("updated_value", Style::kBars, {1, 2, 3, 4, 5}, {1.2, 0.8, 1.05, 0.9, 1.1}));
  PlotSeries bounds =
      Series("95% interval", Style::kErrorBars, {1, 2, 3, 4}, {1.2, 0.8, 1.05, 0.9});
  bounds.y_low = {1.1, 0.7, 0.95, 0.85};
  bounds.y_high = {1.3, 0.9, 1.15, 0.95};
  parameters.series.push_back(bounds);

  Plot response;
  response.title = "Frequency response";
  response.x_label = "frequency [Hz]";
  response.y_label = "|H| [m/N]";
  response.log_y = true;
  response.key_outside = true;
  std::vector<double> f;
  std::vector<double> h;
  std::vector<double> h2;
  for (int i = 0; i <= 60; ++i) {
    double freq = 1.0 + i * 0.5;
    f.push_back(freq);
    h.push_back(1.0 / std::abs(100.0 - freq * freq) + 1e-4);
    h2.push_back(1.0 / std::abs(120.0 - freq * freq) + 1e-4);
  }
  h[30] = kNaN;  // a gap, not an error
  response.series.push_back(Series("measured", Style::kPoints, f, h));
  response.series.push_back(Series("model", Style::kLines, f, h2));
  std::vector<double> peaks_x = {10.0, 10.95};
  std::vector<double> peaks_y = {0.05, 0.04};
  response.series.push_back(Series("peaks", Style::kLinesPoints, peaks_x, peaks_y));

  Figure figure;
  figure.panels = {parameters, response};
  figure.columns = 2;
  figure.width_px = 1100;
  figure.height_px = 450;
  return figure;
}

void ExpectPngOfSize(const std::string& path, int width, int height) {
  std::string png = ReadFile(path);
  ASSERT_GE(png.size(), 24u) << path;
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(static_cast<unsigned char>(png[i]), signature[i]) << "byte " << i;
  }
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(BigEndian32(png, 16), static_cast<uint32_t>(width));
  EXPECT_EQ(BigEndian32(png, 20), static_cast<uint32_t>(height));
}

// Each test gets fresh directories under the test temp dir; they are removed
// afterwards unless FEMUP_KEEP_TEST_FILES is set (to look at the pictures).
class PlotTest : public ::testing::Test {
 protected:
  void TearDown() override {
    if (std::getenv("FEMUP_KEEP_TEST_FILES") != nullptr) return;
    for (const auto& dir : dirs_) {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  }

  std::string MakeTempDir() {
    std::string base = ::testing::TempDir();
    if (base.empty() || base.back() != '/') base += '/';
    std::string pattern = base + "femup_plot_XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    char* made = ::mkdtemp(buffer.data());
    EXPECT_NE(made, nullptr) << pattern;
    if (made == nullptr) return base;
    dirs_.push_back(made);
    return made;
  }

 private:
  std::vector<std::string> dirs_;
};

TEST_F(PlotTest, GnuplotIsFoundOnThisMachine) {
  // gnuplot-nox is part of the development environment.
  EXPECT_TRUE(GnuplotAvailable());
}

TEST_F(PlotTest, RendersTwoPanelFigureWithEveryStyle) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot is not installed";
  std::string stem = MakeTempDir() + "/every_style";
  Figure figure = EveryStyleFigure();

  PlotStatus status = RenderFigure(figure, stem);
  ASSERT_TRUE(status.rendered) << status.message;
  EXPECT_EQ(status.message, "");
  ExpectPngOfSize(stem + ".png", 1100, 450);

  std::string script = ReadFile(stem + ".gp");
  EXPECT_NE(script.find("set terminal pngcairo size 1100,450 enhanced font \",10\""),
            std::string::npos);
  // The script names its files relative to its own folder.
  const std::string leaf = stem.substr(stem.find_last_of('/') + 1);
  EXPECT_NE(script.find("set output '" + leaf + ".png'"), std::string::npos);
  EXPECT_NE(script.find("set multiplot layout 1,2"), std::string::npos);
  EXPECT_NE(script.find("unset multiplot"), std::string::npos);
  EXPECT_NE(script.find("set logscale y"), std::string::npos);
  EXPECT_EQ(script.find("set logscale x"), std::string::npos);
  EXPECT_NE(script.find("set key outside"), std::string::npos);
  // Without any of {}^_@&~ gnuplot prints a string as it is: no escapes.
  EXPECT_NE(script.find("set xlabel 'frequency [Hz]'"), std::string::npos);
  EXPECT_NE(script.find("set title 'Updated parameters (k\\_\\{2\\}\\^x)'"),
            std::string::npos);
  EXPECT_NE(script.find("set xtics ('added\\_mass\\[e2\\]' 1, 'k\\_\\{2\\}\\^x' 2, "
                        "'it''s' 3, 'E\\@1 \\& \\~2' 4, 'mass[1]' 5)"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("title 'updated\\_value'"), std::string::npos);
  EXPECT_NE(script.find("with yerrorbars"), std::string::npos);
  EXPECT_NE(script.find("with lines"), std::string::npos);
  EXPECT_NE(script.find("with points"), std::string::npos);
  EXPECT_NE(script.find("with linespoints"), std::string::npos);
}

TEST_F(PlotTest, BarSeriesAreOffsetSideBySide) {
  std::string stem = MakeTempDir() + "/bars";
  Figure figure = EveryStyleFigure();
  ScopedPath no_gnuplot(MakeTempDir());  // only the script matters here
  RenderFigure(figure, stem);
  std::string script = ReadFile(stem + ".gp");
  // Two bar series at unit spacing: a group 0.8 wide, bars 0.4 wide at -+0.2.
  EXPECT_NE(script.find("using ($1-0.2):2:(0.4) with boxes"), std::string::npos)
      << script;
  EXPECT_NE(script.find("using ($1+0.2):2:(0.4) with boxes"), std::string::npos)
      << script;
  EXPECT_NE(script.find("set xrange [0.5:5.5]"), std::string::npos);
}

TEST_F(PlotTest, SeriesColourWidthAndEqualAxesReachTheScript) {
  std::string stem = MakeTempDir() + "/looks";
  Figure figure;
  Plot plot;
  plot.equal_axes = true;
  PlotSeries line{"line", PlotSeries::Style::kLines, {0, 1}, {0, 1}, {}, {}};
  line.color = "#1a2B3c";
  line.width = 4;
  PlotSeries dots{"dots", PlotSeries::Style::kPoints, {0, 1}, {1, 0}, {}, {}};
  dots.width = 2.5;
  plot.series = {line, dots};
  figure.panels.push_back(plot);
  ScopedPath no_gnuplot(MakeTempDir());
  RenderFigure(figure, stem);
  const std::string script = ReadFile(stem + ".gp");
  EXPECT_NE(script.find("with lines lw 4 lc rgb '#1a2B3c'"), std::string::npos) << script;
  EXPECT_NE(script.find("with points pt 7 ps 2.5 title"), std::string::npos);
  EXPECT_NE(script.find("set size ratio -1"), std::string::npos);
  // Only #rrggbb reaches gnuplot's script: nothing else can be injected.
  for (const std::string bad : {"red", "#12345", "#12345g", "#123456' lw 9"}) {
    figure.panels[0].series[0].color = bad;
    EXPECT_THROW(RenderFigure(figure, stem), InputError) << bad;
  }
  figure.panels[0].series[0].color = "";
  figure.panels[0].series[0].width = -1;
  EXPECT_THROW(RenderFigure(figure, stem), InputError);
}

TEST_F(PlotTest, DataFileHasOneBlockPerSeriesWithNaNForGaps) {
  std::string stem = MakeTempDir() + "/blocks";
  Figure figure = EveryStyleFigure();
  figure.panels[1].series[2].y[1] = std::numeric_limits<double>::infinity();
  ScopedPath no_gnuplot(MakeTempDir());
  RenderFigure(figure, stem);
  std::string data = ReadFile(stem + ".dat");

  // Six series, so six blocks and five double-blank-line separators.
  size_t separators = 0;
  for (size_t at = data.find("\n\n\n"); at != std::string::npos;
       at = data.find("\n\n\n", at + 3)) {
    ++separators;
  }
  EXPECT_EQ(separators, 5u);
  EXPECT_NE(data.find("# index 5: figure panel 2 'Frequency response', series 3 'peaks'"),
            std::string::npos)
      << data;
  EXPECT_NE(data.find("\n1 1.2 1.1 1.3\n"), std::string::npos);  // x y y_low y_high
  EXPECT_NE(data.find("\n16 NaN\n"), std::string::npos);         // the gap
  EXPECT_NE(data.find("\n10.95 NaN\n"), std::string::npos);      // infinity
  EXPECT_EQ(data.find("inf"), std::string::npos);

  std::string script = ReadFile(stem + ".gp");
  for (int block = 0; block < 6; ++block) {
    EXPECT_NE(script.find("data index " + std::to_string(block) + " "), std::string::npos)
        << block;
  }
  EXPECT_EQ(script.find("data index 6"), std::string::npos);
}

TEST_F(PlotTest, TextIsEscapedOnlyWhereGnuplotParsesMarkup) {
  Plot plot;
  plot.title = "back\\slash_1";      // markup: the backslash is escaped too
  plot.x_label = "back\\slash [m]";  // no markup: printed as it is
  plot.y_label = "line\nbreak_{x}";  // control characters become spaces
  plot.series.push_back(Series("it's ok", Style::kLines, {1, 2}, {1, 2}));
  Figure figure;
  figure.panels = {plot};
  std::string stem = MakeTempDir() + "/text";
  ScopedPath no_gnuplot(MakeTempDir());
  RenderFigure(figure, stem);
  std::string script = ReadFile(stem + ".gp");
  EXPECT_NE(script.find("set title 'back\\\\slash\\_1'\n"), std::string::npos) << script;
  EXPECT_NE(script.find("set xlabel 'back\\slash [m]'\n"), std::string::npos) << script;
  EXPECT_NE(script.find("set ylabel 'line break\\_\\{x\\}'\n"), std::string::npos)
      << script;
  EXPECT_NE(script.find("title 'it''s ok'"), std::string::npos) << script;
  EXPECT_NE(script.find("set key inside"), std::string::npos);
}

TEST_F(PlotTest, MismatchedSeriesSizesThrowNamingPanelAndSeries) {
  std::string dir = MakeTempDir();
  Figure figure = EveryStyleFigure();
  figure.panels[1].series[1].y.pop_back();
  try {
    RenderFigure(figure, dir + "/bad");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("panel 2 'Frequency response'"), std::string::npos) << message;
    EXPECT_NE(message.find("series 2 'model'"), std::string::npos) << message;
    EXPECT_NE(message.find("x has 61 values but y has 60"), std::string::npos) << message;
  }
  // Validation comes before any file is written.
  EXPECT_FALSE(FileExists(dir + "/bad.dat"));
  EXPECT_FALSE(FileExists(dir + "/bad.gp"));
}

TEST_F(PlotTest, MisSizedErrorBarsThrowNamingTheSeries) {
  std::string dir = MakeTempDir();
  Figure low = EveryStyleFigure();
  low.panels[0].series[2].y_low.pop_back();
  try {
    RenderFigure(low, dir + "/bad");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("panel 1"), std::string::npos) << message;
    EXPECT_NE(message.find("series 3 '95% interval'"), std::string::npos) << message;
    EXPECT_NE(message.find("y_low has 3 values but x has 4"), std::string::npos)
        << message;
  }
  Figure high = EveryStyleFigure();
  high.panels[0].series[2].y_high.clear();
  EXPECT_THROW(RenderFigure(high, dir + "/bad"), InputError);
  EXPECT_FALSE(FileExists(dir + "/bad.dat"));
}

TEST_F(PlotTest, MalformedFiguresThrow) {
  std::string dir = MakeTempDir();
  Figure no_panels;
  EXPECT_THROW(RenderFigure(no_panels, dir + "/bad"), InputError);

  Figure no_columns = EveryStyleFigure();
  no_columns.columns = 0;
  EXPECT_THROW(RenderFigure(no_columns, dir + "/bad"), InputError);

  Figure no_width = EveryStyleFigure();
  no_width.width_px = 0;
  EXPECT_THROW(RenderFigure(no_width, dir + "/bad"), InputError);

  Figure negative_height = EveryStyleFigure();
  negative_height.height_px = -5;
  EXPECT_THROW(RenderFigure(negative_height, dir + "/bad"), InputError);

  Figure good = EveryStyleFigure();
  EXPECT_THROW(RenderFigure(good, ""), InputError);
  EXPECT_THROW(RenderFigure(good, dir + "/"), InputError);
  EXPECT_THROW(RenderFigure(good, dir + "/bad\nname"), InputError);
  try {
    RenderFigure(good, dir + "/missing_dir/figure");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing_dir' does not exist"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(FileExists(dir + "/bad.dat"));
}

TEST_F(PlotTest, MissingGnuplotIsAStatusAndTheFilesAreStillWritten) {
  std::string stem = MakeTempDir() + "/no_gnuplot";
  std::string empty_dir = MakeTempDir();
  ScopedPath path(empty_dir);
  EXPECT_FALSE(GnuplotAvailable());

  PlotStatus status = RenderFigure(EveryStyleFigure(), stem);
  EXPECT_FALSE(status.rendered);
  EXPECT_EQ(status.message,
            "gnuplot not found on PATH: install gnuplot-nox; the data and script were "
            "written to " +
                stem + ".dat/.gp");
  EXPECT_TRUE(FileExists(stem + ".dat"));
  EXPECT_TRUE(FileExists(stem + ".gp"));
  EXPECT_FALSE(FileExists(stem + ".png"));
}

TEST_F(PlotTest, NonExecutableGnuplotIsNotAvailable) {
  std::string dir = MakeTempDir();
  std::ofstream(dir + "/gnuplot") << "#!/bin/sh\n";
  ASSERT_EQ(::chmod((dir + "/gnuplot").c_str(), 0644), 0);
  ScopedPath path(dir);
  EXPECT_FALSE(GnuplotAvailable());
}

TEST_F(PlotTest, FailedRenderReportsGnuplotStderr) {
  std::string bin = MakeTempDir();
  WriteExecutable(bin + "/gnuplot",
                  "#!/bin/sh\necho \"line 7: boom in $1\" >&2\nexit 3\n");
  std::string stem = MakeTempDir() + "/failing";
  ScopedPath path(bin);
  ASSERT_TRUE(GnuplotAvailable());

  PlotStatus status = RenderFigure(EveryStyleFigure(), stem);
  EXPECT_FALSE(status.rendered);
  EXPECT_NE(status.message.find("exit status 3"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("line 7: boom in failing.gp"), std::string::npos)
      << status.message;
  EXPECT_TRUE(FileExists(stem + ".gp"));
}

TEST_F(PlotTest, StalePictureIsRemovedWhenRenderingFails) {
  std::string stem = MakeTempDir() + "/stale";
  std::ofstream(stem + ".png") << "old picture";
  ScopedPath path(MakeTempDir());
  PlotStatus status = RenderFigure(EveryStyleFigure(), stem);
  EXPECT_FALSE(status.rendered);
  EXPECT_FALSE(FileExists(stem + ".png"));
}

TEST_F(PlotTest, WriteFailureThrowsNamingTheFile) {
  std::string stem = MakeTempDir() + "/blocked";
  ASSERT_EQ(::mkdir((stem + ".dat").c_str(), 0755), 0);  // a directory in the way
  try {
    RenderFigure(EveryStyleFigure(), stem);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(stem + ".dat"), std::string::npos) << e.what();
  }
}

TEST_F(PlotTest, EmptyAndAllMissingPanelsStillRender) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot is not installed";
  Plot nothing;
  nothing.title = "no series";
  Plot all_missing;
  all_missing.title = "all NaN";
  all_missing.log_y = true;
  all_missing.series.push_back(Series("nan", Style::kLines, {1, 2}, {kNaN, kNaN}));
  all_missing.series.push_back(Series("empty", Style::kBars, {}, {}));
  Plot log_bars;
  log_bars.title = "bars on log x";
  log_bars.log_x = true;
  log_bars.series.push_back(Series("a", Style::kBars, {1, 10, 100}, {1, 2, 3}));
  log_bars.series.push_back(Series("b", Style::kBars, {1, 10, 100}, {2, 1, 3}));
  Figure figure;
  figure.panels = {nothing, all_missing, log_bars};
  figure.columns = 2;
  figure.width_px = 640;
  figure.height_px = 480;

  std::string stem = MakeTempDir() + "/degenerate";
  PlotStatus status = RenderFigure(figure, stem);
  ASSERT_TRUE(status.rendered) << status.message;
  ExpectPngOfSize(stem + ".png", 640, 480);
  EXPECT_NE(ReadFile(stem + ".gp").find("set multiplot layout 2,2"), std::string::npos);
}

TEST_F(PlotTest, BackquotesInNamesAreNotRunByGnuplot) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot is not installed";
  std::string dir = MakeTempDir();
  std::string marker = dir + "/pwned";
  Plot plot;
  plot.title = "`touch " + marker + "`";
  plot.x_tick_labels = {"\"`touch " + marker + "`\""};
  plot.series.push_back(Series("`touch " + marker + "`", Style::kPoints, {1}, {2}));
  Figure figure;
  figure.panels = {plot};

  PlotStatus status = RenderFigure(figure, dir + "/quoted");
  EXPECT_TRUE(status.rendered) << status.message;
  EXPECT_FALSE(FileExists(marker));
}

TEST_F(PlotTest, StemsGnuplotWouldMisreadAreMadeRelative) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot is not installed";
  std::string dir = MakeTempDir();
  char* cwd = ::getcwd(nullptr, 0);
  ASSERT_NE(cwd, nullptr);
  std::string old_cwd = cwd;
  std::free(cwd);
  ASSERT_EQ(::chdir(dir.c_str()), 0);
  Figure figure;
  Plot plot;
  plot.series.push_back(Series("s", Style::kLines, {1, 2}, {1, 4}));
  figure.panels = {plot};
  PlotStatus dash = RenderFigure(figure, "-dash");
  PlotStatus pipe = RenderFigure(figure, "<pipe");
  ASSERT_EQ(::chdir(old_cwd.c_str()), 0);
  EXPECT_TRUE(dash.rendered) << dash.message;
  EXPECT_TRUE(pipe.rendered) << pipe.message;
  EXPECT_TRUE(FileExists(dir + "/-dash.png"));
  EXPECT_TRUE(FileExists(dir + "/<pipe.png"));
}

}  // namespace
}  // namespace femup
