// Plots drawn by gnuplot (pngcairo): the data and the script are written next to
// the picture, so a user can restyle a figure without rerunning a study.
#pragma once

#include <string>
#include <vector>

namespace femup {

struct PlotSeries {
  enum class Style { kLines, kPoints, kLinesPoints, kBars, kErrorBars };
  std::string title;
  Style style = Style::kLinesPoints;
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> y_low;   // kErrorBars only: lower ends
  std::vector<double> y_high;  // kErrorBars only: upper ends
  // Optional: a colour ("#rrggbb") and a width (lines: line width; points:
  // point size); empty / 0: gnuplot's next colour and the style's width.
  std::string color = "";
  double width = 0;
};

struct Plot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
  bool log_x = false;
  bool log_y = false;
  // Optional category labels placed at x = 1, 2, ... (parameter names).
  std::vector<std::string> x_tick_labels;
  bool key_outside = false;
  // The same scale on both axes (a structure's geometry drawn to scale).
  bool equal_axes = false;
};

struct Figure {
  std::vector<Plot> panels;  // laid out in a grid of `columns` columns
  int columns = 1;
  int width_px = 900;
  int height_px = 600;
};

struct PlotStatus {
  bool rendered = false;  // the PNG exists
  std::string message;    // why not, when not (e.g. gnuplot is not installed)
};

// Writes <stem>.dat (data), <stem>.gp (script) and renders <stem>.png with
// gnuplot. Throws InputError when the figure is malformed (series sizes differ,
// non-finite values are reported as gaps, not errors); a missing gnuplot or a
// failed render is a status, not an exception.
PlotStatus RenderFigure(const Figure& figure, const std::string& stem);

// True when a gnuplot executable is on PATH.
bool GnuplotAvailable();

}  // namespace femup
