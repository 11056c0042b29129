#pragma once
/// @file
/// A file's whole content, for the tests that read what the program under test wrote (declared once for all tests:
/// a test names it by `using testing::readFile;`).

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace crankcheck::testing {

/// Every byte of `path` ("" when it cannot be read: the test's expectations on it then fail).
inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace crankcheck::testing
