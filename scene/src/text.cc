#include "crankcheck/scene/text.h"

#include <cctype>
#include <cstdint>
#include <cstdio>

namespace crankcheck {
namespace {

// One character of `text` at `i`: its code point and its length in bytes, or length 0 when the byte at `i` does not
// begin a valid UTF-8 sequence (shortest form, no surrogate, at most U+10FFFF).
struct Character {
  std::uint32_t code;
  size_t length;
};

Character readCharacter(const std::string& text, size_t i) {
  const auto u = static_cast<unsigned char>(text[i]);
  if (u < 0x80) return {u, 1};
  const size_t n = u >= 0xf0 && u <= 0xf4 ? 4 : u >= 0xe0 && u <= 0xef ? 3 : u >= 0xc2 && u <= 0xdf ? 2 : 0;
  if (n == 0 || i + n > text.size()) return {u, 0};
  std::uint32_t code = u & (n == 2 ? 0x1f : n == 3 ? 0x0f : 0x07);
  for (size_t k = 1; k < n; ++k) {
    const auto b = static_cast<unsigned char>(text[i + k]);
    if ((b & 0xc0) != 0x80) return {u, 0};
    code = code << 6 | (b & 0x3f);
  }
  const bool shortest = (n == 2 && code >= 0x80) || (n == 3 && code >= 0x800) || (n == 4 && code >= 0x10000);
  if (!shortest || (code >= 0xd800 && code <= 0xdfff) || code > 0x10ffff) return {u, 0};
  return {code, n};
}

bool isLineBreak(std::uint32_t code) {
  return code == '\n' || code == '\r' || code == 0x85 || code == 0x2028 || code == 0x2029;
}

// A character shown as \uHHHH: C1 controls, the separators, bidirectional controls, the byte-order mark.
bool isUnicodeControl(std::uint32_t code) {
  return (code >= 0x80 && code <= 0x9f) || code == 0x2028 || code == 0x2029 || code == 0x061c || code == 0x200e ||
         code == 0x200f || (code >= 0x202a && code <= 0x202e) || (code >= 0x2066 && code <= 0x2069) || code == 0xfeff;
}

void appendHex(std::string& out, const char* format, std::uint32_t value) {
  char buffer[12];
  std::snprintf(buffer, sizeof buffer, format, static_cast<unsigned>(value));
  out += buffer;
}

enum class Quotes { kEscaped, kKept };

// Appends the character at `i` to `out`, escaped as the header says, and returns its length (1 for an invalid byte).
size_t appendEscaped(std::string& out, const std::string& text, size_t i, Quotes quotes, bool named_escapes) {
  const Character c = readCharacter(text, i);
  if (c.length == 0) {
    appendHex(out, "\\x%02x", c.code);
    return 1;
  }
  if (c.length == 1) {
    const char ch = text[i];
    if ((ch == '"' || ch == '\\') && quotes == Quotes::kEscaped) {
      out += '\\';
      out += ch;
    } else if (named_escapes && ch == '\n') {
      out += "\\n";
    } else if (named_escapes && ch == '\r') {
      out += "\\r";
    } else if (named_escapes && ch == '\t') {
      out += "\\t";
    } else if (c.code < 0x20 || c.code == 0x7f) {
      appendHex(out, "\\x%02x", c.code);
    } else {
      out += ch;
    }
    return 1;
  }
  if (isUnicodeControl(c.code)) appendHex(out, "\\u%04x", c.code);
  else out.append(text, i, c.length);
  return c.length;
}

std::string escapeEvery(const std::string& text, Quotes quotes) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) i += appendEscaped(out, text, i, quotes, true);
  return out;
}

}  // namespace

std::string escapeText(const std::string& text) { return escapeEvery(text, Quotes::kEscaped); }

std::string quoteText(const std::string& text) {
  // Written by appends: `"\"" + escapeText(text) + "\""` draws GCC 12's false -Wrestrict at -O3.
  std::string out;
  out += '"';
  out += escapeText(text);
  out += '"';
  return out;
}

std::string escapeControls(const std::string& text) { return escapeEvery(text, Quotes::kKept); }

std::string formatOneLine(const std::string& message) {
  std::string out;
  for (size_t i = 0; i < message.size();) {
    const Character c = readCharacter(message, i);
    if (c.length == 0 || !isLineBreak(c.code)) {
      if (c.length == 1 && message[i] == '\t') {
        out += '\t';
        ++i;
      } else {
        i += appendEscaped(out, message, i, Quotes::kKept, false);
      }
      continue;
    }
    // A line break, and the white space after it (further breaks and the next line's indentation).
    i += c.length;
    while (i < message.size()) {
      const Character next = readCharacter(message, i);
      const bool space = next.length == 1 && std::isspace(static_cast<unsigned char>(message[i]));
      if (!space && !(next.length > 1 && isLineBreak(next.code))) break;
      i += next.length;
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
    if (!out.empty() && i < message.size()) out += out.back() == ':' ? " " : "; ";
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
  return out;
}

}  // namespace crankcheck
