// A self-contained HTML page: its styles and images are inline (no network,
// no file beside it needed), so a report can be mailed, archived or opened
// from any folder. The page is built from titled sections; a section with
// nothing in it is left out rather than shown empty.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace femup {

// Text made safe inside HTML elements and attribute values (& < > " ').
std::string HtmlEscape(std::string_view text);

// RFC 4648 base64 of `bytes` (OpenSSL's encoder), for data: URIs.
std::string Base64Encode(std::string_view bytes);

// True when `bytes` starts with the PNG signature.
bool LooksLikePng(std::string_view bytes);

struct HtmlTable {
  std::vector<std::string> header;             // plain text, escaped when rendered
  std::vector<std::vector<std::string>> rows;  // each as long as `header`
  std::vector<std::string> row_links;          // optional: an href per row, on cell 0
};

class HtmlPage {
 public:
  explicit HtmlPage(std::string title);

  // Facts shown as a list under the title (label, value), plain text.
  void AddFacts(const std::vector<std::pair<std::string, std::string>>& facts);
  // A section with a heading and an anchor `id` ([a-z0-9_-]); `inner_html` is
  // trusted HTML made with the helpers below. Not added when it is empty.
  // Throws std::invalid_argument on an id that is empty, malformed or taken.
  void AddSection(const std::string& id, const std::string& heading,
                  const std::string& inner_html, const std::string& css_class = "");
  bool HasSection(const std::string& id) const;

  // Helpers that make a section's HTML.
  static std::string Paragraph(std::string_view text);
  static std::string Preformatted(std::string_view text);
  // Throws std::invalid_argument when a row's length differs from the header's.
  static std::string Table(const HtmlTable& table);
  // A figure with the PNG inline as a data: URI; throws std::invalid_argument
  // when `png` is not a PNG.
  static std::string PngFigure(std::string_view png, const std::string& caption);
  // A collapsible block, open or closed at first.
  static std::string Details(const std::string& summary, const std::string& inner_html,
                             bool open);

  // The whole page: doctype, inline style, navigation, sections in order.
  std::string Render() const;

 private:
  struct Section {
    std::string id, heading, html, css_class;
  };
  std::string title_;
  std::vector<std::pair<std::string, std::string>> facts_;
  std::vector<Section> sections_;
};

}  // namespace femup
