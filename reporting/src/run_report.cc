#include "femup/reporting/run_report.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "femup/reporting/html_page.h"

namespace femup {
namespace {

namespace fs = std::filesystem;

constexpr std::uintmax_t kLargestShownInput = 256 * 1024;

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Extension(const std::string& name) {
  const auto dot = name.rfind('.');
  return dot == std::string::npos ? "" : name.substr(dot + 1);
}

std::string Stem(const std::string& name) {
  const auto dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

std::string HumanSize(std::uintmax_t bytes) {
  std::ostringstream s;
  s.precision(3);
  if (bytes < 1024) {
    s << bytes << " B";
  } else if (bytes < 1024 * 1024) {
    s << static_cast<double>(bytes) / 1024.0 << " KiB";
  } else {
    s << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MiB";
  }
  return s.str();
}

std::string WhatFileIs(const std::string& name) {
  const std::string ext = Extension(name);
  if (name == "report.html") return "this page";
  if (ext == "json") return "results (JSON)";
  if (ext == "mtx") return "matrix (Matrix Market)";
  if (ext == "png") return "plot";
  if (ext == "dat") return "plot data (gnuplot)";
  if (ext == "gp") return "plot script: gnuplot '" + name + "' redraws the plot";
  if (ext == "uff" || ext == "unv") return "test records (UFF)";
  if (ext == "csv") return "table (CSV)";
  if (ext == "yaml" || ext == "yml") return "study file (YAML)";
  if (ext == "txt") return "text";
  return "";
}

// The panel titles a figure's gnuplot script names ("# figure panel 1 'T'").
std::string FigureCaption(OutputDir* dir, const std::string& png_name) {
  const std::string gp = Stem(png_name) + ".gp";
  std::string caption;
  const auto& files = dir->files();
  if (std::find(files.begin(), files.end(), gp) != files.end()) {
    std::istringstream script(ReadBytes(dir->Stage(gp)));
    const std::string marker = "# figure panel ";
    for (std::string line; std::getline(script, line);) {
      if (line.rfind(marker, 0) != 0) continue;
      const auto open = line.find('\'');
      const auto close = line.rfind('\'');
      if (open == std::string::npos || close <= open) continue;
      if (!caption.empty()) caption += " · ";
      caption += line.substr(open + 1, close - open - 1);
    }
  }
  return caption.empty() ? png_name : caption + " (" + png_name + ")";
}

std::string UtcNow() {
  const std::time_t now =
      std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
  return text;
}

}  // namespace

std::string RenderRunReport(const RunReport& report, OutputDir* dir) {
  HtmlPage page("femup " + report.command + ": " + report.name);
  std::vector<std::pair<std::string, std::string>> facts;
  if (!report.command_line.empty()) facts.emplace_back("command", report.command_line);
  facts.emplace_back("output folder", dir->directory());
  facts.emplace_back("written",
                     UtcNow() + (report.version.empty() ? "" : ", " + report.version));
  page.AddFacts(facts);

  std::string warnings;
  if (!report.warnings.empty()) {
    warnings = "<ul>\n";
    for (const auto& w : report.warnings) warnings += "<li>" + HtmlEscape(w) + "</li>\n";
    warnings += "</ul>\n";
  }
  page.AddSection("warnings", "Warnings", warnings, "warnings");
  page.AddSection("summary", "Summary", HtmlPage::Preformatted(report.summary), "wrap");

  std::string plots;
  for (const auto& name : dir->files()) {
    if (Extension(name) != "png") continue;
    const std::string path = dir->Stage(name);
    if (!fs::exists(path)) continue;  // gnuplot could not render it
    const std::string bytes = ReadBytes(path);
    if (!LooksLikePng(bytes)) continue;
    plots += HtmlPage::PngFigure(bytes, FigureCaption(dir, name));
  }
  page.AddSection("plots", "Plots", plots);

  std::string inputs;
  for (const auto& input : report.inputs) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(input, ec);
    const std::string ext = Extension(input);
    const bool text = ext == "yaml" || ext == "yml" || ext == "json";
    if (!ec && text && size <= kLargestShownInput) {
      inputs += HtmlPage::Details(input + " (" + HumanSize(size) + ")",
                                  HtmlPage::Preformatted(ReadBytes(input)), true);
    } else {
      inputs += HtmlPage::Paragraph(input + (ec ? "" : " (" + HumanSize(size) + ")"));
    }
  }
  page.AddSection("inputs", report.inputs.size() == 1 ? "Input" : "Inputs", inputs,
                  "wrap");

  HtmlTable files{{"file", "size", "what it is"}, {}, {}};
  for (const auto& name : dir->files()) {
    if (name == "report.html") continue;
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(dir->Stage(name), ec);
    if (ec) continue;  // staged but never written (a plot gnuplot could not draw)
    files.rows.push_back({name, HumanSize(size), WhatFileIs(name)});
    files.row_links.push_back(name);
  }
  files.rows.push_back({"report.html", "", WhatFileIs("report.html")});
  files.row_links.push_back("report.html");
  page.AddSection("files", "Files written", HtmlPage::Table(files));
  return page.Render();
}

void WriteRunReport(const RunReport& report, OutputDir* dir) {
  dir->WriteText("report.html", RenderRunReport(report, dir));
}

}  // namespace femup
