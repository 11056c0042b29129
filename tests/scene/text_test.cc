// Text from outside as messages show it (scene/text.h): every character that could act on a terminal, cut a message
// or reorder what is printed around it is escaped, each by the byte sequence written out here by hand (the expected
// strings are the encodings of the code points, from the Unicode standard, not from the code under test).
#include "crankcheck/scene/text.h"

#include <gtest/gtest.h>

namespace crankcheck {
namespace {

TEST(Text, EscapeTextShowsEveryControlAsAnEscape) {
  using namespace std::string_literals;
  EXPECT_EQ(escapeText("plain text, UTF-8: \xc3\xa9\xe2\x82\xac"), "plain text, UTF-8: \xc3\xa9\xe2\x82\xac");  // é €
  EXPECT_EQ(escapeText("a\"b\\c"), "a\\\"b\\\\c");
  EXPECT_EQ(escapeText("1\n2\r3\t4"), "1\\n2\\r3\\t4");
  EXPECT_EQ(escapeText("a\0b"s), "a\\x00b");                                   // a NUL no longer cuts the message
  EXPECT_EQ(escapeText("\x1b[31mred"), "\\x1b[31mred");                        // ESC
  EXPECT_EQ(escapeText("\x7f"), "\\x7f");                                      // DEL
  EXPECT_EQ(escapeText("x\xc2\x85y"), "x\\u0085y");                            // NEL, a C1 control
  EXPECT_EQ(escapeText("\xc2\x9b" "2J"), "\\u009b2J");                         // CSI
  EXPECT_EQ(escapeText("a\xe2\x80\xa8" "b\xe2\x80\xa9"), "a\\u2028b\\u2029");  // line and paragraph separators
  EXPECT_EQ(escapeText("txt.\xe2\x80\xae" "exe"), "txt.\\u202eexe");           // RIGHT-TO-LEFT OVERRIDE
  EXPECT_EQ(escapeText("\xe2\x81\xa6x\xe2\x81\xa9"), "\\u2066x\\u2069");      // isolates
  EXPECT_EQ(escapeText("\xd8\x9c\xe2\x80\x8e\xe2\x80\x8f"), "\\u061c\\u200e\\u200f");
  EXPECT_EQ(escapeText("\xef\xbb\xbfk"), "\\ufeffk");                          // byte-order mark
  EXPECT_EQ(escapeText("\xff\xc0\xaf"), "\\xff\\xc0\\xaf");                    // not UTF-8; an overlong '/'
  EXPECT_EQ(escapeText("\xed\xa0\x80"), "\\xed\\xa0\\x80");                    // a surrogate
  EXPECT_EQ(escapeText("\xe2\x82"), "\\xe2\\x82");                             // cut short
  EXPECT_EQ(escapeText("\xf0\x9f\x98\x80"), "\xf0\x9f\x98\x80");               // U+1F600 stays
}

TEST(Text, QuoteTextAndEscapeControls) {
  EXPECT_EQ(quoteText("a\"b\n"), "\"a\\\"b\\n\"");
  EXPECT_EQ(escapeControls("[engine].\"k\"\n\xe2\x80\xae"), "[engine].\"k\"\\n\\u202e");  // quotes kept
}

TEST(Text, FormatOneLineJoinsEveryKindOfLineBreak) {
  EXPECT_EQ(formatOneLine("Error:\n   detail one\n   detail two\n"), "Error: detail one; detail two");
  EXPECT_EQ(formatOneLine("a\r\nb"), "a; b");
  EXPECT_EQ(formatOneLine("a\xc2\x85" "b\xe2\x80\xa8" "c\xe2\x80\xa9" "d"), "a; b; c; d");
  EXPECT_EQ(formatOneLine("tab\tkept, \"quotes\" and \\ too"), "tab\tkept, \"quotes\" and \\ too");
  EXPECT_EQ(formatOneLine("\x1b[2J and \xe2\x80\xae"), "\\x1b[2J and \\u202e");
}

}  // namespace
}  // namespace crankcheck
