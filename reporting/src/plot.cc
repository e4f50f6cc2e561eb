// Figures for gnuplot: RenderFigure checks a figure, writes its data (one block
// per series) and a gnuplot script that draws it, and has gnuplot render the
// PNG when gnuplot is installed (plot_gnuplot.cc runs it).
#include "femup/reporting/plot.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "femup/core/enum_names.h"
#include "femup/core/errors.h"
#include "plot_internal.h"

namespace femup {
namespace {

using Style = PlotSeries::Style;
using plot_internal::FindGnuplot;
using plot_internal::RunGnuplot;

constexpr EnumName<Style> kStyleNames[] = {
    {Style::kLines, "lines"},
    {Style::kPoints, "points"},
    {Style::kLinesPoints, "linespoints"},
    {Style::kBars, "bars"},
    {Style::kErrorBars, "yerrorbars"},
};

const char* StyleName(Style style) { return NameIn(kStyleNames, style, "unknown"); }

// Text for comments and error messages: control characters become spaces.
std::string Printable(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  }
  return out;
}

std::string PanelName(size_t p, const Plot& plot) {
  std::string name = "figure panel " + std::to_string(p + 1);
  if (!plot.title.empty()) name += " '" + Printable(plot.title) + "'";
  return name;
}

std::string SeriesName(size_t p, const Plot& plot, size_t s, const PlotSeries& series) {
  std::string name = PanelName(p, plot) + ", series " + std::to_string(s + 1);
  if (!series.title.empty()) name += " '" + Printable(series.title) + "'";
  return name;
}

// Shortest text that reads back as the same double; NaN for non-finite values
// (gnuplot treats NaN as undefined, so lines break there).
std::string Number(double value) {
  if (!std::isfinite(value)) return "NaN";
  char buffer[64];
  auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// Text that gnuplot's enhanced-text mode prints literally, so that a name such
// as "added_mass[e2]" is not read as a subscript. gnuplot only runs the
// enhanced-text parser on strings holding one of {}^_@&~ and prints any other
// string as it is, backslashes included; so a string without those characters
// is left alone, and in one with them every character the parser treats
// specially (and the brackets, for good measure) gets a backslash.
std::string EnhancedLiteral(const std::string& text) {
  static const char kTriggers[] = "{}^_@&~";
  static const char kSpecial[] = "\\^_@&~{}[]";
  bool parsed = text.find_first_of(kTriggers) != std::string::npos;
  std::string out;
  out.reserve(text.size() + 8);
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += ' ';
      continue;
    }
    if (parsed && std::strchr(kSpecial, c) != nullptr) out += '\\';
    out += c;
  }
  return out;
}

// A gnuplot single-quoted string. Single quotes are used on purpose: gnuplot
// runs `backquoted` shell commands inside double-quoted strings, and a name
// taken from a study file must never do that.
std::string Quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += '\'';
    out += c;
  }
  out += '\'';
  return out;
}

// User text (titles, labels, tick labels) for the script.
std::string Text(const std::string& text) { return Quoted(EnhancedLiteral(text)); }

// True when the point is drawn at all: finite, and positive on a log axis.
bool Plottable(const Plot& plot, const PlotSeries& series, size_t i) {
  double x = series.x[i];
  double y = series.y[i];
  if (!std::isfinite(x) || !std::isfinite(y)) return false;
  if (plot.log_x && x <= 0) return false;
  if (plot.log_y && y <= 0) return false;
  if (series.style == Style::kErrorBars) {
    if (!std::isfinite(series.y_low[i]) || !std::isfinite(series.y_high[i])) return false;
  }
  return true;
}

bool HasDrawableData(const Plot& plot) {
  for (const auto& series : plot.series) {
    for (size_t i = 0; i < series.x.size(); ++i) {
      if (Plottable(plot, series, i)) return true;
    }
  }
  return false;
}

