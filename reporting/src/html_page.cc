#include "femup/reporting/html_page.h"

#include <openssl/evp.h>

#include <algorithm>
#include <stdexcept>

namespace femup {

std::string HtmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Base64Encode(std::string_view bytes) {
  if (bytes.empty()) return "";
  // EVP_EncodeBlock writes 4 characters per 3 bytes and a terminating NUL. It
  // takes an int length: encode in chunks a multiple of 3 bytes long.
  constexpr std::size_t kChunk = 3 * (1 << 20);
  std::string out;
  out.reserve(4 * ((bytes.size() + 2) / 3) + 1);
  for (std::size_t at = 0; at < bytes.size(); at += kChunk) {
    const std::size_t n = std::min(kChunk, bytes.size() - at);
    std::string block(4 * ((n + 2) / 3) + 1, '\0');
    const int written = EVP_EncodeBlock(
        reinterpret_cast<unsigned char*>(block.data()),
        reinterpret_cast<const unsigned char*>(bytes.data() + at), static_cast<int>(n));
    out.append(block.data(), static_cast<std::size_t>(written));
  }
  return out;
}

bool LooksLikePng(std::string_view bytes) {
  static constexpr char kSignature[] = "\x89PNG\r\n\x1a\n";
  return bytes.size() >= 8 && bytes.substr(0, 8) == std::string_view(kSignature, 8);
}

HtmlPage::HtmlPage(std::string title) : title_(std::move(title)) {}

void HtmlPage::AddFacts(const std::vector<std::pair<std::string, std::string>>& facts) {
  facts_.insert(facts_.end(), facts.begin(), facts.end());
}

bool HtmlPage::HasSection(const std::string& id) const {
  return std::any_of(sections_.begin(), sections_.end(),
                     [&](const Section& s) { return s.id == id; });
}

void HtmlPage::AddSection(const std::string& id, const std::string& heading,
                          const std::string& inner_html, const std::string& css_class) {
  const bool well_formed = !id.empty() && std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
  if (!well_formed) {
    throw std::invalid_argument("HtmlPage: section id '" + id +
                                "' is not made of [a-z0-9_-]");
  }
  if (HasSection(id)) {
    throw std::invalid_argument("HtmlPage: section id '" + id + "' is used twice");
  }
  if (inner_html.find_first_not_of(" \t\r\n") == std::string::npos) return;
  sections_.push_back({id, heading, inner_html, css_class});
}

std::string HtmlPage::Paragraph(std::string_view text) {
  if (text.empty()) return "";
  return "<p>" + HtmlEscape(text) + "</p>\n";
}

std::string HtmlPage::Preformatted(std::string_view text) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) return "";
  return "<pre>" + HtmlEscape(text) + "</pre>\n";
}

std::string HtmlPage::Table(const HtmlTable& table) {
  if (table.rows.empty()) return "";
  if (!table.row_links.empty() && table.row_links.size() != table.rows.size()) {
    throw std::invalid_argument(
        "HtmlPage::Table: " + std::to_string(table.row_links.size()) + " links for " +
        std::to_string(table.rows.size()) + " rows");
  }
  std::string html = "<table>\n<thead><tr>";
  for (const auto& h : table.header) html += "<th>" + HtmlEscape(h) + "</th>";
  html += "</tr></thead>\n<tbody>\n";
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    if (row.size() != table.header.size()) {
      throw std::invalid_argument("HtmlPage::Table: row " + std::to_string(r + 1) +
                                  " has " + std::to_string(row.size()) +
                                  " cells, the header " +
                                  std::to_string(table.header.size()));
    }
    html += "<tr>";
    for (std::size_t c = 0; c < row.size(); ++c) {
      std::string cell = HtmlEscape(row[c]);
      if (c == 0 && !table.row_links.empty() && !table.row_links[r].empty()) {
        cell = "<a href=\"" + HtmlEscape(table.row_links[r]) + "\">" + cell + "</a>";
      }
      html += "<td>" + cell + "</td>";
    }
    html += "</tr>\n";
  }
  return html + "</tbody>\n</table>\n";
}

