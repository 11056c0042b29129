// A report page shows text from outside (a scene's name: its file's stem) as written: cmark-gfm, the renderer the
// report uses, is the judge here. A name with Markdown in it makes no link, no emphasis, no HTML and no code span of
// its own, in a paragraph, a table cell, a caption or a heading; the report's own Markdown (bold verdicts, code spans,
// figure links) stays live.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "crankcheck/validation/report_document.h"

namespace crankcheck::validation {
namespace {

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// The HTML text of `name` as cmark-gfm writes text (its entities).
std::string asHtmlText(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

class ShownAsWrittenTest : public ::testing::TestWithParam<const char*> {};

TEST_P(ShownAsWrittenTest, EveryPlaceOfThePageShowsTheNameAsText) {
  const std::string name = GetParam();
  ReportDocument doc("t");
  doc.showAsWritten({name, "single_cylinder"});
  doc.addHeading(2, name);
  doc.addParagraph("The scene " + name + " passes; **FAIL** stays bold, `code` stays code: " +
                   formatCodeSpan("crankcheck stepped " + name + ".toml"));
  doc.addTable({"scene", "verdict"}, {{name, "**FAIL**"}, {name + " lambda=0.3", "pass"}});
  doc.addFigure("fig", "Panel \"" + name + "\": a caption");
  const std::string html = doc.toHtml();
  // Only the page's own links (the heading's in the contents, the figure's two and its CSV) and its own emphasis:
  // none made of the name.
  EXPECT_EQ(count(html, "<a href="), 4u) << html;
  EXPECT_EQ(count(html, "<strong>FAIL</strong>"), 2u) << html;
  EXPECT_EQ(count(html, "<em>"), 1u) << html;  // the figure's caption, *...*
  EXPECT_EQ(count(html, "<img"), 1u) << html;
  EXPECT_EQ(count(html, "<code>"), 2u) << html;  // `code` and the command
  // The name's text in the heading, the paragraph, both cells, the image's alt text and the caption, and once more
  // inside the command's code span.
  EXPECT_GE(count(html, asHtmlText(name)), 7u) << html;
  EXPECT_NE(html.find("<code>crankcheck stepped " + asHtmlText(name) + ".toml</code>"), std::string::npos) << html;
}

INSTANTIATE_TEST_SUITE_P(Names, ShownAsWrittenTest,
                         ::testing::Values("[x](javascript:alert(1))", "*em* and _em_", "a`b`c", "<b>bold</b>",
                                           "&amp; entity", "![img](x.png)", "__init__", "~~struck~~", "a\\*b",
                                           "www.example.com", "mail@example.com", "https://example.com/x"),
                         [](const auto& info) { return "name" + std::to_string(info.index); });

// An underscore inside a word is text to GitHub's Markdown and stays as it is; one that could open emphasis is escaped.
TEST(EscapeMarkdownTextTest, EscapesOnlyWhatCouldOpenMarkup) {
  EXPECT_EQ(escapeMarkdownText("v8_cross_plane"), "v8_cross_plane");
  EXPECT_EQ(escapeMarkdownText("_x_"), "\\_x\\_");
  EXPECT_EQ(escapeMarkdownText("[a](b)"), "\\[a\\](b)");
  EXPECT_EQ(escapeMarkdownText("two\nlines"), "two lines");
}

// A code span is delimited by a run of backticks longer than any inside it, padded where the text ends in one.
TEST(FormatCodeSpanTest, HoldsBackticksAsWritten) {
  EXPECT_EQ(formatCodeSpan("ls"), "`ls`");
  EXPECT_EQ(formatCodeSpan("a`b"), "``a`b``");
  EXPECT_EQ(formatCodeSpan("`a``"), "``` `a`` ```");
  ReportDocument doc("t");
  doc.addParagraph(formatCodeSpan("echo `date` ``x``"));
  EXPECT_NE(doc.toHtml().find("<code>echo `date` ``x``</code>"), std::string::npos) << doc.toHtml();
}

}  // namespace
}  // namespace crankcheck::validation