std::string DirectoryOf(const std::string& path) {
  size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

void Validate(const Figure& figure, const std::string& stem) {
  if (stem.empty()) throw InputError("plot", "the output stem is empty");
  for (char c : stem) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      throw InputError("plot stem '" + Printable(stem) + "'",
                       "contains a control character; gnuplot cannot quote it");
    }
  }
  if (stem.back() == '/') {
    throw InputError("plot stem '" + stem + "'",
                     "names a directory; expected a path without extension such as "
                     "out/frequencies");
  }
  std::string directory = DirectoryOf(stem);
  struct stat info;
  if (::stat(directory.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) {
    throw InputError("plot stem '" + stem + "'",
                     "directory '" + directory + "' does not exist");
  }
  if (figure.width_px <= 0 || figure.height_px <= 0) {
    throw InputError("figure", "size must be positive, got " +
                                   std::to_string(figure.width_px) + "x" +
                                   std::to_string(figure.height_px) + " pixels");
  }
  if (figure.columns < 1) {
    throw InputError("figure",
                     "columns must be at least 1, got " + std::to_string(figure.columns));
  }
  if (figure.panels.empty()) throw InputError("figure", "has no panels");
  for (size_t p = 0; p < figure.panels.size(); ++p) {
    const Plot& plot = figure.panels[p];
    for (size_t s = 0; s < plot.series.size(); ++s) {
      const PlotSeries& series = plot.series[s];
      std::string where = SeriesName(p, plot, s, series);
      const bool hex_color =
          series.color.size() == 7 && series.color[0] == '#' &&
          std::all_of(series.color.begin() + 1, series.color.end(), [](char c) {
            return std::isxdigit(static_cast<unsigned char>(c));
          });
      if (!series.color.empty() && !hex_color) {
        throw InputError(
            where, "color '" + Printable(series.color) + "' is not of the form #rrggbb");
      }
      if (!(series.width >= 0) || !std::isfinite(series.width)) {
        throw InputError(where, "width must be >= 0 and finite");
      }
      if (series.x.size() != series.y.size()) {
        throw InputError(where, "x has " + std::to_string(series.x.size()) +
                                    " values but y has " +
                                    std::to_string(series.y.size()));
      }
      switch (series.style) {
        case Style::kLines:
        case Style::kPoints:
        case Style::kLinesPoints:
        case Style::kBars:
          break;
        case Style::kErrorBars:
          if (series.y_low.size() != series.x.size()) {
            throw InputError(
                where, "error bars: y_low has " + std::to_string(series.y_low.size()) +
                           " values but x has " + std::to_string(series.x.size()));
          }
          if (series.y_high.size() != series.x.size()) {
            throw InputError(
                where, "error bars: y_high has " + std::to_string(series.y_high.size()) +
                           " values but x has " + std::to_string(series.x.size()));
          }
          break;
        default:
          throw InputError(where, "unknown series style " +
                                      std::to_string(static_cast<int>(series.style)));
      }
    }
  }
}

// Side-by-side placement of the bar series of one panel. On a log x axis the
// offsets and widths are in decades.
struct BarLayout {
  double width = 0;             // of one bar
  std::vector<double> offsets;  // per series; meaningful for bar series only
  double extent = 0;            // furthest bar edge from its x
};

BarLayout LayOutBars(const Plot& plot) {
  BarLayout layout;
  layout.offsets.assign(plot.series.size(), 0.0);
  std::vector<double> xs;
  size_t bar_count = 0;
  for (const auto& series : plot.series) {
    if (series.style != Style::kBars) continue;
    ++bar_count;
    for (double x : series.x) {
      if (!std::isfinite(x)) continue;
      if (plot.log_x) {
        if (x > 0) xs.push_back(std::log10(x));
      } else {
        xs.push_back(x);
      }
    }
  }
  if (bar_count == 0) return layout;
  std::sort(xs.begin(), xs.end());
  double spacing = 0;
  if (xs.size() >= 2) {
    double scale = std::max(std::abs(xs.front()), std::abs(xs.back()));
    double tiny = 1e-12 * std::max(scale, 1.0);
    for (size_t i = 1; i < xs.size(); ++i) {
      double gap = xs[i] - xs[i - 1];
      if (gap > tiny && (spacing == 0 || gap < spacing)) spacing = gap;
    }
  }
  if (spacing == 0) spacing = plot.log_x ? 0.5 : 1.0;
  double group = 0.8 * spacing;
  layout.width = group / static_cast<double>(bar_count);
  size_t k = 0;
  for (size_t s = 0; s < plot.series.size(); ++s) {
    if (plot.series[s].style != Style::kBars) continue;
    layout.offsets[s] =
        (static_cast<double>(k) - 0.5 * static_cast<double>(bar_count - 1)) *
        layout.width;
    ++k;
  }
  layout.extent = 0.5 * group;
  return layout;
}

