#pragma once
/// @file
/// Text from outside crankcheck (a file's path, a scene's key, a program's output) as it is shown in messages and
/// reports: one line, nothing that acts on a terminal or reorders what is printed around it.
///
/// What is escaped, by every function here (docs/safety.md, "Text from outside"): C0 controls and DEL as \xHH (tab,
/// newline and carriage return as \t, \n, \r in escapeText); a byte that is not part of valid UTF-8 as \xHH; the
/// C1 controls (U+0080..U+009F, NEL among them), the line and paragraph separators U+2028 and U+2029, the
/// bidirectional controls (U+061C, U+200E, U+200F, U+202A..U+202E, U+2066..U+2069) and U+FEFF as \uHHHH. Every
/// other UTF-8 letter stays as it is.

#include <string>

namespace crankcheck {

/// `text` with every character listed above escaped, and backslash and double quote as \\ and \" (so that the
/// result can stand inside double quotes).
std::string escapeText(const std::string& text);

/// escapeText(text) in double quotes: a path or a program's output as a message quotes it.
std::string quoteText(const std::string& text);

/// `text` with every character listed above escaped, and backslash and double quote left as they are: a key or a
/// file name shown without quotes ("scene.toml: [engine].x\x00: unknown key").
std::string escapeControls(const std::string& text);

/// A message as one line, as every refusal is printed: its line breaks (\n, \r, U+0085, U+2028, U+2029) and the
/// indentation after them as "; " (as " " after a colon), every other character listed above escaped (a tab stays),
/// quotes and backslashes as they are. For an engine's exception (Simbody's spans several lines).
std::string formatOneLine(const std::string& message);

}  // namespace crankcheck