std::string HtmlPage::PngFigure(std::string_view png, const std::string& caption) {
  if (!LooksLikePng(png)) {
    throw std::invalid_argument("HtmlPage::PngFigure: '" + caption + "' is not a PNG");
  }
  return "<figure><img alt=\"" + HtmlEscape(caption) + "\" src=\"data:image/png;base64," +
         Base64Encode(png) + "\"><figcaption>" + HtmlEscape(caption) +
         "</figcaption></figure>\n";
}

std::string HtmlPage::Details(const std::string& summary, const std::string& inner_html,
                              bool open) {
  if (inner_html.empty()) return "";
  return std::string("<details") + (open ? " open" : "") + "><summary>" +
         HtmlEscape(summary) + "</summary>\n" + inner_html + "</details>\n";
}

namespace {

// Readable on a laptop screen and in print; the system's fonts, no web fonts.
constexpr const char* kStyle = R"(
:root { color-scheme: light; --ink: #1d232b; --muted: #5b6672; --rule: #d8dde3;
        --accent: #1f5f99; --warn-bg: #fff4d6; --warn-rule: #d9a400; }
* { box-sizing: border-box; }
body { margin: 0; font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto,
       "DejaVu Sans", sans-serif; color: var(--ink); background: #fafbfc; }
header, main { max-width: 1120px; margin: 0 auto; padding: 0 20px; }
header { padding-top: 20px; }
h1 { font-size: 1.6em; margin: 0.2em 0 0.4em; }
h2 { font-size: 1.2em; margin: 0 0 0.6em; color: var(--accent); }
nav { margin: 0.6em 0 1em; display: flex; flex-wrap: wrap; gap: 6px 14px; }
nav a { color: var(--accent); text-decoration: none; border-bottom: 1px dotted; }
dl.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 14px;
           margin: 0; color: var(--muted); }
dl.facts dt { font-weight: 600; } dl.facts dd { margin: 0; overflow-wrap: anywhere; }
section { background: #fff; border: 1px solid var(--rule); border-radius: 6px;
          padding: 14px 18px; margin: 14px 0; }
section.warnings { background: var(--warn-bg); border-color: var(--warn-rule); }
pre { font: 13px/1.4 ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace;
      overflow-x: auto; white-space: pre; margin: 0.4em 0; }
section.wrap pre { white-space: pre-wrap; overflow-wrap: anywhere; }
figure { margin: 0 0 18px; } figure img { max-width: 100%; height: auto;
         border: 1px solid var(--rule); }
figcaption { color: var(--muted); font-size: 0.92em; }
table { border-collapse: collapse; font-size: 0.95em; }
th, td { text-align: left; padding: 3px 12px 3px 0; border-bottom: 1px solid var(--rule); }
td:nth-child(2) { text-align: right; font-variant-numeric: tabular-nums; }
ul { margin: 0.2em 0; padding-left: 1.3em; }
details summary { cursor: pointer; color: var(--accent); }
footer { max-width: 1120px; margin: 0 auto; padding: 8px 20px 24px; color: var(--muted);
         font-size: 0.85em; }
)";

}  // namespace

std::string HtmlPage::Render() const {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>" +
      HtmlEscape(title_) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  html += "<header>\n<h1>" + HtmlEscape(title_) + "</h1>\n";
  if (!facts_.empty()) {
    html += "<dl class=\"facts\">\n";
    for (const auto& [label, value] : facts_) {
      html += "<dt>" + HtmlEscape(label) + "</dt><dd>" + HtmlEscape(value) + "</dd>\n";
    }
    html += "</dl>\n";
  }
  if (sections_.size() > 1) {
    html += "<nav>";
    for (const auto& s : sections_) {
      html += "<a href=\"#" + s.id + "\">" + HtmlEscape(s.heading) + "</a>";
    }
    html += "</nav>\n";
  }
  html += "</header>\n<main>\n";
  for (const auto& s : sections_) {
    html += "<section id=\"" + s.id + "\"" +
            (s.css_class.empty() ? "" : " class=\"" + HtmlEscape(s.css_class) + "\"") +
            ">\n<h2>" + HtmlEscape(s.heading) + "</h2>\n" + s.html + "</section>\n";
  }
  html +=
      "</main>\n<footer>Written by femup; self-contained: styles and images are in "
      "this file.</footer>\n</body>\n</html>\n";
  return html;
}

}  // namespace femup
