#include "crankcheck/validation/errors.h"

#include <cstdio>

namespace crankcheck {

std::string quotePath(const std::filesystem::path& path) {
  std::string out = "\"";
  for (const char c : path.string()) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (u < 0x20 || u == 0x7f) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\x%02x", u);
      out += buffer;
    } else {
      out += c;  // printable ASCII and the bytes of UTF-8 letters
    }
  }
  return out + "\"";
}

}  // namespace crankcheck