// The `using` and `with` clauses of one series, with its colour and width
// (the series' own, or the style's).
std::string PlotClause(const Plot& plot, const PlotSeries& series, double bar_width,
                       double bar_offset) {
  const auto width = [&](double style_default) {
    return Number(series.width > 0 ? series.width : style_default);
  };
  const std::string color = series.color.empty() ? "" : " lc rgb '" + series.color + "'";
  switch (series.style) {
    case Style::kLines:
      return "using 1:2 with lines lw " + width(2) + color;
    case Style::kPoints:
      return "using 1:2 with points pt 7 ps " + width(0.8) + color;
    case Style::kLinesPoints:
      return "using 1:2 with linespoints lw " + width(1.5) + " pt 7 ps 0.8" + color;
    case Style::kErrorBars:
      return "using 1:2:3:4 with yerrorbars lw " + width(1.5) + " pt 7 ps 0.8" + color;
    case Style::kBars: {
      std::string using_clause;
      if (plot.log_x) {
        // Box edges at x * 10^(offset -+ width/2): centre and width in data units.
        double left = std::pow(10.0, bar_offset - 0.5 * bar_width);
        double right = std::pow(10.0, bar_offset + 0.5 * bar_width);
        using_clause = "using ($1*" + Number(0.5 * (left + right)) + "):2:($1*" +
                       Number(right - left) + ")";
      } else if (bar_offset == 0) {
        using_clause = "using 1:2:(" + Number(bar_width) + ")";
      } else {
        using_clause = "using ($1" + std::string(bar_offset > 0 ? "+" : "") +
                       Number(bar_offset) + "):2:(" + Number(bar_width) + ")";
      }
      return using_clause + " with boxes fill solid 0.7 border -1" + color;
    }
  }
  return "using 1:2";
}

void WriteFile(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    throw InputError(path,
                     std::string("cannot open for writing: ") + std::strerror(errno));
  }
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.flush();
  bool written = static_cast<bool>(out);
  out.close();
  if (!written || out.fail()) {
    throw InputError(path, "writing failed (disk full or no permission?)");
  }
}

}  // namespace

