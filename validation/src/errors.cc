#include "crankcheck/validation/errors.h"

#include <cctype>
#include <cstdio>

namespace crankcheck {

std::string quotePath(const std::filesystem::path& path) { return quoteText(path.string()); }

std::string quoteText(const std::string& text) {
  std::string out = "\"";
  out += escapeText(text);
  return out += '"';
}

std::string escapeText(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  auto hex = [&out](unsigned char u) {
    char buffer[8];
    std::snprintf(buffer, sizeof buffer, "\\x%02x", u);
    out += buffer;
  };
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      hex(u);
    } else if (u >= 0x80) {
      // A UTF-8 sequence passes whole when it is valid (shortest form, no surrogate, at most U+10FFFF) and not a C1
      // control; otherwise its first byte is shown as \xHH and the next byte is looked at anew.
      const size_t n = u >= 0xf0 && u <= 0xf4 ? 4 : u >= 0xe0 && u <= 0xef ? 3 : u >= 0xc2 && u <= 0xdf ? 2 : 0;
      bool valid = n > 0 && i + n <= text.size();
      for (size_t k = 1; valid && k < n; ++k) valid = (static_cast<unsigned char>(text[i + k]) & 0xc0) == 0x80;
      if (valid) {
        const auto b1 = static_cast<unsigned char>(text[i + 1]);
        if (n == 2) valid = !(u == 0xc2 && b1 < 0xa0);          // U+0080..U+009F: C1 controls
        if (n == 3) valid = !(u == 0xe0 && b1 < 0xa0) && !(u == 0xed && b1 >= 0xa0);  // overlong; surrogates
        if (n == 4) valid = !(u == 0xf0 && b1 < 0x90) && !(u == 0xf4 && b1 >= 0x90);  // overlong; above U+10FFFF
      }
      if (!valid) {
        hex(u);
        ++i;
        continue;
      }
      out.append(text, i, n);
      i += n;
      continue;
    } else {
      out += c;  // printable ASCII
    }
    ++i;
  }
  return out;
}

std::string formatOneLine(const std::string& message) {
  std::string out;
  for (size_t i = 0; i < message.size(); ++i) {
    if (message[i] != '\n' && message[i] != '\r') {
      out += message[i];
      continue;
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    while (i + 1 < message.size() && std::isspace(static_cast<unsigned char>(message[i + 1]))) ++i;
    if (!out.empty() && i + 1 < message.size()) out += out.back() == ':' ? " " : "; ";
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace crankcheck
