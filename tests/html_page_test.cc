// HtmlPage: a self-contained page; escaping, base64 (RFC 4648's test vectors),
// inline PNG figures, tables, empty sections left out, bad ids refused.
#include "femup/reporting/html_page.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace femup {
namespace {

const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);

TEST(HtmlEscape, EscapesTheFiveSpecialCharacters) {
  EXPECT_EQ(HtmlEscape("a<b> & \"c\" 'd'"), "a&lt;b&gt; &amp; &quot;c&quot; &#39;d&#39;");
  EXPECT_EQ(HtmlEscape("plain text, 1.5 m"), "plain text, 1.5 m");
  EXPECT_EQ(HtmlEscape(""), "");
}

TEST(Base64Encode, MatchesTheRfc4648TestVectors) {
  EXPECT_EQ(Base64Encode(""), "");
  EXPECT_EQ(Base64Encode("f"), "Zg==");
  EXPECT_EQ(Base64Encode("fo"), "Zm8=");
  EXPECT_EQ(Base64Encode("foo"), "Zm9v");
  EXPECT_EQ(Base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64Encode("foobar"), "Zm9vYmFy");
}

TEST(Base64Encode, EncodesBinaryAndLongInputWithoutLineBreaks) {
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>(i);
  const std::string once = Base64Encode(bytes);
  EXPECT_EQ(once.substr(0, 8), "AAECAwQF");  // 00 01 02 03 04 05
  EXPECT_EQ(once.size(), 344u);              // 4 * ceil(256 / 3)
  // More than one of the encoder's internal chunks (3 MiB).
  std::string big(7 * 1024 * 1024, 'a');  // 3k + 1 bytes: one byte in the last group
  const std::string encoded = Base64Encode(big);
  EXPECT_EQ(encoded.size(), 4 * ((big.size() + 2) / 3));
  EXPECT_EQ(encoded.find('\n'), std::string::npos);
  bool groups_agree = true;  // "aaa" is "YWFh" in every whole group, across chunks
  for (std::size_t at = 0; at + 4 < encoded.size(); at += 4) {
    groups_agree = groups_agree && encoded.compare(at, 4, "YWFh") == 0;
  }
  EXPECT_TRUE(groups_agree);
  EXPECT_EQ(encoded.substr(encoded.size() - 4), "YQ==");  // the last 'a'
}

TEST(LooksLikePng, ChecksTheSignature) {
  EXPECT_TRUE(LooksLikePng(kPngSignature + "rest"));
  EXPECT_FALSE(LooksLikePng("GIF89a..."));
  EXPECT_FALSE(LooksLikePng(kPngSignature.substr(0, 7)));
}

TEST(HtmlPage, RendersTitleFactsAndSectionsInOrderWithNavigation) {
  HtmlPage page("femup run: a <study>");
  page.AddFacts({{"command", "femup run a.yaml"}});
  page.AddSection("summary", "Summary", HtmlPage::Preformatted("x = 1 & y < 2"));
  page.AddSection("files", "Files", HtmlPage::Paragraph("result.json"));
  const std::string html = page.Render();
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("<title>femup run: a &lt;study&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("<dt>command</dt><dd>femup run a.yaml</dd>"), std::string::npos);
  EXPECT_NE(html.find("<pre>x = 1 &amp; y &lt; 2</pre>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"#summary\">Summary</a>"), std::string::npos);
  EXPECT_LT(html.find("id=\"summary\""), html.find("id=\"files\""));
  EXPECT_NE(html.find("<style>"), std::string::npos);
  // Self-contained: nothing fetched from elsewhere.
  EXPECT_EQ(html.find("http"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
}

TEST(HtmlPage, LeavesOutAnEmptySection) {
  HtmlPage page("t");
  page.AddSection("plots", "Plots", "");
  page.AddSection("warnings", "Warnings", HtmlPage::Preformatted(" \n"));
  page.AddSection("summary", "Summary", HtmlPage::Paragraph("ok"));
  EXPECT_FALSE(page.HasSection("plots"));
  EXPECT_FALSE(page.HasSection("warnings"));
  EXPECT_TRUE(page.HasSection("summary"));
  const std::string html = page.Render();
  EXPECT_EQ(html.find("Plots"), std::string::npos);
  EXPECT_EQ(html.find("<nav>"), std::string::npos);  // one section: no navigation
}

TEST(HtmlPage, RefusesAMalformedOrRepeatedSectionId) {
  HtmlPage page("t");
  EXPECT_THROW(page.AddSection("", "Empty", "<p>x</p>"), std::invalid_argument);
  EXPECT_THROW(page.AddSection("Two words", "Bad", "<p>x</p>"), std::invalid_argument);
  page.AddSection("summary", "Summary", "<p>x</p>");
  EXPECT_THROW(page.AddSection("summary", "Again", "<p>y</p>"), std::invalid_argument);
}

TEST(HtmlPage, InlinesAPngAsADataUri) {
  const std::string png = kPngSignature + "IHDR";
  const std::string figure = HtmlPage::PngFigure(png, "factors & errors");
  EXPECT_NE(figure.find("src=\"data:image/png;base64," + Base64Encode(png) + "\""),
            std::string::npos);
  EXPECT_NE(figure.find("alt=\"factors &amp; errors\""), std::string::npos);
  EXPECT_NE(figure.find("<figcaption>factors &amp; errors</figcaption>"),
            std::string::npos);
  EXPECT_THROW(HtmlPage::PngFigure("not a png", "x"), std::invalid_argument);
}

TEST(HtmlPage, TablesEscapeCellsLinkRowsAndCheckRowLengths) {
  HtmlTable table{
      {"file", "size"}, {{"a<b>.json", "1 B"}, {"c.mtx", "2 B"}}, {"a.json", ""}};
  const std::string html = HtmlPage::Table(table);
  EXPECT_NE(html.find("<th>file</th><th>size</th>"), std::string::npos);
  EXPECT_NE(html.find("<td><a href=\"a.json\">a&lt;b&gt;.json</a></td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td>c.mtx</td>"), std::string::npos);  // no link given
  EXPECT_EQ(HtmlPage::Table({{"x"}, {}, {}}), "");            // no rows: nothing
  EXPECT_THROW(HtmlPage::Table({{"x", "y"}, {{"1"}}, {}}), std::invalid_argument);
  EXPECT_THROW(HtmlPage::Table({{"x"}, {{"1"}}, {"a", "b"}}), std::invalid_argument);
}

TEST(HtmlPage, DetailsAreOpenOrClosedAndEmptyWhenTheirContentIs) {
  EXPECT_EQ(HtmlPage::Details("s", "", true), "");
  EXPECT_EQ(HtmlPage::Details("a.yaml", "<pre>x</pre>", true).rfind("<details open>", 0),
            0u);
  EXPECT_EQ(HtmlPage::Details("a.yaml", "<pre>x</pre>", false).rfind("<details>", 0), 0u);
}

}  // namespace
}  // namespace femup