PlotStatus RenderFigure(const Figure& figure, const std::string& stem) {
  Validate(figure, stem);

  // gnuplot reads a file name starting with '<' as a shell command and expands a
  // leading '~'; an argument starting with '-' would be an option.
  std::string base = stem;
  if (base[0] == '<' || base[0] == '-' || base[0] == '~' || base[0] == '|' ||
      base[0] == '+') {
    base = "./" + base;
  }
  const std::string data_path = base + ".dat";
  const std::string script_path = base + ".gp";
  const std::string png_path = base + ".png";
  // Inside the script, files are named relative to the script's folder.
  const std::size_t slash = base.find_last_of('/');
  const std::string directory =
      slash == std::string::npos ? "." : base.substr(0, slash + 1);
  std::string leaf = slash == std::string::npos ? base : base.substr(slash + 1);
  if (leaf[0] == '<' || leaf[0] == '-' || leaf[0] == '~' || leaf[0] == '|' ||
      leaf[0] == '+') {
    leaf = "./" + leaf;
  }
  const std::string data_name = leaf + ".dat";
  const std::string png_name = leaf + ".png";

  std::ostringstream data;
  std::ostringstream script;
  const size_t panel_count = figure.panels.size();
  const size_t columns = static_cast<size_t>(figure.columns);
  const size_t rows = (panel_count + columns - 1) / columns;

  data << "# femup figure data for " << Quoted(script_path)
       << ": one block per series (gnuplot `index N`),\n"
       << "# columns x y, or x y y_low y_high for error bars; NaN marks a missing "
          "value.\n";

  script
      << "# femup figure: " << panel_count << " panel" << (panel_count == 1 ? "" : "s")
      << ". Restyle and redraw, in this folder, with: gnuplot " << Quoted(leaf + ".gp")
      << "\n"
      << "# Text holding one of {}^_@&~ goes through enhanced-text markup, so there\n"
      << "# the special characters are escaped: \\_ prints _, \\[ prints [.\n"
      << "set encoding utf8\n"
      << "set terminal pngcairo size " << figure.width_px << "," << figure.height_px
      << " enhanced font \",10\"\n"
      << "set output " << Quoted(png_name) << "\n"
      << "data = " << Quoted(data_name) << "\n"
      << "# NaN in the data is undefined for gnuplot: points are skipped, lines break.\n";
  if (panel_count > 1) {
    script << "set multiplot layout " << rows << "," << columns << "\n";
  }

  size_t block = 0;
  for (size_t p = 0; p < panel_count; ++p) {
    const Plot& plot = figure.panels[p];
    const bool has_data = HasDrawableData(plot);
    const BarLayout bars = LayOutBars(plot);
    const size_t tick_count = plot.x_tick_labels.size();

    script << "\n# " << PanelName(p, plot) << "\n"
           << "reset\n"
           << "set grid lc rgb '#d0d0d0'\n";
    if (!plot.title.empty()) script << "set title " << Text(plot.title) << "\n";
    if (!plot.x_label.empty()) script << "set xlabel " << Text(plot.x_label) << "\n";
    if (!plot.y_label.empty()) script << "set ylabel " << Text(plot.y_label) << "\n";
    if (plot.log_x) script << "set logscale x\n";
    if (plot.log_y) script << "set logscale y\n";

    if (tick_count > 0) {
      size_t characters = 0;
      script << "set xtics (";
      for (size_t i = 0; i < tick_count; ++i) {
        if (i > 0) script << ", ";
        script << Text(plot.x_tick_labels[i]) << " " << (i + 1);
        characters += plot.x_tick_labels[i].size() + 2;
      }
      script << ")";
      // About 7 px per character at font size 10: turn crowded labels.
      double panel_width =
          static_cast<double>(figure.width_px) / static_cast<double>(columns);
      if (7.0 * static_cast<double>(characters) > 0.75 * panel_width) {
        script << " rotate by 45 right";
      }
      script << "\n";
    }

    // x range: categories get a slot each, as long as the data stays inside.
    if (tick_count > 0 && !plot.log_x) {
      double low = 0.5;
      double high = static_cast<double>(tick_count) + 0.5;
      bool inside = true;
      for (size_t s = 0; s < plot.series.size(); ++s) {
        const PlotSeries& series = plot.series[s];
        double reach = series.style == Style::kBars ? bars.extent : 0.0;
        for (double x : series.x) {
          if (std::isfinite(x) && (x - reach < low || x + reach > high)) inside = false;
        }
      }
      if (inside || !has_data) {
        script << "set xrange [" << Number(low) << ":" << Number(high) << "]\n";
      }
    } else if (!has_data) {
      script << (plot.log_x ? "set xrange [1:10]\n" : "set xrange [0:1]\n");
    }
    if (!has_data) {
      script << (plot.log_y ? "set yrange [1:10]\n" : "set yrange [0:1]\n")
             << "set label 'no finite data' at graph 0.5,0.5 center\n";
    } else if (bars.width > 0 && !plot.log_y) {
      script << "set yrange [*<0:0<*]  # bars stand on y = 0\n";
    }
    if (plot.equal_axes) {
      // To scale, with a margin: lines on the data's edges stay off the border.
      script << "set size ratio -1  # x and y to the same scale\n"
             << "set offsets graph 0.06, graph 0.06, graph 0.06, graph 0.06\n";
    }

    bool any_title = false;
    for (const auto& series : plot.series) any_title = any_title || !series.title.empty();
    if (!any_title) {
      script << "unset key\n";
    } else if (plot.key_outside) {
      script << "set key outside right top\n";
    } else {
      script << "set key inside top right\n";
      // Headroom above autoscaled data, so the key (about 15 px a line) does not
      // cover the tallest points: a key taking a share f of the plot height needs
      // the range extended by f / (1 - f).
      if (has_data) {
        double lines = 0;
        for (const auto& series : plot.series) lines += series.title.empty() ? 0.0 : 1.0;
        double plot_height = std::max(
            40.0,
            static_cast<double>(figure.height_px) / static_cast<double>(rows) - 70.0);
        double share = std::min(0.5, (15.0 * lines + 10.0) / plot_height);
        script << "set offsets 0, 0, graph "
               << Number(std::round(100 * share / (1 - share)) / 100) << ", 0\n";
      }
    }

    if (plot.series.empty()) {  // ranges and label were set above: no data
      script << "plot NaN notitle\n";
      continue;
    }

    script << "plot ";
    for (size_t s = 0; s < plot.series.size(); ++s) {
      const PlotSeries& series = plot.series[s];
      const bool error_bars = series.style == Style::kErrorBars;

      if (block > 0) data << "\n\n";
      data << "# index " << block << ": " << SeriesName(p, plot, s, series) << " ("
           << StyleName(series.style) << ")\n"
           << (error_bars ? "# x y y_low y_high\n" : "# x y\n");
      for (size_t i = 0; i < series.x.size(); ++i) {
        data << Number(series.x[i]) << ' ' << Number(series.y[i]);
        if (error_bars) {
          data << ' ' << Number(series.y_low[i]) << ' ' << Number(series.y_high[i]);
        }
        data << '\n';
      }
      // gnuplot counts blocks by their separators; an empty block still needs a row.
      if (series.x.empty()) data << (error_bars ? "NaN NaN NaN NaN\n" : "NaN NaN\n");

      if (s > 0) script << ", \\\n     ";
      script << "data index " << block << " "
             << PlotClause(plot, series, bars.width, bars.offsets[s]) << " "
             << (series.title.empty() ? std::string("notitle")
                                      : "title " + Text(series.title));
      ++block;
    }
    script << "\n";
  }
  if (panel_count > 1) script << "\nunset multiplot\n";
  script << "set output\n";

  WriteFile(data_path, data.str());
  WriteFile(script_path, script.str());
  std::remove(png_path.c_str());  // never leave a picture of older data behind

  std::string gnuplot = FindGnuplot();
  if (gnuplot.empty()) {
    PlotStatus status;
    status.message =
        "gnuplot not found on PATH: install gnuplot-nox; the data and script "
        "were written to " +
        base + ".dat/.gp";
    return status;
  }
  return RunGnuplot(gnuplot, directory, script_path, png_path);
}

}  // namespace femup
